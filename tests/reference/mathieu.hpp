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

}  // namespace reference
