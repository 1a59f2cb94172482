#pragma once
// The free system M f̈ + C ḟ + K f = 0 (K, M symmetric positive definite) in first-order form, in
// scaled modal coordinates of the test's own: f = Φη with (K, M)'s M-orthonormal modes Φ (Eigen's
// generalized self-adjoint solver), ω² = diag ΦᵀKΦ, state y = [ω η; η̇]:
//
//   ẏ = A y,   A = [[0, diag ω], [−diag ω, −ΦᵀCΦ]],
//
// whose eigenvalues are the λ of (λ²M + λC + K) q = 0. The plain companion matrix
// [[0, I], [−M⁻¹K, −M⁻¹C]] spans ω_max² (≈ 1e11 for the blade) and loses five digits of the low
// modes; this form spans ω_max. Header-only, independent of the library's eigensolvers.
#include <Eigen/Dense>

namespace reference {

struct FirstOrderModes {
  Eigen::MatrixXd M, Phi, A;
  Eigen::VectorXd omega;

  FirstOrderModes(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K) : M(mass) {
    const Eigen::Index n = M.rows();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(K, M);
    Phi = modes.eigenvectors();
    omega = modes.eigenvalues().cwiseSqrt();
    A.resize(2 * n, 2 * n);
    A << Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd(omega.asDiagonal()), -Eigen::MatrixXd(omega.asDiagonal()),
        -Phi.transpose() * C * Phi;
  }
  Eigen::VectorXcd eigenvalues() const { return Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues(); }
  // The state y of a displacement f and velocity v (η = ΦᵀM f, since ΦᵀMΦ = I), and back.
  Eigen::VectorXd state(const Eigen::VectorXd& f, const Eigen::VectorXd& v) const {
    Eigen::VectorXd y(A.rows());
    y << omega.cwiseProduct(Phi.transpose() * (M * f)), Phi.transpose() * (M * v);
    return y;
  }
  Eigen::VectorXd displacement(const Eigen::VectorXd& y) const {
    return Phi * y.head(omega.size()).cwiseQuotient(omega);
  }
};

}  // namespace reference
