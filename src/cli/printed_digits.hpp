#pragma once
// The digits of the numbers in the JSON and CSV outputs (docs/outputs.md): a computed number is
// printed with the digits its error estimate supports, so that a file changes when an answer
// changes by more than its estimate, not with the last bits a BLAS kernel leaves.
//  - An error estimate (dimensionless: relative, or absolute on max|ρ|) is printed with 2
//    significant digits, rounded up, and at least finest_resolution.
//  - A result with an absolute error E is rounded to the decade of E (the unit of its last digit
//    is the largest power of ten ≤ E, so rounding moves it by at most E/2), E as printed; with a
//    relative estimate e, E = e·|value| and at least 3 significant digits.
//  - No result is printed finer than finest_resolution of itself.
//  - A check's measure of an error (a residual, an energy balance) gets 2 significant digits.
//  - A computed number without an estimate of its own gets 6 significant digits.
// Inputs and what is computed from them by arithmetic alone (grids, speeds in rpm, θ = kΩ) are
// printed in full. --digits full prints every number in full: the shortest text that reads back
// as the same double.
#include <string>
#include <vector>

namespace bladestab::cli {

// Below this fraction of a result, digits are rounding: the paper blade's results move by up to
// 5.4e-12 of themselves between OpenBLAS's Zen and Prescott kernels (the first mode near buckling;
// the maps' max|ρ| by up to 1.4e-5, under their 1e-3 tolerance), and a digit must lie far above
// that to stay the same in thousands of numbers (docs/outputs.md).
inline constexpr double finest_resolution = 1e-7;

enum class DigitsRule { estimate, full };

class PrintedDigits {
public:
  explicit PrintedDigits(DigitsRule rule = DigitsRule::estimate) : full_(rule == DigitsRule::full) {}

  double absolute(double value, double error) const;
  double relative(double value, double error) const;
  double estimate(double error) const;
  double measure(double error) const;
  double unestimated(double value) const;

  // Element by element: each value with its own error, or all with one.
  std::vector<double> relative(const std::vector<double>& values, const std::vector<double>& errors) const;
  std::vector<double> absolute(const std::vector<double>& values, const std::vector<double>& errors) const;
  std::vector<double> absolute(const std::vector<double>& values, double error) const;
  std::vector<double> estimate(const std::vector<double>& errors) const;
  std::vector<double> unestimated(const std::vector<double>& values) const;

private:
  bool full_;
};

// Significant digits worth printing for a value with relative error `error` (3 to 12).
int significant_digits(double error);

// `value` to `figures` significant digits, trailing zeros kept ("329.38710", "236", "3.39e+03"): as
// C's %#.*g but without its trailing point, and without the digit past them that fmt's '#' adds ("236.0").
std::string with_figures(double value, int figures);

// An error estimate as a table prints it: 2 significant digits, rounded up (docs/outputs.md rule 1,
// without the files' floor), "1.6e-02" for 0.015499.
std::string estimate_text(double error);

// A table's number to the significant digits its relative error supports (with_figures).
std::string to_significant_digits(double value, double relative_error);

// A table's number: in fixed point to the decade of its error, at most max_decimals of them, without
// a negative zero; from 1e6 on in exponent form with the significant digits the error supports.
std::string fixed_to_error(double value, double error, int max_decimals = 12);

}  // namespace bladestab::cli
