#pragma once
// A one-line progress indicator on stderr, shown only when stderr is a terminal and the output
// is for people (table format); in an embedded run (embedding.hpp), its progress callback.
#include <functional>
#include <string>

namespace bladestab::cli {

std::function<void(int, int)> progress_reporter(const std::string& label, bool enabled);

}  // namespace bladestab::cli
