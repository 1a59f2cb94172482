#pragma once
// The monodromy matrix of an LTP system whose coefficient acts in pulses (docs/theory.md §3–§4):
// no Fourier series. Over one period T the coefficient is f(t) on the pulse [0, t_c) and 0 after,
// so with A_free = A₀ − f₀ B (the system without the coefficient)
//
//   Φ(T) = e^{A_free (T − t_c)} · Φ_pulse,   Φ̇_pulse = (A_free + f(t) B) Φ_pulse on [0, t_c],
//
// Φ_pulse by the sixth-order Magnus propagator (f smooth inside the pulse, so step doubling
// converges at sixth order), the flight after it by one matrix exponential. An impulse is the jump
// limit t_c → 0 at fixed J = ∫f dt: Φ_pulse = e^{J B} = I + J B where B² = 0 (the scaled modal
// form's B), then flight over the whole T.
#include <functional>
#include <limits>
#include <optional>

#include <Eigen/Dense>

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

// A periodic coefficient that acts in one pulse per period.
struct PeriodicPulse {
  double period = 0;                     // T; the system's period must be the same
  double width = 0;                      // t_c: the pulse is [0, t_c) of each period
  std::function<double(double)> value;   // f(t) on [0, t_c); 0 after
  std::optional<double> impulse;         // set: the pulse is the jump I + J B, J = *impulse; `value`
                                         // over `width` is then its rectangle (for RKF45 checks)
};

struct PulseMonodromy {
  Eigen::MatrixXd monodromy;     // Φ(T)
  Eigen::VectorXcd multipliers;  // its eigenvalues ρ, sorted by |ρ|, largest first
  int steps = 0;                 // Magnus steps through the pulse; 0 for an impulse's exact jump
  double error_estimate = 0;     // of the multipliers (StepDoubling; 0 for an impulse)
};

// A_free = A₀ − f₀ B, the state matrix between pulses.
Eigen::MatrixXd free_state_matrix(const LinearPeriodicSystem& system);

// Φ(T) with a fixed number of Magnus steps through the pulse (ignored for an impulse). The system
// gives A₀, B and f₀ = coefficients[0]; its other coefficients are not used. Throws
// std::invalid_argument if the system's period is not the pulse's.
Eigen::MatrixXd pulse_monodromy(const LinearPeriodicSystem& system, const PeriodicPulse& pulse, int steps);

// Φ(T) with the pulse's steps doubled (StepDoubling, from 1/32 of the count where h‖A‖ ≤ 2 on the
// pulse) until the multipliers are within `tolerance` > 0, relative above max|ρ| = 1. Throws
// NumericalError if 2^16 steps do not reach it, WorkLimitError if the steps `max_flops` affords
// (magnus_step_work) do not. progress(done, total) after each step count (total: the most the
// ladder can take, then done at its end).
PulseMonodromy exact_pulse_monodromy(const LinearPeriodicSystem& system, const PeriodicPulse& pulse, double tolerance,
                                     const std::function<void(int, int)>& progress = {},
                                     double max_flops = std::numeric_limits<double>::infinity());

// f(t) − f₀ of the pulsed coefficient over one period, the variation that multiplies B.
std::function<double(double)> pulse_variation(const LinearPeriodicSystem& system, const PeriodicPulse& pulse);

}  // namespace bladestab
