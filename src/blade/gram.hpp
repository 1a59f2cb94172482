#pragma once
// The weighted Gram products every Ritz matrix is made of (docs/theory.md §2): internal to blade/.
#include <Eigen/Dense>

namespace bladestab {

// ∫ c(s) a_i(s) b_j(s) ds  =  aᵀ diag(w ∘ c) b, for shape functions a, b sampled at quadrature
// points with weights w.
inline Eigen::MatrixXd gram(const Eigen::VectorXd& weighted_coefficient, const Eigen::MatrixXd& a,
                            const Eigen::MatrixXd& b) {
  return a.transpose() * weighted_coefficient.asDiagonal() * b;
}

inline Eigen::MatrixXd symmetrized(const Eigen::MatrixXd& m) { return 0.5 * (m + m.transpose()); }

}  // namespace bladestab
