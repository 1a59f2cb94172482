#include "finite_results.hpp"

#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"

namespace bladestab::cli {

const FiniteResults& FiniteResults::require(const std::string& quantity, double value) const {
  if (!std::isfinite(value)) {
    throw NumericalError(fmt::format("{}: the {} came out {}, not a number that can be reported; the scene's values "
                                     "are at the edge of what the model resolves",
                                     what_, quantity, value));
  }
  return *this;
}

}  // namespace bladestab::cli
