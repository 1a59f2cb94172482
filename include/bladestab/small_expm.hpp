#pragma once
// e^X for the small dense matrices of a time-stepping loop, without heap traffic: a workspace
// sized once holds every intermediate, so the thousands of exponentials of a monodromy matrix
// allocate nothing. Eigen's MatrixFunctions exp() allocates its Padé temporaries on every call,
// which was about half the time of a Magnus monodromy (issue 9's profile).
//
// Method: scaling and squaring with the degree-12 Taylor polynomial (Higham, "Functions of
// Matrices", §10.3). X is scaled by 2^−s until ‖X‖₁ ≤ 0.33, where the Taylor remainder
// Σ_{k≥13} ‖X‖^k/k! ≤ 1e-16; the polynomial is evaluated by Paterson–Stockmeyer in powers
// X, X², X³, X⁴ (five products), then squared s times.
#include <Eigen/Dense>

namespace bladestab {

class SmallExpm {
 public:
  explicit SmallExpm(Eigen::Index n);
  // result = e^X; `result` must not alias X.
  void compute(const Eigen::MatrixXd& X, Eigen::MatrixXd& result);

 private:
  Eigen::MatrixXd x1_, x2_, x3_, x4_, block_, product_;
};

}  // namespace bladestab
