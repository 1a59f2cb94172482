#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

#include "embedding.hpp"

namespace bladestab::cli {

std::function<void(int, int)> progress_reporter(const std::string& label, bool enabled) {
  if (const EmbeddedRun* run = embedded_run(); run != nullptr) {
    if (!run->progress) return {};
    return [progress = run->progress, label](int done, int total) { progress(label, done, total); };
  }
  if (!enabled || isatty(fileno(stderr)) == 0) return {};
  return [label](int done, int total) {
    std::fprintf(stderr, "\r%s %d/%d (%3d%%)", label.c_str(), done, total, total ? 100 * done / total : 100);
    if (done == total) std::fprintf(stderr, "\r%*s\r", static_cast<int>(label.size()) + 24, "");
    std::fflush(stderr);
  };
}

}  // namespace bladestab::cli
