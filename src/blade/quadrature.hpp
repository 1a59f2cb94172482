#pragma once
#include <Eigen/Dense>

namespace bladestab {

// n-point Gauss–Legendre rule on [a, b]: exact for polynomials of degree 2n − 1.
struct QuadratureRule {
  Eigen::VectorXd points;
  Eigen::VectorXd weights;
};

QuadratureRule gauss_legendre(int n, double a, double b);

}  // namespace bladestab
