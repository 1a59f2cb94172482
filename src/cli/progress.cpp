#include "progress.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <unistd.h>

#include "embedding.hpp"

namespace bladestab::cli {
namespace {

// The width of the progress line standing on the terminal (0: none): a line that ends the run
// early (an error, a stop) is written over it, not after it.
std::atomic<int> open_width{0};

}  // namespace

void clear_progress_line() {
  char blank[256];
  const int width = std::min(open_width.exchange(0), static_cast<int>(sizeof blank) - 2);
  if (width <= 0) return;
  blank[0] = '\r';
  std::memset(blank + 1, ' ', static_cast<std::size_t>(width));
  blank[width + 1] = '\r';
  // write, not stdio: a signal handler and the deadline's thread call this too. Its failure is
  // ignored, as the line that follows it ignores its own.
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, blank, static_cast<std::size_t>(width) + 2);
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
