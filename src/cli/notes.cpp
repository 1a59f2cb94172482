#include "notes.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "support/message_text.hpp"
#include "embedding.hpp"
#include "progress.hpp"

namespace bladestab::cli {

void print_stderr_line(const char* kind, const std::string& message) {
  constexpr std::size_t longest = 2000;
  std::string line = one_line(message);
  if (line.size() > longest) line = line.substr(0, longest) + "…";
  // fwrite, its failure ignored: a stderr that cannot take the line (a full disk, a file-size
  // limit) has nowhere to report that, and fmt::print would throw from the run's last handler.
  const std::string text = fmt::format("bladestab: {}: {}\n", kind, line);
  clear_progress_line();
  std::fwrite(text.data(), 1, text.size(), stderr);
}

void print_note(const std::string& message) {
  if (EmbeddedAnswer* answer = embedded_answer(); answer != nullptr) {
    answer->notes.push_back(one_line(message));
  } else {
    print_stderr_line("note", message);
  }
}

}  // namespace bladestab::cli
