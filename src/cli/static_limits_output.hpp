#pragma once
// Where a range of operating points (a Campbell diagram's speeds, a sweep's values, a check's
// speed range) meets the blade's static limits (static_limits.hpp), as every format shows it: one
// line for the table and a "static_limits" object in the JSON.
#include <functional>
#include <string>

#include "bladestab/blade/static_limits.hpp"
#include "json_output.hpp"
#include "printed_digits.hpp"

namespace bladestab::cli {

// The parameter of the range: its values ascending or not, how a value reads in a sentence
// ("212.4 rad/s", "blade.length = 3.5"), and the JSON field of a limit's value.
struct RangeParameter {
  bool ascending = true;
  std::function<std::string(double)> words;
  const char* json_field = "speed_rad_s";
};

// The speeds of a diagram or a check, ascending, in rad/s.
RangeParameter speed_parameter();

// "the blade buckles under its static tip compression below 212.4 rad/s: the diagram starts
// there", with `what` the output ("diagram", "sweep"); empty when the range meets no limit.
std::string limits_line(const PathWithinLimits& limits, const RangeParameter& parameter, const std::string& what);

// "static_limits": {"below": {"kind", "field", <json_field>} or null, "above": …, "text": the line};
// where a limit lies is found to 1e-12 relative and printed to that estimate (`digits`).
void write_static_limits(Json& json, const PathWithinLimits& limits, const RangeParameter& parameter,
                         const std::string& what, const PrintedDigits& digits);

}  // namespace bladestab::cli
