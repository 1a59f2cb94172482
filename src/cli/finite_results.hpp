#pragma once
// A result is printed only when every number of it is finite: a NaN or an infinity is a failure of
// the computation (NumericalError, exit 1) naming the quantity, never output (a Young's modulus of
// 1e-308 would otherwise print "Λ = nan"). The commands whose outputs always pass through
// json_text() (which refuses them too, json_output.hpp) need no more than that.
#include <string>

namespace bladestab::cli {

class FiniteResults {
public:
  // `what` names the result in the message, e.g. "modes".
  explicit FiniteResults(std::string what) : what_(std::move(what)) {}
  // Throws NumericalError "modes: frequency of mode 3 is nan; …" unless `value` is finite.
  const FiniteResults& require(const std::string& quantity, double value) const;

private:
  std::string what_;
};

}  // namespace bladestab::cli
