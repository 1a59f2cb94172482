#pragma once
// Boundaries of the regions of dynamic instability (SPEC §4, (B.15)–(B.23)). On a boundary a
// Floquet multiplier sits at −1 (a 2T-periodic solution, odd harmonics of θ/2) or +1 (T-periodic,
// even harmonics). In modal coordinates η (q = Φη), with the ansatz η = Σ_{k∈S} c_k e^{ikθt/2},
//
//   [Λ + F₀Ĝ + i(kθ/2)Ĉ − (kθ/2)² I] c_k + Σ_{m≠0} F_m Ĝ c_{k−2m} = 0,   k ∈ S,
//
// S = {±1, ±3, …, ±(2K−1)} (−1) or {0, ±2, …, ±2K} (+1) for the K-th approximation. This is a
// quadratic eigenproblem in θ at fixed load (K = 1 is Bolotin's first approximation (B.15)) and,
// since every F_m is proportional to F_max, a linear one in F_max at fixed θ.
// Beyond the first approximation, a root whose eigenvector peaks in the highest harmonic kept is
// not resolved by the truncation and is dropped; raise the approximation to see high-order (thin)
// regions.
// Combination resonances (|ρ| leaving the unit circle away from ±1) are not boundaries of this
// kind; only the Floquet multipliers show them.
#include <vector>

#include "bladestab/periodic_system.hpp"

namespace bladestab {

struct Boundary {
  double theta_rad_s = 0;  // pulse angular frequency θ on the boundary
  double peak_force_n = 0; // F_max on the boundary
  int multiplier = -1;     // −1 or +1
  int mode = 0;            // 1-based index of the dominant mode
  int order = 0;           // n in θ ≈ 2ω_mode / n
};

// `system` supplies the modal matrices and the load shape; its load is scaled to `peak_force_n`.
// All boundary θ > 0 at that load, both families, sorted by θ.
std::vector<Boundary> boundary_frequencies(const PeriodicSystem& system, double peak_force_n, int approximation);

// All boundary F_max ≥ 0 at pulse frequency θ (the load shape per newton of F_max is the system's
// load divided by `system_peak_force_n`), both families, sorted by F_max.
std::vector<Boundary> boundary_loads(const PeriodicSystem& system, double system_peak_force_n, double theta_rad_s,
                                     int approximation);

}  // namespace bladestab
