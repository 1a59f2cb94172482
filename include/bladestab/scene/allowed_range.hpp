#pragma once
// An interval of allowed values and how messages state it. Scene keys and command-line options
// check their numbers with it, so a limit reads the same wherever the same quantity is given.
#include <optional>
#include <string>
#include <vector>

namespace bladestab {

struct AllowedRange {
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;

  static AllowedRange closed(double lo, double hi) { return {lo, hi, false, false}; }
  static AllowedRange open(double lo, double hi) { return {lo, hi, true, true}; }
  static AllowedRange above(double lo, double hi) { return {lo, hi, true, false}; }  // (lo, hi]
  static AllowedRange below(double lo, double hi) { return {lo, hi, false, true}; }  // [lo, hi)

  bool contains(double x) const;  // false for NaN
  std::string text() const;       // "[100000, 1e13]", "(0, 1]"
};

// A limit as messages print it: the shortest form that reads back as the same double (1e+13 →
// "1e13", 0.5 → "0.5").
std::string limit_text(double x);

// A list that names a set (engine orders, the loads to compare): not empty, each value once, each
// value allowed. How messages state it — "must be a non-empty list of distinct integers, each in
// [1, 1000]" — and its test. Scene keys and command-line lists check their lists with these, so a
// list is refused alike wherever it is given.
std::string distinct_integers_rule(long lo, long hi);
std::string distinct_numbers_rule(const AllowedRange& allowed);
// The first value that repeats an earlier one, if any.
std::optional<double> first_repeat(const std::vector<double>& values);

}  // namespace bladestab
