#include "printed_digits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <fmt/format.h>

namespace bladestab::cli {
namespace {

// The powers of ten that are doubles exactly, 10⁰ … 10²².
constexpr double exact_powers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                   1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// The decade of x > 0: the exponent of the largest power of ten ≤ x. Its logarithm decides away
// from a power of ten; within 1e-12 of one (in the logarithm) its 17 digits do, as they would
// everywhere (a history's samples: 10⁵ values a second faster).
int decade(double x) {
  const double l = std::log10(x), floor = std::floor(l);
  if (std::isfinite(l) && l - floor > 1e-12 && floor + 1 - l > 1e-12) return static_cast<int>(floor);
  const std::string text = fmt::format("{:.16e}", x);
  return std::atoi(text.c_str() + text.find('e') + 1);
}

// The double nearest `units`·10^k, which prints back as that decimal: where units and 10^|k| are
// doubles exactly, one correctly rounded product or quotient is it (Clinger's fast path), else strtod.
double decimal(long units, int k) {
  if (std::labs(units) < (1L << 53) && k >= 0 && k <= 22) return static_cast<double>(units) * exact_powers[k];
  if (std::labs(units) < (1L << 53) && k < 0 && k >= -22) return static_cast<double>(units) / exact_powers[-k];
  return std::strtod(fmt::format("{}e{}", units, k).c_str(), nullptr);
}

// `value` rounded to `digits` significant digits. Up to 12 digits `value` is scaled to them by
// one correctly rounded product (an error below 1e-4 of a unit) and rounded to the nearest
// integer, except within 1e-3 of a tie, which its decimal expansion decides.
double significant(double value, int digits) {
  if (value != 0 && std::isfinite(value) && digits <= 12) {
    const int shift = digits - 1 - decade(std::abs(value));
    if (shift >= -22 && shift <= 22) {
      const double scaled = shift >= 0 ? value * exact_powers[shift] : value / exact_powers[-shift];
      if (std::abs(scaled - std::floor(scaled) - 0.5) > 1e-3) return decimal(std::lround(scaled), -shift);
    }
  }
  return std::strtod(fmt::format("{:.{}e}", value, digits - 1).c_str(), nullptr);
}

bool usable(double x) { return std::isfinite(x) && x > 0; }

// f(value, index) of every value.
template <class F>
std::vector<double> each(const std::vector<double>& values, F f) {
  std::vector<double> out(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) out[k] = f(values[k], k);
  return out;
}

}  // namespace

double PrintedDigits::absolute(double value, double error) const {
  if (full_ || !std::isfinite(value) || !usable(error)) return value;
  if (value == 0) return 0.0;  // never −0
  const int last = decade(std::max(measure(error), finest_resolution * std::abs(value)));
  const int first = decade(std::abs(value));
  if (first < last) {  // below its error: 0 or ±1 unit of the error's decade
    const long units = std::lround(value / decimal(1, last));
    return units == 0 ? 0.0 : decimal(units, last);
  }
  return significant(value, first - last + 1);
}

double PrintedDigits::relative(double value, double error) const {
  if (full_ || !std::isfinite(value) || !usable(error)) return value;
  if (value == 0) return 0.0;
  const int first = decade(std::abs(value));
  const int last = std::min(decade(estimate(error) * std::abs(value)), first - 2);
  return significant(value, first - last + 1);
}

double PrintedDigits::estimate(double error) const {
  if (full_ || !usable(error)) return error;
  return std::max(measure(error), finest_resolution);
}

double PrintedDigits::measure(double error) const {
  if (error < 0) return -measure(-error);
  if (full_ || !usable(error)) return error;
  const int second = decade(error) - 1;  // the decade of its second digit
  const long units = std::lround(error / decimal(1, second));
  const double shown = decimal(units, second);
  return shown < error ? decimal(units + 1, second) : shown;
}

double PrintedDigits::unestimated(double value) const {
  if (full_ || !std::isfinite(value)) return value;
  return value == 0 ? 0.0 : significant(value, 6);
}

std::vector<double> PrintedDigits::relative(const std::vector<double>& values, const std::vector<double>& errors) const {
  return each(values, [&](double v, std::size_t k) { return relative(v, errors.at(k)); });
}

std::vector<double> PrintedDigits::absolute(const std::vector<double>& values, const std::vector<double>& errors) const {
  return each(values, [&](double v, std::size_t k) { return absolute(v, errors.at(k)); });
}

std::vector<double> PrintedDigits::absolute(const std::vector<double>& values, double error) const {
  return each(values, [&](double v, std::size_t) { return absolute(v, error); });
}

std::vector<double> PrintedDigits::estimate(const std::vector<double>& errors) const {
  return each(errors, [&](double e, std::size_t) { return estimate(e); });
}

std::vector<double> PrintedDigits::unestimated(const std::vector<double>& values) const {
  return each(values, [&](double v, std::size_t) { return unestimated(v); });
}

int significant_digits(double error) {
  return std::clamp(static_cast<int>(std::floor(-std::log10(std::max(error, 1e-15)))) + 1, 3, 12);
}

std::string with_figures(double value, int figures) {
  if (!std::isfinite(value) || value == 0) return fmt::format("{:.{}g}", value, figures);
  // The decimal exponent after rounding to `figures` digits (9.996 to 3 figures is 1.00e+01).
  const std::string scientific = fmt::format("{:.{}e}", value, figures - 1);
  const int exponent = std::stoi(scientific.substr(scientific.find('e') + 1));
  if (exponent < -4 || exponent >= figures) return scientific;  // where %g takes the exponent form
  return fmt::format("{:.{}f}", value, figures - 1 - exponent);
}

std::string estimate_text(double error) { return fmt::format("{:.1e}", PrintedDigits().measure(error)); }

std::string to_significant_digits(double value, double relative_error) {
  return with_figures(value, significant_digits(relative_error));
}

std::string fixed_to_error(double value, double error, int max_decimals) {
  if (std::abs(value) >= 1e6) return fmt::format("{:.{}e}", value, significant_digits(error / std::abs(value)) - 1);
  const int decimals =
      std::clamp(static_cast<int>(-std::floor(std::log10(std::max(error, 1e-300)))), 0, max_decimals);
  const double unit = std::pow(10.0, -decimals);
  return fmt::format("{:.{}f}", std::abs(value) < 0.5 * unit ? 0.0 : value, decimals);
}

}  // namespace bladestab::cli
