#include "bladestab/ltp/pulse_monodromy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/base/numerical_error.hpp"

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

// What Φ(T_p) takes from the unloaded blade, the same at every step count of the contact: A_free
// and the flight between contacts (over the whole T_p after an impulse), computed once per ladder.
struct FreeFlight {
  Eigen::MatrixXd A_free, flight;
};

FreeFlight free_flight(const PeriodicSystem& sys, const PulseTrain& train) {
  const double T = train.period_s, tc = train.contact_time_s;
  if (std::abs(sys.period() - T) > 1e-12 * T) {
    throw std::invalid_argument(fmt::format("pulse_monodromy: the system's period {:.12g} s is not the pulse period "
                                            "{:.12g} s", sys.period(), T));
  }
  FreeFlight f;
  f.A_free = free_state_matrix(sys);
  f.flight = (f.A_free * (train.profile == PulseProfile::impulse ? T : T - tc)).exp();
  return f;
}

Eigen::MatrixXd pulse_monodromy(const FreeFlight& f, const PeriodicSystem& sys, const PulseTrain& train, int steps) {
  const double tc = train.contact_time_s;
  if (train.profile == PulseProfile::impulse) {
    // (A.5) as the jump limit: ẏ = F(t) B y over a vanishing window of impulse J = ∫F dt gives
    // y⁺ = e^{J B} y⁻ = (I + J B) y⁻, since B² = 0. The scene's impulse is F_max t_c, compressive.
    const double J = -train.peak_n * tc;
    const int n = sys.state_size();
    return f.flight * (Eigen::MatrixXd::Identity(n, n) + J * sys.B);
  }
  return f.flight * magnus_propagator(f.A_free, sys.B, [&train](double t) { return train.force(t); }, 0, tc, steps);
}

}  // namespace

Eigen::MatrixXd free_state_matrix(const PeriodicSystem& sys) { return sys.A0 - sys.load.at(0).real() * sys.B; }

Eigen::MatrixXd pulse_monodromy(const PeriodicSystem& sys, const PulseTrain& train, int steps) {
  return pulse_monodromy(free_flight(sys, train), sys, train, steps);
}

PulseMonodromy exact_pulse_monodromy(const PeriodicSystem& sys, const PulseTrain& train, double tolerance,
                                     const std::function<void(int, int)>& progress) {
  if (!(tolerance > 0)) throw std::invalid_argument(fmt::format("exact_pulse_monodromy: tolerance {} must be > 0", tolerance));
  PulseMonodromy result;
  const FreeFlight flight = free_flight(sys, train);
  if (train.profile == PulseProfile::impulse) {
    result.monodromy = pulse_monodromy(flight, sys, train, 0);
    result.multipliers = sorted_multipliers(result.monodromy);
  } else {
    // From 1/32 of the count where h‖A‖ ≤ 2 on the contact: the exponential takes the stiff modes
    // exactly (a map of the true train, N = 8, 2.2× faster than from 1/2, every point within 4e-6
    // of it). A level is accepted when it agrees with the one before within the tolerance and the
    // differences contract (4× a level) or the count reaches h‖A‖ ≤ 2: two coarse counts that
    // agree by chance do not pass.
    constexpr int max_steps = 1 << 16;
    const double contact_steps = minimum_magnus_steps(sys) * train.contact_time_s / train.period_s;
    const int first_steps = std::max(2, 1 << static_cast<int>(std::ceil(std::log2(std::max(1.0, contact_steps / 32)))));
    Eigen::VectorXcd previous = sorted_multipliers(pulse_monodromy(flight, sys, train, first_steps));
    double previous_distance = std::numeric_limits<double>::infinity();
    // The levels done and the most the ladder can take: log2(max_steps / first_steps) + 1.
    const int most = static_cast<int>(std::lround(std::log2(static_cast<double>(max_steps) / first_steps))) + 1;
    int done = 1;
    if (progress) progress(done, most);
    for (int steps = 2 * first_steps;; steps *= 2) {
      if (steps > max_steps) {
        throw NumericalError(fmt::format("the exact pulse monodromy did not converge to {:g} within {} steps",
                                             tolerance, max_steps));
      }
      result.monodromy = pulse_monodromy(flight, sys, train, steps);
      result.multipliers = sorted_multipliers(result.monodromy);
      result.steps = steps;
      result.error_estimate = multiplier_set_distance(result.multipliers, previous);
      if (progress) progress(++done, most);
      const double scale = std::max(1.0, result.multipliers.cwiseAbs().maxCoeff());
      const bool contracting = 4 * result.error_estimate <= previous_distance || steps >= contact_steps;
      if (std::isfinite(result.error_estimate) && result.error_estimate <= tolerance * scale && contracting) break;
      previous = result.multipliers;
      previous_distance = result.error_estimate;
    }
    if (progress) progress(done, done);
  }
  return result;
}

std::function<double(double)> pulse_load_variation(const PeriodicSystem& sys, const PulseTrain& train) {
  const double F0 = sys.load.at(0).real();
  return [&train, F0](double t) { return train.force(t) - F0; };
}

}  // namespace bladestab
