// Gauss–Legendre nodes by Newton's method on P_n from the Tricomi initial guesses; weights from
// P_n'. Accurate to a few ulp for the n (< 1000) used here.
#include "blade/quadrature.hpp"

#include <cmath>
#include <stdexcept>

#include "bladestab/base/constants.hpp"

namespace bladestab {

QuadratureRule gauss_legendre(int n, double a, double b) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: n must be >= 1");
  QuadratureRule rule{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1, p1 = x;  // three-term recurrence for P_n(x)
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2 / ((1 - x * x) * dp * dp);
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    rule.points(i) = mid - half * x;
    rule.points(n - 1 - i) = mid + half * x;
    rule.weights(i) = rule.weights(n - 1 - i) = half * w;
  }
  return rule;
}

}  // namespace bladestab
