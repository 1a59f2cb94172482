#include "support/message_text.hpp"

#include <fmt/format.h>

namespace bladestab {

std::string one_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    switch (c) {
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (byte < 0x20 || byte == 0x7f) {
          out += fmt::format("\\x{:02x}", byte);
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string echoed(std::string_view value, std::size_t max_chars) {
  std::string shown;
  if (value.size() <= max_chars) {
    shown = one_line(value);
  } else {
    std::size_t cut = max_chars;
    // Back to the first byte of a UTF-8 character (continuation bytes are 10xxxxxx).
    while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xC0) == 0x80) --cut;
    shown = fmt::format("{}… ({} bytes)", one_line(value.substr(0, cut)), value.size());
  }
  const bool hidden_edges = value.empty() || value.front() == ' ' || value.back() == ' ';
  return hidden_edges ? "'" + shown + "'" : shown;
}

}  // namespace bladestab
