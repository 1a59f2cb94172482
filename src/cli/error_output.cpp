#include "error_output.hpp"

#include <fmt/format.h>

namespace bladestab::cli {

void write_error_budget(JsonWriter& json, const ErrorBudget& b) {
  json.value("error_estimate", b.total())
      .begin_object("error_budget")
      .value("basis", b.basis)
      .value("reduction", b.reduction)
      .value("load", b.load)
      .value("method", b.method)
      .begin_array("unbounded");
  for (const std::string& part : b.unbounded) json.value(nullptr, part);
  json.end_array().end_object();
}

std::string describe_error_budget(const ErrorBudget& b) {
  std::string text = fmt::format("{:.1e} (basis {:.1e}, reduction {:.1e}, load {:.1e}, method {:.1e})", b.total(),
                                 b.basis, b.reduction, b.load, b.method);
  for (std::size_t k = 0; k < b.unbounded.size(); ++k) text += (k == 0 ? "; not bounded: " : ", ") + b.unbounded[k];
  return text;
}

}  // namespace bladestab::cli
