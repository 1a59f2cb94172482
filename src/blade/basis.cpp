#include "blade/basis.hpp"

#include <cmath>

#include "bladestab/base/constants.hpp"

namespace bladestab {
namespace {

// Paper basis (18a–c).
void sample_sine(FieldRole role, int terms, double L, const Eigen::VectorXd& s, BasisSamples& out) {
  for (int n = 1; n <= terms; ++n) {
    const double lam = (2 * n - 1) * pi / (2 * L);
    for (Eigen::Index q = 0; q < s.size(); ++q) {
      const double sn = std::sin(lam * s(q)), cs = std::cos(lam * s(q));
      switch (role) {
        case FieldRole::rotation:  // U_n = sin(λs)
          out.value(q, n - 1) = sn;
          out.slope(q, n - 1) = lam * cs;
          out.curvature(q, n - 1) = -lam * lam * sn;
          break;
        case FieldRole::lateral:
        case FieldRole::lateral_clamped:  // V_n = (1 − cos λs)/λ
          out.value(q, n - 1) = (1 - cs) / lam;
          out.slope(q, n - 1) = sn;
          out.curvature(q, n - 1) = lam * cs;
          break;
        case FieldRole::axial:  // W_n = sin(λs)/λ
          out.value(q, n - 1) = sn / lam;
          out.slope(q, n - 1) = cs;
          out.curvature(q, n - 1) = -lam * sn;
          break;
      }
    }
  }
}

// Integrated Legendre polynomials. With x = 2s/L − 1 and I1_m(x) = ∫_{−1}^x P_m,
// I2_m(x) = ∫_{−1}^x I1_m:  I1_0 = x + 1, I1_m = (P_{m+1} − P_{m−1})/(2m + 1);
// I2_0 = (x + 1)²/2, I2_m = (I1_{m+1} − I1_{m−1})/(2m + 1).
void sample_legendre(FieldRole role, int terms, double L, const Eigen::VectorXd& s, BasisSamples& out) {
  const int top = terms + 2;  // P_0 .. P_{terms+1}
  Eigen::VectorXd P(top + 1), I1(top), I2(terms);
  for (Eigen::Index q = 0; q < s.size(); ++q) {
    const double x = 2 * s(q) / L - 1;
    P(0) = 1;
    P(1) = x;
    for (int k = 2; k <= top; ++k) P(k) = ((2 * k - 1) * x * P(k - 1) - (k - 1) * P(k - 2)) / k;
    I1(0) = x + 1;
    for (int m = 1; m < top; ++m) I1(m) = (P(m + 1) - P(m - 1)) / (2 * m + 1);
    I2(0) = 0.5 * (x + 1) * (x + 1);
    for (int m = 1; m < terms; ++m) I2(m) = (I1(m + 1) - I1(m - 1)) / (2 * m + 1);
    for (int k = 0; k < terms; ++k) {
      // dP_k/dx from (1 − x²)P_k' = k(P_{k−1} − x P_k), continued to the end points.
      double dP = 0;
      if (k > 0) {
        dP = std::abs(1 - x * x) > 1e-14 ? k * (P(k - 1) - x * P(k)) / (1 - x * x)
                                         : (x > 0 ? 1.0 : (k % 2 ? 1.0 : -1.0)) * 0.5 * k * (k + 1);
      }
      if (role == FieldRole::lateral_clamped) {  // ψ_k = (L/2)² I2_{k−1}
        out.value(q, k) = 0.25 * L * L * I2(k);
        out.slope(q, k) = 0.5 * L * I1(k);
        out.curvature(q, k) = P(k);
      } else {  // φ_k = (L/2) I1_{k−1}
        out.value(q, k) = 0.5 * L * I1(k);
        out.slope(q, k) = P(k);
        out.curvature(q, k) = 2 / L * dP;
      }
    }
  }
}

}  // namespace

BasisSamples sample_basis(BasisKind kind, FieldRole role, int terms, double length,
                          const Eigen::VectorXd& points) {
  BasisSamples out{Eigen::MatrixXd(points.size(), terms), Eigen::MatrixXd(points.size(), terms),
                   Eigen::MatrixXd(points.size(), terms)};
  if (kind == BasisKind::sine) {
    sample_sine(role, terms, length, points, out);
  } else {
    sample_legendre(role, terms, length, points, out);
  }
  return out;
}

int quadrature_points_needed(BasisKind kind, int terms) {
  // Legendre: the richest integrand is ψ_i ψ_j (degree 2·terms + 2) or T_cf φ_i' φ_j' (degree
  // 2·terms); n points integrate degree 2n − 1 exactly.
  if (kind == BasisKind::legendre) return terms + 3;
  // Sine: products oscillate up to wavenumber 2λ_N = (2N − 1)π/L; Gauss–Legendre reaches machine
  // precision once n exceeds that bandwidth by a margin (checked in the tests against twice n).
  return 2 * terms + 24;
}

}  // namespace bladestab
