#include "bladestab/pulse_monodromy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bladestab/magnus.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

// Eigenvalues sorted by |ρ|, largest first; NaN if the Magnus series diverged (too few steps).
Eigen::VectorXcd sorted_multipliers(const Eigen::MatrixXd& Phi) {
  if (!Phi.allFinite()) return Eigen::VectorXcd::Constant(Phi.rows(), std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXcd rho = Eigen::EigenSolver<Eigen::MatrixXd>(Phi, false).eigenvalues();
  std::sort(rho.data(), rho.data() + rho.size(), [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  return rho;
}

}  // namespace

Eigen::MatrixXd pulse_monodromy(const PeriodicSystem& sys, const PulseTrain& train, int steps) {
  const double T = train.period_s, tc = train.contact_time_s;
  if (std::abs(sys.period() - T) > 1e-12 * T) {
    throw std::invalid_argument(fmt::format("pulse_monodromy: the system's period {:.12g} s is not the pulse period "
                                            "{:.12g} s", sys.period(), T));
  }
  const int n = sys.state_size();
  // SPEC §4: A(t) = A₀ + (F(t) − F₀) B, so the unloaded blade is A₀ − F₀ B.
  const Eigen::MatrixXd A_free = sys.A0 - sys.load.at(0).real() * sys.B;
  if (train.profile == PulseProfile::impulse) {
    // (A.5) as the jump limit: ẏ = F(t) B y over a vanishing window of impulse J = ∫F dt gives
    // y⁺ = e^{J B} y⁻ = (I + J B) y⁻, since B² = 0. The scene's impulse is F_max t_c, compressive.
    const double J = -train.peak_n * tc;
    return (A_free * T).exp() * (Eigen::MatrixXd::Identity(n, n) + J * sys.B);
  }
  const Eigen::MatrixXd contact = magnus_propagator(
      [&](double t) -> Eigen::MatrixXd { return A_free + train.force(t) * sys.B; }, n, 0, tc, steps);
  return (A_free * (T - tc)).exp() * contact;
}

PulseMonodromy exact_pulse_monodromy(const PeriodicSystem& sys, const PulseTrain& train, double tolerance) {
  if (!(tolerance > 0)) throw std::invalid_argument(fmt::format("exact_pulse_monodromy: tolerance {} must be > 0", tolerance));
  PulseMonodromy result;
  if (train.profile == PulseProfile::impulse) {
    result.monodromy = pulse_monodromy(sys, train, 0);
    result.multipliers = sorted_multipliers(result.monodromy);
  } else {
    constexpr int first_steps = 2, max_steps = 1 << 16;
    Eigen::VectorXcd previous = sorted_multipliers(pulse_monodromy(sys, train, first_steps));
    for (int steps = 2 * first_steps;; steps *= 2) {
      if (steps > max_steps) {
        throw std::runtime_error(fmt::format("the exact pulse monodromy did not converge to {:g} within {} steps",
                                             tolerance, max_steps));
      }
      result.monodromy = pulse_monodromy(sys, train, steps);
      result.multipliers = sorted_multipliers(result.monodromy);
      result.steps = steps;
      result.error_estimate = multiplier_distance(result.multipliers, previous);
      if (std::isfinite(result.error_estimate) && result.error_estimate <= tolerance) break;
      previous = result.multipliers;
    }
  }
  // Liouville: det Φ(T) = exp(∫₀^T tr A dt), and tr A(t) = tr A₀ = −tr Ĉ (B has a zero diagonal).
  // In logarithms from the LU factors: damped stiff modes put det Φ far below the smallest double.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(result.monodromy);
  double log_det = 0, sign = lu.permutationP().determinant();
  for (Eigen::Index i = 0; i < lu.matrixLU().rows(); ++i) {
    log_det += std::log(std::abs(lu.matrixLU()(i, i)));
    sign *= lu.matrixLU()(i, i) < 0 ? -1 : 1;
  }
  result.determinant_error = std::abs(sign * std::exp(log_det + sys.modal_C.trace() * train.period_s) - 1);
  return result;
}

double multiplier_distance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  if (a.size() != b.size()) throw std::invalid_argument("multiplier_distance: sets of different sizes");
  std::vector<std::tuple<double, Eigen::Index, Eigen::Index>> pairs;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    for (Eigen::Index j = 0; j < b.size(); ++j) {
      pairs.emplace_back(std::abs(a(i) - b(j)) / std::max(1.0, std::abs(a(i))), i, j);
    }
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

}  // namespace bladestab
