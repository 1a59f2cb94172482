#include "bladestab/ltp/monodromy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/reversing_symmetry.hpp"
#include "ltp/rkf45_propagation.hpp"

namespace bladestab {

using cplx = std::complex<double>;

Eigen::MatrixXd magnus_monodromy(const LinearPeriodicSystem& sys, int steps, bool whole_period) {
  const auto f = [&sys](double t) { return sys.variation(t); };
  const double T = sys.period();
  const std::optional<Eigen::VectorXd> r = !whole_period && steps % 2 == 0 ? reversing_signature(sys) : std::nullopt;
  if (!r) return magnus_propagator(sys.A0, sys.B, f, 0, T, steps);
  // Φ(T) = R U⁻¹ R U (reversing_symmetry.hpp) where U is well conditioned, as it is for a blade
  // near stability; a fast-growing U would lose its small directions in U⁻¹, and the second half
  // is then integrated as the first.
  const Eigen::MatrixXd U = magnus_propagator(sys.A0, sys.B, f, 0, T / 2, steps / 2);
  if (!U.allFinite()) return U;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(U);
  if (!(lu.rcond() > 1e-4)) return magnus_propagator(sys.A0, sys.B, f, T / 2, T, steps / 2) * U;
  return r->asDiagonal() * lu.solve(r->asDiagonal() * U);
}

NumericalError monodromy_overflow(double period) {
  return NumericalError(fmt::format("unstable: the monodromy matrix overflows the double range (max|ρ| > 1e308, max "
                                    "Re λ > {:.3g} 1/s): the system grows past it within one period, so no multiplier "
                                    "can be printed",
                                    std::log(1e308) / period));
}

double monodromy_step_work(const LinearPeriodicSystem& sys) {
  return magnus_step_work(sys.state_size()) * (reversing_signature(sys) ? 0.5 : 1.0);
}

Eigen::VectorXcd sorted_eigenvalues(const Eigen::MatrixXd& phi) {
  Eigen::EigenSolver<Eigen::MatrixXd> eig(phi, false);
  if (eig.info() != Eigen::Success) throw NumericalError("the eigenvalues of the monodromy matrix did not converge");
  Eigen::VectorXcd rho = eig.eigenvalues();
  std::sort(rho.data(), rho.data() + rho.size(), [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  return rho;
}

Eigen::VectorXcd monodromy_multipliers(const LinearPeriodicSystem& sys, int steps) {
  const Eigen::MatrixXd phi = magnus_monodromy(sys, steps);
  if (!phi.allFinite()) throw NumericalError(fmt::format("the monodromy overflowed with {} Magnus steps", steps));
  return sorted_eigenvalues(phi);
}

Eigen::MatrixXd rkf45_monodromy(const LinearPeriodicSystem& sys, double rtol) {
  // The scaled coordinates make every entry of Φ order one: atol = rtol.
  const int n = sys.state_size();
  return rkf45_propagate(sys, series_variation(sys), Eigen::MatrixXd::Identity(n, n), rtol, rtol);
}

int minimum_magnus_steps(const LinearPeriodicSystem& sys) {
  // max_t ‖A(t)‖₂ ≤ ‖A₀‖₂ + ‖B‖₂ Σ_{m≥1} 2|f_m|
  double amplitude = 0;
  for (std::size_t m = 1; m < sys.coefficients.size(); ++m) amplitude += 2 * std::abs(sys.coefficients[m]);
  // ‖a‖₂ = √λ_max(aᵀa), to the rounding of λ_max (ε‖a‖²): a symmetric eigenvalue solve, several
  // times cheaper than the SVD.
  const auto norm2 = [](const Eigen::MatrixXd& a) {
    const Eigen::MatrixXd gram = a.transpose() * a;
    return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly)
                                       .eigenvalues()
                                       .maxCoeff()));
  };
  const double bound = norm2(sys.A0) + amplitude * norm2(sys.B);
  const double steps = std::max({32.0, 8.0 * sys.coefficients.size(), bound * sys.period() / 2});
  return steps > (1 << 30) ? (1 << 30) + 1 : 1 << static_cast<int>(std::ceil(std::log2(steps)));
}

double multiplier_set_distance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  // Pairs matched closest first over all pairs (a double root meets each partner once).
  std::vector<std::tuple<double, Eigen::Index, Eigen::Index>> pairs;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    for (Eigen::Index j = 0; j < b.size(); ++j) pairs.emplace_back(std::abs(a(i) - b(j)), i, j);
  }
  if (std::any_of(pairs.begin(), pairs.end(), [](const auto& p) { return std::isnan(std::get<0>(p)); })) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  double largest = 0;
  for (const auto& [d, i, j] : pairs) {
    if (used_a[i] || used_b[j]) continue;
    used_a[i] = used_b[j] = true;
    largest = std::max(largest, d);
  }
  return largest;
}

double liouville_error(const Eigen::MatrixXd& phi, const LinearPeriodicSystem& sys) {
  // det Φ(T) = exp(∫₀ᵀ tr A dt) = exp(T tr A₀): f − f₀ has mean zero over a period.
  // In logarithms from the LU factors: damped stiff modes put det Φ far below the smallest double.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(phi);
  double log_det = 0, sign = lu.permutationP().determinant();
  for (Eigen::Index i = 0; i < lu.matrixLU().rows(); ++i) {
    log_det += std::log(std::abs(lu.matrixLU()(i, i)));
    sign *= lu.matrixLU()(i, i) < 0 ? -1 : 1;
  }
  return std::abs(sign * std::exp(log_det - sys.A0.trace() * sys.period()) - 1);
}

}  // namespace bladestab
