#pragma once
// Characteristic values of Mathieu's equation y'' + (a − 2q cos 2τ) y = 0 by the tridiagonal
// (continued-fraction) recurrences of the Fourier coefficients (Abramowitz & Stegun 20.2),
// truncated at 60 terms: exact to rounding for |q| ≲ 100. Independent of the library.
#include <cmath>

#include <Eigen/Dense>

namespace reference {

enum class MathieuKind { a_even, a_odd, b_even, b_odd };  // a_{2r}, a_{2r+1}, b_{2r+2}, b_{2r+1}

// The r-th (0-based) characteristic value of the given kind: mathieu(a_odd, 0, q) = a_1(q),
// mathieu(b_even, 0, q) = b_2(q), mathieu(a_even, 1, q) = a_2(q), …
inline double mathieu(MathieuKind kind, int r, double q) {
  constexpr int n = 60;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    switch (kind) {
      case MathieuKind::a_even: T(k, k) = 4.0 * k * k; break;                     // A_0, A_2, …
      case MathieuKind::b_even: T(k, k) = 4.0 * (k + 1) * (k + 1); break;         // B_2, B_4, …
      case MathieuKind::a_odd:
      case MathieuKind::b_odd: T(k, k) = (2.0 * k + 1) * (2.0 * k + 1); break;    // A_1, A_3, … / B_1, …
    }
    if (k + 1 < n) T(k, k + 1) = T(k + 1, k) = q;
  }
  if (kind == MathieuKind::a_even) T(0, 1) = T(1, 0) = std::sqrt(2.0) * q;  // symmetrized A_0 row
  if (kind == MathieuKind::a_odd) T(0, 0) += q;
  if (kind == MathieuKind::b_odd) T(0, 0) -= q;
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly).eigenvalues()(r);
}

// The boundary θ of y'' + ω0²(1 − F̄/2 + (F̄/2) cos θt) y = 0 (w0 = ω0) where Mathieu's a equals
// the characteristic value of `kind` and `rank`: with τ = θt/2 it is y'' + (a − 2q cos 2τ) y = 0,
// x = 4ω0²/θ², a = x(1 − F̄/2), q = −x F̄/4, taken here as |q| (the sign only swaps a_odd and
// b_odd); bisected in x on [x0, x1], which must bracket one root.
inline double mathieu_blade_boundary(MathieuKind kind, int rank, double fbar, double w0, double x0, double x1) {
  double lo = x0, hi = x1;
  const auto g = [&](double x) { return x * (1 - fbar / 2) - mathieu(kind, rank, x * fbar / 4); };
  for (int i = 0; i < 200; ++i) ((g(0.5 * (lo + hi)) > 0) == (g(lo) > 0) ? lo : hi) = 0.5 * (lo + hi);
  return 2 * w0 / std::sqrt(0.5 * (lo + hi));
}

}  // namespace reference
