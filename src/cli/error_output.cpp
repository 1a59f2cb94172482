#include "error_output.hpp"

#include <fmt/format.h>

namespace bladestab::cli {

void write_error_budget(Json& json, const ErrorBudget& b, const PrintedDigits& digits) {
  json["error_estimate"] = digits.estimate(b.total());
  Json& parts = json["error_budget"];
  parts["basis"] = digits.estimate(b.basis);
  parts["reduction"] = digits.estimate(b.reduction);
  parts["load"] = digits.estimate(b.load);
  parts["method"] = digits.estimate(b.method);
  parts["unbounded"] = b.unbounded;
}

std::string describe_error_budget(const ErrorBudget& b) {
  std::string text = fmt::format("{} (basis {}, reduction {}, load {}, method {})", estimate_text(b.total()),
                                 estimate_text(b.basis), estimate_text(b.reduction), estimate_text(b.load),
                                 estimate_text(b.method));
  for (std::size_t k = 0; k < b.unbounded.size(); ++k) text += (k == 0 ? "; not bounded: " : ", ") + b.unbounded[k];
  return text;
}

}  // namespace bladestab::cli
