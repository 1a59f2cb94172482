#pragma once
// Frequency domain against time domain (docs/theory.md §5 "Cross-checks"), point by point in F̄_max at the
// scene's speed:
//  (a) max|ρ| from the Floquet multipliers against the growth per revolution of a long transient
//      under the same periodic load — once with the paper's cosine approximation (42), once with
//      the true pulse train (its monodromy through each contact);
//  (b) the monodromy matrix Φ(T) from the transient's RKF45 integrator against the Magnus one of
//      the frequency domain (cosine approximation);
//  (c) hence how wrong the cosine approximation is for the real, short pulse.
// Each transient is the fast method's (transient.hpp) on the model its Floquet multipliers use:
// the scene's reduction for the cosine approximation, the model `stability` analyses the true
// train on for the pulse (the whole Ritz model where it affords it); each is checked against an
// independent integration through its first contact, each growth carries an error estimate
// (GrowthFit), and a point agrees when |growth − max|ρ|| is within the sum of the two estimates.
#include <functional>
#include <string>
#include <vector>

#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct CrosscheckPoint {
  double fmax_over_fcr = 0;
  // Paper's cosine approximation.
  double floquet_cosine = 0, floquet_cosine_error = 0, transient_cosine_growth = 0, transient_cosine_error = 0;
  double rkf45_max_abs_multiplier = 0;   // from the RKF45 monodromy at rtol 1e-8
  double monodromy_difference = 0;       // ‖Φ_RKF45 − Φ_Magnus‖ / ‖Φ_Magnus‖ (Frobenius)
  // True pulse train: its multipliers by the monodromy through each contact.
  double floquet_pulse = 0, floquet_pulse_error = 0, transient_pulse_growth = 0, transient_pulse_error = 0;
  // GrowthFit::omitted of each transient: why its growth fit is not meaningful (empty: it is). A
  // row whose growth is not resolved does not agree.
  std::string transient_cosine_omitted, transient_pulse_omitted;
  // The Floquet multipliers are per load period, the transient growth per revolution: a revolution
  // holds this many load periods (load.pulses_per_rev), and the growth is compared as its root.
  double load_periods_per_revolution = 1;
  // The modes each row's model keeps (PeriodicSystem::kept_modes): the cosine rows on the scene's
  // reduction, the pulse rows on the model `stability` takes for the true train (crosscheck.cpp).
  int cosine_modes = 0, pulse_modes = 0, model_modes = 0;  // model_modes: the whole Ritz model's dofs
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

// The Magnus work of crosscheck(scene, options) before it starts, in eigensolver flops
// (magnus_step_work): per point, the systems it integrates (the cosine load's on the scene's
// reduction, the true train's on the model `stability` takes for it; both built at the largest
// load) at twice the steps where h‖A‖₂ ≤ 2 (minimum_magnus_steps) for each ladder, the bound its
// ladders converge within.
double crosscheck_magnus_work(const Scene& scene, const CrosscheckOptions& options);

// Load periods T_p in a revolution: pulses_per_rev, unless load.pulse_frequency_hz sets T_p.
double load_periods_per_revolution(const Scene& scene);

}  // namespace bladestab
