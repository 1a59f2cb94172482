#include "bladestab/ltp/hill.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/monodromy.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

// The Hill matrix in the real sin/cos basis: with x = Σ c_k e^{ikθt}, a_k = c_k + c_{−k} and
// b_k = i (c_k − c_{−k}) are the cosine and sine amplitudes; H_r = P H P⁻¹ is real. P and P⁻¹
// have at most two identity blocks per block row and column, so H_r is summed block by block
// (O(N² n) instead of two dense complex N × N products, N = n(2q + 1)).
Eigen::MatrixXd real_hill_matrix(const LinearPeriodicSystem& sys, int q) {
  const int n = sys.state_size(), N = n * (2 * q + 1);
  const Eigen::MatrixXcd H = hill_matrix(sys, q);
  struct Entry {
    int row, col;  // block indices
    cplx value;    // times the identity block
  };
  const cplx i(0, 1);
  std::vector<Entry> P{{0, q, 1}}, Pinv{{q, 0, 1}};  // constant term first
  for (int k = 1; k <= q; ++k) {
    const int cos_row = 2 * k - 1, sin_row = 2 * k, plus = q + k, minus = q - k;
    P.insert(P.end(), {{cos_row, plus, 1}, {cos_row, minus, 1}, {sin_row, plus, i}, {sin_row, minus, -i}});
    Pinv.insert(Pinv.end(),
                {{plus, cos_row, 0.5}, {plus, sin_row, -0.5 * i}, {minus, cos_row, 0.5}, {minus, sin_row, 0.5 * i}});
  }
  Eigen::MatrixXd Hr = Eigen::MatrixXd::Zero(N, N);
  for (const Entry& p : P) {
    for (const Entry& r : Pinv) {
      Hr.block(p.row * n, r.col * n, n, n) += (p.value * r.value * H.block(p.col * n, r.row * n, n, n)).real();
    }
  }
  return Hr;
}

}  // namespace

Eigen::MatrixXcd hill_matrix(const LinearPeriodicSystem& sys, int q) {
  // The eigensolvers and LU after it may not return on NaN or infinity.
  if (!sys.A0.allFinite() || !sys.B.allFinite() || !std::isfinite(sys.angular_frequency)) {
    throw NumericalError("the periodic system is not finite");
  }
  const int n = sys.state_size(), blocks = 2 * q + 1;
  const int M = static_cast<int>(sys.coefficients.size()) - 1;
  Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(n * blocks, n * blocks);
  for (int j = -q; j <= q; ++j) {
    for (int k = std::max(-q, j - M); k <= std::min(q, j + M); ++k) {
      H.block((j + q) * n, (k + q) * n, n, n) = sys.harmonic(j - k);
    }
    H.block((j + q) * n, (j + q) * n, n, n).diagonal().array() -= cplx(0, j * sys.angular_frequency);
  }
  return H;
}

Eigen::VectorXcd hill_multipliers(const LinearPeriodicSystem& sys, int q) {
  // Classical sorting: of the n(2q+1) exponents keep the n with the smallest |Im λ|.
  Eigen::EigenSolver<Eigen::MatrixXd> eig(real_hill_matrix(sys, q), false);
  if (eig.info() != Eigen::Success) throw NumericalError("the Hill matrix's eigenvalues did not converge");
  std::vector<cplx> lambda(eig.eigenvalues().data(), eig.eigenvalues().data() + eig.eigenvalues().size());
  std::sort(lambda.begin(), lambda.end(), [](cplx a, cplx b) { return std::abs(a.imag()) < std::abs(b.imag()); });
  const int n = sys.state_size();
  Eigen::VectorXcd rho(n);
  for (int k = 0; k < n; ++k) rho(k) = std::exp(lambda[k] * sys.period());
  std::sort(rho.data(), rho.data() + n, [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  return rho;
}

Eigen::VectorXcd koopman_hill_multipliers(const LinearPeriodicSystem& sys, int q) {
  // Φ(T) ≈ C e^{HT} W: C sums the block rows, W is the central block column. In the real sin/cos
  // basis (real_hill_matrix: H = P⁻¹ H_r P) this is C_r e^{H_r T} E₀, with P W = E₀ the constant
  // term's block and C_r = C P⁻¹ = [I, I, 0, I, 0, …] (x(0) is a₀ plus the cosine amplitudes).
  // From H_r = V Λ V⁻¹: C_r V e^{ΛT} (V⁻¹ E₀), a real eigenproblem in place of a complex one.
  const int n = sys.state_size(), N = n * (2 * q + 1);
  Eigen::EigenSolver<Eigen::MatrixXd> eig(real_hill_matrix(sys, q), true);
  if (eig.info() != Eigen::Success) throw NumericalError("the Hill matrix's eigenvalues did not converge");
  const Eigen::MatrixXcd V = eig.eigenvectors();
  Eigen::MatrixXcd Y = V.partialPivLu().solve(Eigen::MatrixXcd::Identity(N, n));
  for (int i = 0; i < N; ++i) Y.row(i) *= std::exp(eig.eigenvalues()(i) * sys.period());
  Eigen::MatrixXcd CV = V.topRows(n);  // the constant term, then each cosine amplitude
  for (int k = 1; k <= q; ++k) CV += V.middleRows((2 * k - 1) * n, n);
  const Eigen::MatrixXd Phi = (CV * Y).real();
  return sorted_eigenvalues(Phi);
}

}  // namespace bladestab
