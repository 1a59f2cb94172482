#include "bladestab/ltp/step_doubling.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace bladestab {

StepDoubling::StepDoubling(int first, int last, int safe) : first_(first), last_(last), safe_(safe) {
  if (first < 1 || last < first) {
    throw std::invalid_argument(fmt::format("StepDoubling: the ladder {}..{} is empty", first, last));
  }
}

int StepDoubling::levels() const {
  int levels = 0;
  for (long long steps = first_; steps <= last_; steps *= 2) ++levels;
  return levels;
}

std::optional<double> StepDoubling::judge(int steps, double distance, double allowed, double floor) {
  const std::optional<double> before = previous_distance_;
  previous_distance_ = distance;
  const double ratio = before ? *before / distance : 0;
  double error = std::numeric_limits<double>::infinity();
  if (ratio >= 16 && ratio <= 256) {
    error = distance / 15;
  } else if ((ratio >= 4 && ratio < 16) || (before && *before <= allowed) || steps >= safe_) {
    error = distance;
  }
  error = std::max(error, floor);
  if (error <= allowed) return error;  // false for NaN
  return std::nullopt;
}

void StepDoubling::start() { previous_distance_.reset(); }

bool StepDoubling::overflowed(int steps) {
  start();
  const bool growth = last_overflow_ == steps / 2 && last_overflow_ >= safe_;
  last_overflow_ = steps;
  return growth;
}

}  // namespace bladestab
