#pragma once
// The boundary equations of the regions of dynamic instability of an LTP system stated in modal
// form (linear_periodic_system.hpp; docs/theory.md §4, the paper's (B.15)–(B.23)). On a boundary a
// Floquet multiplier sits at −1 (a 2T-periodic solution, odd harmonics of θ/2) or +1 (T-periodic,
// even harmonics). With the ansatz η = Σ_{k∈S} c_k e^{ikθt/2},
//
//   [Λ + f₀G + i(kθ/2)C − (kθ/2)² I] c_k + Σ_{m≠0} f_m G c_{k−2m} = 0,   k ∈ S,
//
// S = {±1, ±3, …, ±(2K−1)} (−1) or {0, ±2, …, ±2K} (+1) for the K-th approximation. This is a
// quadratic eigenproblem in θ at a fixed amplitude (K = 1 is Bolotin's first approximation (B.15)) and,
// since every f_m is proportional to the amplitude, a linear one in the amplitude at fixed θ.
// Beyond the first approximation, a root whose eigenvector peaks in the highest harmonic kept is
// not resolved by the truncation and is dropped; raise the approximation to see high-order (thin)
// regions.
// Combination resonances (|ρ| leaving the unit circle away from ±1) are not boundaries of this
// kind; only the Floquet multipliers show them.
#include <limits>
#include <optional>
#include <vector>

#include "bladestab/ltp/linear_periodic_system.hpp"

namespace bladestab {

struct Boundary {
  double theta_rad_s = 0;  // the coefficient's angular frequency θ on the boundary
  double peak_force_n = 0; // its amplitude on the boundary (the blade: the tip load's F_max)
  int multiplier = -1;     // −1 or +1
  int mode = 0;            // 1-based index of the dominant mode
  int order = 0;           // n in θ ≈ 2ω_mode / n
};

// `system` (with its modal form) supplies the matrices and the coefficient's shape, at the amplitude
// `peak_force_n`. All boundary θ > 0 at that amplitude, sorted by θ: of both multiplier signs, or of the
// one whose multiplier is `multiplier_sign` (−1 or +1; each sign is its own eigenproblem, so one costs half).
std::vector<Boundary> boundary_frequencies(const LinearPeriodicSystem& system, double peak_force_n, int approximation,
                                           int multiplier_sign = 0);

// All boundary amplitudes ≥ 0 at the frequency θ (the system's coefficients are at the amplitude
// `system_peak_force_n`), sorted by amplitude; both signs or `multiplier_sign` as above.
std::vector<Boundary> boundary_loads(const LinearPeriodicSystem& system, double system_peak_force_n, double theta_rad_s,
                                     int approximation, int multiplier_sign = 0);

// |ρ − b.multiplier| for the Floquet multiplier ρ of `system` closest to ±1 at the boundary point
// (θ = b.theta_rad_s, amplitude b.peak_force_n; the system's is `system_peak_force_n`), from the
// monodromy matrix by Magnus steps, doubled (StepDoubling) until Φ(T) settles to `tolerance`
// relative to its largest entry: a check that shares nothing with the boundary eigenproblem. On a boundary it
// is 0; it grows like the square root of the distance from it. None where Φ(T) does not settle
// (or overflows) within max_magnus_steps or the steps `max_flops` affords (magnus_step_work).
struct MultiplierGap {
  std::optional<double> gap;
  double work = 0;  // of the Magnus steps taken (magnus_step_work)
};
MultiplierGap multiplier_gap(const LinearPeriodicSystem& system, double system_peak_force_n, const Boundary& b,
                             double tolerance, double max_flops = std::numeric_limits<double>::infinity());

}  // namespace bladestab
