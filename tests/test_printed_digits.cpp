// The digits of the JSON and CSV outputs (src/cli/printed_digits.hpp, docs/outputs.md): values
// rounded to the decade of their error, worked by hand; a BLAS-level change of a value leaves its
// printed text alone; the rounding never moves a value by more than half its error; and the
// documents' text (src/cli/json_output.hpp) prints the rounded doubles as the short decimals they
// were rounded to.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "cli/json_output.hpp"
#include "cli/printed_digits.hpp"

using bladestab::cli::estimate_text;
using bladestab::cli::DigitsRule;
using bladestab::cli::Json;
using bladestab::cli::PrintedDigits;

namespace {

std::string text(double v) { return fmt::format("{}", v); }

}  // namespace

TEST_CASE("printed digits: a value to the decade of its error, worked by hand", "[printed_digits]") {
  const PrintedDigits digits;
  // 68.0354375847 Hz ± 3.2e-7 relative: E = 2.18e-5, printed 2.2e-5, its decade 1e-5.
  CHECK(text(digits.relative(68.03543758474244, 3.2e-7)) == "68.03544");
  // The same frequency from another BLAS kernel (measured: Prescott against Zen, 7.5e-14 apart).
  CHECK(text(digits.relative(68.03543758473735, 3.2e-7)) == "68.03544");
  // max|ρ| = 2.199229657 ± 1e-7 absolute: to 1e-7.
  CHECK(text(digits.absolute(2.1992296566, 1e-7)) == "2.1992297");
  // An undamped multiplier on the unit circle, to the map's tolerance 1e-3: 1 (not 1.0000000000008).
  CHECK(text(digits.relative(1.0000000000007996, 1e-3)) == "1");
  // Below its error: 0 or one unit of the error's decade, never rounding noise.
  CHECK(digits.absolute(-3.3e-17, 1e-7) == 0);
  CHECK(text(digits.absolute(7e-4, 1e-3)) == "0.001");
  CHECK(digits.absolute(4e-4, 1e-3) == 0);
  // A relative estimate keeps 3 significant digits however large it is.
  CHECK(text(digits.relative(1234.5678, 0.5)) == "1230");
  CHECK(text(digits.relative(-0.0123456, 2.0)) == "-0.0123");
  // An estimate: 2 digits, rounded away from zero.
  CHECK(text(digits.estimate(2.1e-4 * (1 + 1e-12))) == "0.00022");
  CHECK(text(digits.estimate(2.19e-4)) == "0.00022");
  CHECK(text(digits.estimate(1e-3)) == "0.001");
  CHECK(text(digits.estimate(9.96e-4)) == "0.001");
  CHECK(digits.estimate(0) == 0);
  // ... and no finer than finest_resolution (1e-7): below it, digits are rounding that BLAS kernels
  // do differently. A frequency's 2.9e-12 (its eigensolver's rounding) prints as 1e-7, and the
  // frequency with 8 digits.
  CHECK(text(digits.estimate(2.9e-12)) == "1e-07");
  CHECK(text(digits.relative(68.03543758474244, 2.9e-12)) == "68.035438");
  CHECK(text(digits.absolute(68.03543758474244, 1e-12)) == "68.035438");
  // A check's measure of an error: 2 digits away from zero, no floor (it measures the rounding).
  CHECK(text(digits.measure(-3.41e-13)) == "-3.5e-13");
  // Without an estimate: 6 significant digits.
  CHECK(text(digits.unestimated(0.123456789)) == "0.123457");
  // NaN ("no value") passes through, to be written as null.
  CHECK(std::isnan(digits.relative(std::numeric_limits<double>::quiet_NaN(), 1e-3)));
  // --digits full: every double as it is.
  const PrintedDigits full(DigitsRule::full);
  CHECK(full.relative(68.03543758474244, 3.2e-7) == 68.03543758474244);
  CHECK(full.estimate(2.1e-4 * (1 + 1e-12)) == 2.1e-4 * (1 + 1e-12));
}

TEST_CASE("printed digits: the rounding moves a value by at most half its error", "[printed_digits]") {
  const PrintedDigits digits;
  std::mt19937_64 random(20240523);
  std::uniform_real_distribution<double> mantissa(1, 10);
  std::uniform_int_distribution<int> exponent(-12, 6), relative_exponent(-12, -1);
  for (int n = 0; n < 20000; ++n) {
    const double value = (n % 2 ? -1 : 1) * mantissa(random) * std::pow(10.0, exponent(random));
    const double error = mantissa(random) * std::pow(10.0, relative_exponent(random));
    const double absolute = digits.absolute(value, error * std::abs(value));
    const double relative = digits.relative(value, error);
    INFO("value " << text(value) << ", relative error " << text(error));
    // The unit of the last digit is at most the printed error, or finest_resolution of the value:
    // the rounding is at most half of it.
    const double finest = bladestab::cli::finest_resolution * std::abs(value);
    CHECK(std::abs(absolute - value) <= 0.5 * std::max(digits.measure(error * std::abs(value)), finest) * (1 + 1e-9));
    CHECK(std::abs(relative - value) <= 0.5 * digits.estimate(error) * std::abs(value) * (1 + 1e-9));
  }
}

TEST_CASE("JSON documents: lists of numbers on one line, two-space indentation, no NaN", "[printed_digits]") {
  Json document;
  document["title"] = "map — \"θ\"";
  document["x"] = std::vector<double>{100, 136.5};
  document["max"] = bladestab::cli::numbers_or_null({1.5, std::numeric_limits<double>::quiet_NaN()});
  document["names"] = std::vector<std::string>{"a"};
  document["empty"] = Json::array();
  document["point"] = {{"y", 0.25}, {"label", nullptr}};
  // The decimal a value was rounded to, as the CSV files print it (fmt): nlohmann's own shortest
  // form gives 75.00712300000001 for this one.
  document["f"] = 75.007123;
  CHECK(bladestab::cli::json_text(document) ==
        "{\n"
        "  \"title\": \"map — \\\"θ\\\"\",\n"
        "  \"x\": [100, 136.5],\n"
        "  \"max\": [1.5, null],\n"
        "  \"names\": [\n"
        "    \"a\"\n"
        "  ],\n"
        "  \"empty\": [],\n"
        "  \"point\": {\n"
        "    \"y\": 0.25,\n"
        "    \"label\": null\n"
        "  },\n"
        "  \"f\": 75.007123\n"
        "}\n");
  // JSON has no NaN: an unflagged one is a bug upstream, refused rather than printed as null.
  document["point"]["y"] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(bladestab::cli::json_text(document), std::logic_error);
}

TEST_CASE("a table's error estimate: 2 digits rounded up, never less than was estimated", "[printed_digits]") {
  // The largest relative error of the paper blade's 12 modes, 0.015499 (JSON 0.016), and a Campbell
  // diagram's 9.433e-7 (JSON 9.5e-7): "1.5e-02" and "9.4e-07" had stated less.
  CHECK(estimate_text(0.015499) == "1.6e-02");
  CHECK(estimate_text(9.433e-7) == "9.5e-07");
  CHECK(estimate_text(2.5e-12) == "2.5e-12");  // exact: no floor in a table
  CHECK(estimate_text(0) == "0.0e+00");
}

TEST_CASE("a table's number shows exactly the significant digits asked for, as C's %#g without its point",
          "[digits]") {
  using bladestab::cli::with_figures;
  // Worked by hand: 236.3787 to 3 figures is 236 (fmt's '#' gives "236.0", a fourth digit that is wrong).
  CHECK(with_figures(236.3787, 3) == "236");
  CHECK(with_figures(1279.6, 4) == "1280");
  CHECK(with_figures(3390.2, 3) == "3.39e+03");
  CHECK(with_figures(8.37, 3) == "8.37");
  CHECK(with_figures(1.5, 3) == "1.50");
  CHECK(with_figures(68.2, 12) == "68.2000000000");
  CHECK(with_figures(9.996, 3) == "10.0");
  CHECK(with_figures(999.6, 3) == "1.00e+03");
  CHECK(with_figures(0.000123456, 3) == "0.000123");
  CHECK(with_figures(0.0000123456, 3) == "1.23e-05");
  CHECK(with_figures(-42.25, 2) == "-42");
  CHECK(with_figures(0, 3) == "0");
  // Against C's printf %#.*g, whose only difference is the trailing point of a whole number.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> exponent(-6, 8), mantissa(1, 10);
  for (int k = 0; k < 2000; ++k) {
    const double value = mantissa(random) * std::pow(10.0, std::floor(exponent(random)));
    const int figures = 3 + k % 10;
    char c[64];
    std::snprintf(c, sizeof c, "%#.*g", figures, value);
    std::string expected = c;
    if (expected.back() == '.') expected.pop_back();
    CHECK(with_figures(value, figures) == expected);
  }
}

namespace {

// The rules' textbook definitions by decimal text (the digits a reader sees), apart from the
// arithmetic the program uses: the decade read from 17 digits, a rounding to n digits as printf's.
int text_decade(double x) {
  const std::string t = fmt::format("{:.16e}", x);
  return std::stoi(t.substr(t.find('e') + 1));
}
double text_decimal(long units, int k) { return std::stod(fmt::format("{}e{}", units, k)); }
double text_significant(double value, int digits) { return std::stod(fmt::format("{:.{}e}", value, digits - 1)); }
double text_measure(double e) {
  const int second = text_decade(e) - 1;
  const long units = std::lround(e / text_decimal(1, second));
  const double shown = text_decimal(units, second);
  return shown < e ? text_decimal(units + 1, second) : shown;
}
double text_absolute(double value, double error) {
  if (value == 0) return 0.0;
  const int last = text_decade(std::max(text_measure(error), bladestab::cli::finest_resolution * std::abs(value)));
  const int first = text_decade(std::abs(value));
  if (first < last) {
    const long units = std::lround(value / text_decimal(1, last));
    return units == 0 ? 0.0 : text_decimal(units, last);
  }
  return text_significant(value, first - last + 1);
}

}  // namespace

TEST_CASE("printed digits: the rounding's arithmetic gives the digits of the decimal text, ties and powers of ten too",
          "[printed_digits]") {
  const PrintedDigits digits;
  std::mt19937_64 random(2063);
  std::uniform_real_distribution<double> exponent(-12, 8), unit(0, 1);
  // Values at powers of ten and halfway between two roundings, where a scaled product's rounding
  // could decide; then values and errors spread over 20 decades.
  std::vector<std::pair<double, double>> cases;
  for (int k = -12; k <= 8; ++k) {
    const double p = std::pow(10.0, k);
    for (const double v : {p, std::nextafter(p, 0.0), std::nextafter(p, 2 * p), 1.25 * p, 1.2345 * p, 9.9995 * p}) {
      for (const double e : {1e-3 * p, 1e-5 * p, 0.05 * p, p}) cases.emplace_back(v, e);
    }
  }
  for (int i = 0; i < 200000; ++i) {
    const double v = (unit(random) < 0.5 ? -1 : 1) * std::pow(10.0, exponent(random));
    cases.emplace_back(v, std::abs(v) * std::pow(10.0, -10 * unit(random)));
  }
  int differ = 0;
  for (const auto& [v, e] : cases) {
    if (digits.absolute(v, e) != text_absolute(v, e) && ++differ <= 5) {
      WARN(fmt::format("{:.17g} ± {:.17g}: {:.17g}, the text {:.17g}", v, e, digits.absolute(v, e), text_absolute(v, e)));
    }
    if (digits.measure(e) != text_measure(e) && ++differ <= 5) WARN(fmt::format("measure {:.17g}", e));
  }
  CHECK(differ == 0);
}
