#pragma once
// Frequency domain against time domain (docs/theory.md §5 "Cross-checks"), point by point in F̄_max at the
// scene's speed:
//  (a) max|ρ| from the Floquet multipliers against the growth per revolution of a long transient
//      under the same periodic load — once with the paper's cosine approximation (42), once with
//      the true pulse train (its Fourier series in the frequency domain);
//  (b) the monodromy matrix Φ(T) from the transient's RKF45 integrator against the Magnus one of
//      the frequency domain (cosine approximation);
//  (c) hence how wrong the cosine approximation is for the real, short pulse.
// The transients are the fast method's (transient.hpp) on the whole Ritz model, each checked
// against RKF45 through its first contact; each growth carries an error estimate (GrowthFit), and
// a point agrees when |growth − max|ρ|| is within the sum of the two estimates.
#include <functional>
#include <vector>

#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct CrosscheckPoint {
  double fmax_over_fcr = 0;
  // Paper's cosine approximation.
  double floquet_cosine = 0, floquet_cosine_error = 0, transient_cosine_growth = 0, transient_cosine_error = 0;
  double rkf45_max_abs_multiplier = 0;   // from the RKF45 monodromy at rtol 1e-8
  double monodromy_difference = 0;       // ‖Φ_RKF45 − Φ_Magnus‖ / ‖Φ_Magnus‖ (Frobenius)
  // True pulse train.
  // floquet_pulse_error: the series' monodromy's own error plus floquet_pulse_load_error, the
  // series' truncation: |max|ρ| − the true train's max|ρ|| plus that one's error.
  double floquet_pulse = 0, floquet_pulse_error = 0, transient_pulse_growth = 0, transient_pulse_error = 0;
  double floquet_pulse_load_error = 0;
  int pulse_harmonics = 0;
  double pulse_series_tail = 0;
  // The Floquet multipliers are per load period, the transient growth per revolution: a revolution
  // holds this many load periods (load.pulses_per_rev), and the growth is compared as its root.
  double load_periods_per_revolution = 1;
  bool cosine_agrees() const;
  bool pulse_agrees() const;
};

struct CrosscheckOptions {
  std::vector<double> fmax_over_fcr{1, 2, 5, 10};
  double revolutions = 16;
  double tolerance = 1e-6;  // Floquet; the transients run at 1e-8
  int threads = 1;          // points side by side (the answer does not depend on it)
  std::function<void(int, int)> progress;
};

std::vector<CrosscheckPoint> crosscheck(const Scene& scene, const CrosscheckOptions& options);

}  // namespace bladestab
