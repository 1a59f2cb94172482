#pragma once
// e^X for the small dense matrices of a time-stepping loop, without heap traffic: a workspace
// sized once holds every intermediate, so the thousands of exponentials of a monodromy matrix
// allocate nothing. Eigen's MatrixFunctions exp() allocates its Padé temporaries on every call,
// which was about half the time of a Magnus monodromy (issue 9's profile).
//
// Method: scaling and squaring with the degree-18 Taylor polynomial T₁₈, evaluated in five
// matrix products by the scheme of Bader, Blanes & Casas, "Computing the matrix exponential with
// an optimized Taylor polynomial approximation", Mathematics 7 (2019) 1174, §4.2 (their y₁₈ with
// the coefficients that minimize the sum of their magnitudes). X is scaled by 2^−s until
// α₂ = max(‖X²‖₁^½, ‖X³‖₁^⅓) ≤ θ₁₈ = 1.0909, where T₁₈'s backward error is below the unit
// roundoff 2^−53 (their Table 3; the bound through α₂ instead of ‖X‖₁ is Al-Mohy & Higham,
// SIAM J. Matrix Anal. Appl. 31 (2009) 970, Thm. 4.2), then squared s times. X² and X³ are the
// scheme's own products, so the sharper count costs nothing. The paper's degree-12
// Paterson–Stockmeyer polynomial costs as many products but reaches only ‖X‖₁ ≤ 0.33: two
// squarings more per step.
#include <Eigen/Dense>

namespace bladestab {

class SmallExpm {
 public:
  explicit SmallExpm(Eigen::Index n);
  // result = e^X; `result` must not alias X.
  void compute(const Eigen::MatrixXd& X, Eigen::MatrixXd& result);

 private:
  Eigen::MatrixXd x1_, x2_, x3_, x6_, a_, b_, y9_;
};

}  // namespace bladestab
