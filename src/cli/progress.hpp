#pragma once
// A one-line progress indicator on stderr, shown only when stderr is a terminal and the output
// is for people (table format); in an embedded run (embedding.hpp), its progress callback.
#include <functional>
#include <string>

namespace bladestab::cli {

std::function<void(int, int)> progress_reporter(const std::string& label, bool enabled);

// Clears a progress line left standing (a run that ends before its progress completes), so that
// the line written next starts at the terminal's first column. Async-signal-safe (a lock-free
// atomic and write(2)): the stops that end the process from a signal handler or the deadline call it.
void clear_progress_line();

}  // namespace bladestab::cli
