#include "support/scalar_search.hpp"

#include <algorithm>
#include <cmath>

namespace bladestab {

double illinois_root(const std::function<double(double)>& g, double a, double ga, double b, double gb) {
  int side = 0;
  for (int iter = 0; iter < 60 && std::abs(b - a) > 1e-12 * std::max(1.0, std::abs(b)); ++iter) {
    const double c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if (gc == 0) return c;
    if ((gc > 0) == (gb > 0)) {
      b = c, gb = gc;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = c, ga = gc;
      if (side == 1) gb *= 0.5;
      side = 1;
    }
  }
  return std::abs(ga) < std::abs(gb) ? a : b;
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
