#pragma once
// The monodromy matrix of the true pulse train (load.approximation = "exact", SPEC §3–§4): no
// Fourier series. Over one pulse period T_p the load is the pulse on [0, t_c] and nothing after,
// so with A_free = A₀ − F₀ B (the blade without load)
//
//   Φ(T_p) = e^{A_free (T_p − t_c)} · Φ_pulse,   Φ̇_pulse = (A_free + F(t) B) Φ_pulse on [0, t_c],
//
// Φ_pulse by the sixth-order Magnus propagator (F(t) is smooth inside the window for every
// profile of Appendix A, so step doubling converges at sixth order), the free flight by one
// matrix exponential. The impulse (A.5) is the jump limit t_c → 0 at fixed J = ∫F dt: a velocity
// jump Φ_pulse = I + J B (exact: B² = 0), then free flight over the whole T_p.
//
// Multipliers are per pulse period T_p = PeriodicSystem::period() (θ = 2π/T_p), as the Fourier
// methods give them; with pulses_per_rev = k, one revolution is Φ(T_p)^k.
#include <functional>

#include <Eigen/Dense>

#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"

namespace bladestab {

struct PulseMonodromy {
  Eigen::MatrixXd monodromy;     // Φ(T_p)
  Eigen::VectorXcd multipliers;  // its eigenvalues ρ, sorted by |ρ|, largest first
  int steps = 0;                 // Magnus steps through the contact; 0 for the impulse's exact jump
  double error_estimate = 0;     // multiplier_set_distance between `steps` and steps/2 (0 for the impulse)
};

// A_free = A₀ − F₀ B, the state matrix of the blade between contacts (SPEC §4: A(t) = A₀ + (F(t) − F₀) B).
Eigen::MatrixXd free_state_matrix(const PeriodicSystem& system);

// Φ(T_p) with a fixed number of Magnus steps through the contact (ignored for the impulse).
// The system gives A₀, B and F₀ = load[0]; its other harmonics are not used. Throws
// std::invalid_argument if the system's period is not the train's.
Eigen::MatrixXd pulse_monodromy(const PeriodicSystem& system, const PulseTrain& train, int steps);

// Φ(T_p) with the contact's steps doubled until two successive counts give multipliers within
// `tolerance` > 0, relative above max|ρ| = 1 (multiplier_set_distance). Throws NumericalError if
// 2^16 steps do not reach it. progress(done, total) after each step count of the ladder (total:
// the most it can take, then done at its end).
PulseMonodromy exact_pulse_monodromy(const PeriodicSystem& system, const PulseTrain& train, double tolerance,
                                     const std::function<void(int, int)>& progress = {});

// F(t) − F₀ of the true train, the load variation that multiplies B.
std::function<double(double)> pulse_load_variation(const PeriodicSystem& system, const PulseTrain& train);

}  // namespace bladestab
