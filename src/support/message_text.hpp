#pragma once
// What a user typed, as it goes into a one-line message. Errors echo the offending value; a value
// may hold newlines, escapes or a million list elements, and the message must stay one short line.
#include <cstddef>
#include <string>
#include <string_view>

namespace bladestab {

// Control characters written as escapes (\n, \t, \r, \xHH): the text cannot break the line.
std::string one_line(std::string_view text);

// one_line(value), cut after `max_chars` bytes (on a UTF-8 character boundary) with
// "… (N bytes)"; quoted in '…' when empty or when it has spaces at either end, which would
// otherwise not be seen.
std::string echoed(std::string_view value, std::size_t max_chars = 60);

}  // namespace bladestab
