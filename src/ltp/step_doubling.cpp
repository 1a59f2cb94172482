#include "bladestab/ltp/step_doubling.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"

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

int affordable_last_level(int first, int last, double step_flops, double max_flops) {
  int affordable = 0;
  for (long long steps = 2LL * first; steps <= last && (2.0 * steps - first) * step_flops <= max_flops; steps *= 2) {
    affordable = static_cast<int>(steps);
  }
  return affordable;
}

void throw_unconverged(const std::string& what, int last, int limit, const std::string& unit) {
  if (last == 0) {
    throw WorkLimitError(fmt::format("{}: the work limit affords fewer than the two levels a judgement needs", what));
  }
  if (last < limit) {
    throw WorkLimitError(fmt::format("{} within {} {}, all that the work limit affords", what, last, unit));
  }
  throw NumericalError(fmt::format("{} within {} {}", what, last, unit));
}

}  // namespace bladestab
