#include "bladestab/magnus.hpp"

#include <cmath>

#include <unsupported/Eigen/MatrixFunctions>

namespace bladestab {

Eigen::MatrixXd magnus_propagator(const StateMatrixFunction& A, int size, double t0, double t1, int steps) {
  const double h = (t1 - t0) / steps;
  const double r = std::sqrt(15.0) / 10;  // Gauss nodes 1/2 ∓ √15/10, 1/2
  const auto commutator = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) -> Eigen::MatrixXd {
    return x * y - y * x;
  };
  Eigen::MatrixXd X = Eigen::MatrixXd::Identity(size, size);
  for (int k = 0; k < steps; ++k) {
    const double t = t0 + k * h;
    const Eigen::MatrixXd A1 = A(t + (0.5 - r) * h), A2 = A(t + 0.5 * h), A3 = A(t + (0.5 + r) * h);
    // Moments of A on the step, then the commutator form of the 6th-order Magnus expansion.
    const Eigen::MatrixXd a1 = h * A2;
    const Eigen::MatrixXd a2 = std::sqrt(15.0) / 3 * h * (A3 - A1);
    const Eigen::MatrixXd a3 = 10.0 / 3 * h * (A3 - 2 * A2 + A1);
    const Eigen::MatrixXd c1 = commutator(a1, a2);
    const Eigen::MatrixXd c2 = -1.0 / 60 * commutator(a1, 2 * a3 + c1);
    const Eigen::MatrixXd omega = a1 + a3 / 12 + 1.0 / 240 * commutator(-20 * a1 - a3 + c1, a2 + c2);
    X = omega.exp() * X;
  }
  return X;
}

}  // namespace bladestab
