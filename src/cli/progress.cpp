#include "progress.hpp"

#include <atomic>
#include <cstdio>
#include <unistd.h>

#include "embedding.hpp"

namespace bladestab::cli {
namespace {

// The width of the progress line standing on the terminal (0: none): a line that ends the run
// early (an error, a stop) is written over it, not after it.
std::atomic<int> open_width{0};

}  // namespace

int progress_line_width() { return open_width.load(); }

void clear_progress_line() {
  if (const int width = open_width.exchange(0); width > 0) std::fprintf(stderr, "\r%*s\r", width, "");
}

std::function<void(int, int)> progress_reporter(const std::string& label, bool enabled) {
  if (const EmbeddedRun* run = embedded_run(); run != nullptr) {
    if (!run->progress) return {};
    return [progress = run->progress, label](int done, int total) { progress(label, done, total); };
  }
  if (!enabled || isatty(fileno(stderr)) == 0) return {};
  return [label](int done, int total) {
    open_width = static_cast<int>(label.size()) + 24;  // before the line: a stop may come as it is written
    std::fprintf(stderr, "\r%s %d/%d (%3d%%)", label.c_str(), done, total, total ? 100 * done / total : 100);
    if (done == total) clear_progress_line();
    std::fflush(stderr);
  };
}

}  // namespace bladestab::cli
