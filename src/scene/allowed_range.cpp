#include "bladestab/scene/allowed_range.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

namespace bladestab {

bool AllowedRange::contains(double x) const {
  const bool above_lo = lo_open ? x > lo : x >= lo;
  const bool below_hi = hi_open ? x < hi : x <= hi;
  return above_lo && below_hi;
}

std::string AllowedRange::text() const {
  return fmt::format("{}{}, {}{}", lo_open ? '(' : '[', limit_text(lo), limit_text(hi), hi_open ? ')' : ']');
}

std::string limit_text(double x) {
  // The shortest round-trip form, or where that has an exponent or the exponent form is clearly
  // shorter, the exponent form without its '+' and leading zeros: 1e5, 1e13 and 1e-6 rather than
  // 100000, 10000000000000 and 1e-06, but 1000 and 0.001.
  const std::string plain = fmt::format("{}", x);
  for (int digits = 0; digits <= 16; ++digits) {
    std::string exponential = fmt::format("{:.{}e}", x, digits);
    if (std::stod(exponential) != x) continue;
    const auto e = exponential.find('e');
    std::string exponent = exponential.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, 1);  // the sign
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    exponential = exponential.substr(0, e + 1) + (negative ? "-" : "") + exponent;
    const bool plain_has_exponent = plain.find('e') != std::string::npos;
    return plain_has_exponent || exponential.size() + 2 <= plain.size() ? exponential : plain;
  }
  return plain;
}

std::string distinct_integers_rule(long lo, long hi) {
  return fmt::format("must be a non-empty list of distinct integers, each in [{}, {}]", lo, hi);
}

std::string distinct_numbers_rule(const AllowedRange& allowed) {
  return "must be a non-empty list of distinct numbers, each in " + allowed.text();
}

std::optional<double> first_repeat(const std::vector<double>& values) {
  for (auto it = values.begin(); it != values.end(); ++it) {
    if (std::find(values.begin(), it, *it) != it) return *it;
  }
  return std::nullopt;
}

}  // namespace bladestab
