#include "bladestab/ltp/step_doubling.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"

namespace bladestab {

StepDoubling::StepDoubling(int first, int last, int safe, double step_work, double max_work)
    : first_(first), safe_(safe), most_(last) {
  if (first < 1) throw std::invalid_argument(fmt::format("StepDoubling: the first level {} has no steps", first));
  for (long long steps = first; steps <= last; steps *= 2) {
    if ((2.0 * steps - first) * step_work > max_work) {
      work_limited_ = true;
      break;
    }
    last_ = static_cast<int>(steps);
  }
  if (work_limited_ && last_ < 2LL * first) last_ = 0;
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

void StepDoubling::give_up(const std::string& what, const std::string& unit) const {
  if (work_limited_ && last_ == 0) {
    throw WorkLimitError(fmt::format("{}: the work limit affords fewer than the two levels a judgement needs", what));
  }
  if (work_limited_) throw WorkLimitError(fmt::format("{} within {} {}, all that the work limit affords", what, last_, unit));
  if (last_ == 0) throw NumericalError(fmt::format("{}: its first level, {} {}, is past the most, {}", what, first_, unit, most_));
  throw NumericalError(fmt::format("{} within {} {}", what, last_, unit));
}

}  // namespace bladestab
