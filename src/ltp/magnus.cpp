#include "bladestab/ltp/magnus.hpp"

#include <cmath>

#include "bladestab/ltp/small_expm.hpp"

namespace bladestab {

Eigen::MatrixXd magnus_propagator(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B,
                                  const std::function<double(double)>& phi, double t0, double t1, int steps) {
  const auto commutator = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) -> Eigen::MatrixXd {
    return x * y - y * x;
  };
  // With A_i = A₀ + φ_i B at the Gauss nodes: a1 = h(A₀ + φ₂B), a2 = βB, a3 = γB, and
  // c1 = hβP, c2 = −(2hγP + h²β(Q + φ₂R))/60, where P = [A₀,B], Q = [A₀,P], R = [B,P];
  // [X, Y] of the last term then needs S1..S6 below.
  const Eigen::MatrixXd P = commutator(A0, B), Q = commutator(A0, P), R = commutator(B, P);
  const Eigen::MatrixXd S1 = commutator(A0, Q), S2 = commutator(A0, R), S3 = commutator(B, Q), S4 = commutator(B, R),
                        S5 = commutator(P, Q), S6 = commutator(P, R);
  const double h = (t1 - t0) / steps, r = std::sqrt(15.0) / 10;
  const Eigen::Index n = A0.rows();
  // Every buffer is sized here: the loop allocates nothing.
  Eigen::MatrixXd X = Eigen::MatrixXd::Identity(n, n), omega(n, n), step(n, n), next(n, n);
  SmallExpm expm(n);
  for (int k = 0; k < steps; ++k) {
    const double t = t0 + k * h;
    const double f1 = phi(t + (0.5 - r) * h), f2 = phi(t + 0.5 * h), f3 = phi(t + (0.5 + r) * h);
    const double beta = std::sqrt(15.0) / 3 * h * (f3 - f1), gamma = 10.0 / 3 * h * (f3 - 2 * f2 + f1);
    // X = x0 A₀ + xB B + xP P,  Y = yB B + yP P + yQ Q + yR R  (X = −20a1 − a3 + c1, Y = a2 + c2)
    const double x0 = -20 * h, xB = -20 * h * f2 - gamma, xP = h * beta;
    const double yB = beta, yP = -2 * h * gamma / 60, yQ = -h * h * beta / 60, yR = -h * h * beta * f2 / 60;
    // Ω = a1 + a3/12 + [X, Y]/240, with [X, Y] expanded over the nested commutators.
    omega = h * A0 + (h * f2 + gamma / 12) * B + (x0 * yB / 240) * P + (x0 * yP / 240) * Q +
            ((xB * yP - xP * yB) / 240) * R;
    omega += (x0 * yQ / 240) * S1 + (x0 * yR / 240) * S2 + (xB * yQ / 240) * S3 + (xB * yR / 240) * S4 +
             (xP * yQ / 240) * S5 + (xP * yR / 240) * S6;
    expm.compute(omega, step);
    next.noalias() = step * X;
    X.swap(next);
  }
  return X;
}

}  // namespace bladestab
