#include "static_limits_output.hpp"

#include <utility>

#include <fmt/format.h>

namespace bladestab::cli {

RangeParameter speed_parameter() {
  return {true, [](double speed) { return fmt::format("{:.7g} rad/s", speed); }, "speed_rad_s"};
}

std::string limits_line(const PathWithinLimits& limits, const RangeParameter& parameter, const std::string& what) {
  const std::string where = describe_path_limits(limits, parameter.ascending, parameter.words);
  if (where.empty()) return where;
  const char* part = limits.before && limits.after ? "lies between them" : limits.before ? "starts there" : "stops there";
  return fmt::format("{}: the {} {}", where, what, part);
}

void write_static_limits(Json& json, const PathWithinLimits& limits, const RangeParameter& parameter,
                         const std::string& what, const PrintedDigits& digits) {
  // The limit before the range's first value is below it when the values ascend.
  const auto& below = parameter.ascending ? limits.before : limits.after;
  const auto& above = parameter.ascending ? limits.after : limits.before;
  Json& out = json["static_limits"];
  for (const auto& [name, limit] : {std::pair{"below", &below}, std::pair{"above", &above}}) {
    out[name] = *limit ? Json{{"kind", to_string((*limit)->kind)},
                              {"field", (*limit)->field},
                              {parameter.json_field, digits.relative((*limit)->where, 1e-12)}}
                       : Json(nullptr);
  }
  out["text"] = limits_line(limits, parameter, what);
}

}  // namespace bladestab::cli
