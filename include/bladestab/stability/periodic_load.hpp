#pragma once
// The tip load as a periodic function of time (docs/theory.md §3, Appendix A): a train of compressive
// pulses F(t) ≤ 0, its exact complex Fourier coefficients, and the series the frequency domain
// uses — the paper's cosine approximation (42) or the true pulse's series, truncated.
#include <complex>
#include <optional>
#include <vector>

#include "bladestab/blade/blade_properties.hpp"
#include "bladestab/ltp/linear_periodic_system.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct PulseTrain {
  PulseProfile profile = PulseProfile::half_sine;
  double peak_n = 0;          // F_max > 0 (the force is −F_max at its peak)
  double contact_time_s = 0;  // t_c
  double period_s = 0;        // T_p, time between pulses
  int count = 0;              // pulses in all; 0 = endless
  bool frequency_known = true; // false: Ω = 0 and no pulse_frequency_hz; the period is a nominal 1 s
                               // (the series' shape depends only on t_c/T_p, so boundaries in θ still work)

  double angular_frequency() const;  // θ = 2π / T_p
  // F(t) of the true pulse train [N]; 0 outside the contact windows [start, start + t_c) and
  // after the last pulse.
  double force(double t) const;
  // dF/dt [N/s], with the same half-open windows (the right-hand limit at an edge).
  double force_rate(double t) const;
  // max |dF/dt| over a pulse, between its edges.
  double max_force_rate() const;
  // Whether F is even about the middle of its contact, F(t_c − τ) = F(τ): every profile but the saw-tooth.
  bool even_profile() const { return profile != PulseProfile::sawtooth; }
  // Pulse starts and ends in [t0, t1]: where F or F' jumps, so integrator steps land there.
  std::vector<double> edges(double t0, double t1) const;
  // The time since the current pulse started, if one is on at t.
  std::optional<double> time_in_pulse(double t) const;
  // F_m = (1/T_p) ∫₀^{T_p} F(t) e^{−i m θ t} dt, exact closed form for every profile.
  std::complex<double> fourier_coefficient(int m) const;
  // (1/T_p) ∫ F² dt, for Parseval's tail bound.
  double mean_square() const;
};

// From the scene: F_max = F̄_max F_cr, T_p = 1/f_p with f_p = load.pulse_frequency_hz or
// pulses_per_rev · Ω/2π, t_c = contact_time_rev · 2π/Ω (a fraction of a revolution).
PulseTrain pulse_train(const Scene& scene);

// The train as the pulsed coefficient of the LTP kernels (pulse_monodromy.hpp): F(t) on the
// contact [0, t_c) of each pulse period; the impulse (A.5) as the jump J = −F_max t_c.
PeriodicPulse periodic_pulse(const PulseTrain& train);


// F(t) ≈ Σ_{|m| ≤ M} F_m e^{i m θ t}, stored for m = 0..M (F_{−m} = conj F_m).
struct LoadSeries {
  double angular_frequency = 0;              // θ
  std::vector<std::complex<double>> coefficients;
  double relative_tail = 0;                  // ‖F − series‖₂ / ‖F‖₂ (Parseval); 0 for the cosine approximation
  bool cosine_approximation = false;
  // load.approximation = "exact": only the mean F_0 is kept (the periodic system's A₀ and B need
  // no more); the time variation is the PulseTrain's own F(t), in exact_pulse_monodromy
  // (pulse_monodromy.hpp). The Fourier methods must not be run on such a series.
  bool exact_pulse = false;
  double exact_peak_n = 0;  // exact_pulse: F_max, the most compressive load of the period
  bool frequency_known = true;
  int harmonics() const { return static_cast<int>(coefficients.size()) - 1; }
  double value(double t) const;  // the series at time t [N]
  // The most compressive force of the series over a period (≤ 0 for a pulse train) [N], from
  // 64 samples per highest harmonic; −F_max for the exact pulse.
  double minimum() const;
};

// The cosine approximation (42): −F_max/2 + (F_max/2) cos θt, i.e. F_0 = −F_max/2, F_1 = F_max/4.
LoadSeries cosine_approximation(const PulseTrain& train);

// The true pulse's series with the fewest harmonics M ≤ max_harmonics whose relative L2 tail is
// at most `relative_tail` (the impulse has no convergent series: InputError).
LoadSeries fourier_series(const PulseTrain& train, double relative_tail, int max_harmonics);

// The mean F_0 of the true pulse only, for load.approximation = "exact" (any profile, the impulse too).
LoadSeries exact_pulse_mean(const PulseTrain& train);

// What the scene's load.approximation asks for.
LoadSeries load_series(const Scene& scene, double relative_tail = 1e-2, int max_harmonics = 200);

// The analyses that answer for the continuum blade (stability, map, boundaries, check) refuse
// load.profile = "impulse" with load.approximation = "exact" (InputError): the velocity jump kicks
// every Ritz mode alike, so its multipliers have no limit as the terms grow (docs/theory.md §3.5).
void refuse_impulse_jump(const Scene& scene);

}  // namespace bladestab
