#pragma once
// A one-line progress indicator on stderr, shown only when stderr is a terminal and the output
// is for people (table format); in an embedded run (embedding.hpp), its progress callback.
#include <functional>
#include <string>

namespace bladestab::cli {

std::function<void(int, int)> progress_reporter(const std::string& label, bool enabled);

// Clears a progress line left standing (a run that ends before its progress completes), so that
// the line written next starts at the terminal's first column.
void clear_progress_line();

// The width of the progress line standing on the terminal, 0 for none; async-signal-safe (a
// lock-free atomic), for the stops that end the process from a signal handler or the deadline.
int progress_line_width();

}  // namespace bladestab::cli
