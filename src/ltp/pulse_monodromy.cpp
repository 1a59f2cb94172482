#include "bladestab/ltp/pulse_monodromy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/step_doubling.hpp"

namespace bladestab {
namespace {

// What Φ(T) takes from the system between pulses, the same at every step count of the pulse:
// A_free and the flight after the pulse (over the whole T after an impulse), computed once.
struct FreeFlight {
  Eigen::MatrixXd A_free, flight;
};

FreeFlight free_flight(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse) {
  const double T = pulse.period, tc = pulse.width;
  if (std::abs(sys.period() - T) > 1e-12 * T) {
    throw std::invalid_argument(fmt::format("pulse_monodromy: the system's period {:.12g} s is not the pulse period "
                                            "{:.12g} s", sys.period(), T));
  }
  FreeFlight f;
  f.A_free = free_state_matrix(sys);
  f.flight = (f.A_free * (pulse.impulse ? T : T - tc)).exp();
  return f;
}

Eigen::MatrixXd pulse_monodromy(const FreeFlight& f, const LinearPeriodicSystem& sys, const PeriodicPulse& pulse,
                                int steps) {
  if (pulse.impulse) {
    // The jump limit: ẏ = f(t) B y over a vanishing window of J = ∫f dt gives y⁺ = e^{J B} y⁻ =
    // (I + J B) y⁻, since B² = 0.
    const int n = sys.state_size();
    return f.flight * (Eigen::MatrixXd::Identity(n, n) + *pulse.impulse * sys.B);
  }
  return f.flight * magnus_propagator(f.A_free, sys.B, pulse.value, 0, pulse.width, steps);
}

// Eigenvalues sorted by |ρ|, largest first; NaN if the Magnus series diverged (too few steps).
Eigen::VectorXcd finite_multipliers(const Eigen::MatrixXd& phi) {
  if (!phi.allFinite()) return Eigen::VectorXcd::Constant(phi.rows(), std::numeric_limits<double>::quiet_NaN());
  return sorted_eigenvalues(phi);
}

}  // namespace

Eigen::MatrixXd free_state_matrix(const LinearPeriodicSystem& sys) {
  return sys.A0 - sys.coefficients.at(0).real() * sys.B;
}

Eigen::MatrixXd pulse_monodromy(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse, int steps) {
  return pulse_monodromy(free_flight(sys, pulse), sys, pulse, steps);
}

PulseMonodromy exact_pulse_monodromy(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse, double tolerance,
                                     const std::function<void(int, int)>& progress, double max_flops) {
  if (!(tolerance > 0)) throw std::invalid_argument(fmt::format("exact_pulse_monodromy: tolerance {} must be > 0", tolerance));
  PulseMonodromy result;
  const FreeFlight flight = free_flight(sys, pulse);
  if (pulse.impulse) {
    result.monodromy = pulse_monodromy(flight, sys, pulse, 0);
    result.multipliers = finite_multipliers(result.monodromy);
    return result;
  }
  // From 1/32 of the count where h‖A‖ ≤ 2 on the pulse: the exponential takes the stiff modes
  // exactly (a map of the paper blade's true train, N = 8, 2.2× faster than from 1/2).
  const double pulse_steps = minimum_magnus_steps(sys) * pulse.width / pulse.period;
  const int first = std::max(2, 1 << static_cast<int>(std::ceil(std::log2(std::max(1.0, pulse_steps / 32)))));
  StepDoubling ladder(first, 1 << 16, static_cast<int>(std::min(pulse_steps, 1e9)), magnus_step_work(sys.state_size()),
                      max_flops);
  int done = 0;
  Eigen::VectorXcd previous;
  for (int steps = first; steps <= ladder.last(); steps *= 2) {
    result.monodromy = pulse_monodromy(flight, sys, pulse, steps);
    result.steps = steps;
    if (progress) progress(++done, ladder.levels());
    if (!result.monodromy.allFinite()) {
      if (ladder.overflowed(steps)) throw monodromy_overflow(pulse.period);
      previous.resize(0);
      continue;
    }
    result.multipliers = sorted_eigenvalues(result.monodromy);
    if (previous.size() > 0) {
      const double distance = multiplier_set_distance(result.multipliers, previous);
      const double allowed = tolerance * std::max(1.0, result.multipliers.cwiseAbs().maxCoeff());
      if (const std::optional<double> error = ladder.judge(steps, distance, allowed)) {
        result.error_estimate = *error;
        if (progress) progress(done, done);
        return result;
      }
    }
    previous = result.multipliers;
  }
  ladder.give_up(fmt::format("the pulse monodromy did not converge to {:g}", tolerance), "steps");
}

std::function<double(double)> pulse_variation(const LinearPeriodicSystem& sys, const PeriodicPulse& pulse) {
  const double f0 = sys.coefficients.at(0).real();
  return [value = pulse.value, width = pulse.width, f0](double t) { return (t < width ? value(t) : 0.0) - f0; };
}

}  // namespace bladestab
