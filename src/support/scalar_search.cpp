#include "support/scalar_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <boost/math/tools/toms748_solve.hpp>

namespace bladestab {

double bracketed_root(const std::function<double(double)>& g, double a, double ga, double b, double gb) {
  const double tolerance = 1e-12 * std::max(1.0, std::abs(b));
  const auto close_enough = [tolerance](double lo, double hi) { return hi - lo <= tolerance; };
  std::uintmax_t iterations = 100;
  const std::pair<double, double> bracket = boost::math::tools::toms748_solve(g, a, b, ga, gb, close_enough, iterations);
  return 0.5 * (bracket.first + bracket.second);
}

double golden_minimum(const std::function<double(double)>& f, double a, double b, double tolerance) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1);  // 1/φ
  const double lo = a, hi = b;
  double c = b - ratio * (b - a), d = a + ratio * (b - a);
  double fc = f(c), fd = f(d);
  for (int iter = 0; iter < 200 && b - a > tolerance; ++iter) {
    if (fc <= fd) {
      b = d, d = c, fd = fc;
      c = b - ratio * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + ratio * (b - a), fd = f(d);
    }
  }
  double best = fc <= fd ? c : d, value = std::min(fc, fd);
  for (double end : {lo, hi}) {
    const double v = f(end);
    if (v < value) best = end, value = v;
  }
  return best;
}

}  // namespace bladestab
