#pragma once
// The program's lines on stderr: "bladestab: KIND: MESSAGE", one line whatever the message holds
// (values are echoed short where they are put in, and this keeps any message that quotes input,
// CLI11's among them, on one line).
#include <string>

namespace bladestab::cli {

// kind "error" (bad input, exit 2), "failed" (exit 1) or "note" (the answer stands, exit 0).
void print_stderr_line(const char* kind, const std::string& message);

// A note beside an answer that stands but is not the whole of what was asked (boundaries: some did
// not converge; a tolerance the basis cannot reach).
// In an embedded run (embedding.hpp) it goes to the answer's notes.
void print_note(const std::string& message);

}  // namespace bladestab::cli
