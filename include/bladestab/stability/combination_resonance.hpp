#pragma once
// Which modes a combination resonance couples (docs/theory.md §4: multipliers leaving the unit circle as a
// complex pair, away from ±1). A parametric load of frequency θ couples two modes i < j where
//   sum type:         ω_i + ω_j ≈ nθ,
//   difference type:  ω_j − ω_i ≈ nθ (gyroscopic systems),
// ω the natural frequencies under the mean load. Inside such a region the two modes lock: with the
// detuning δ = ω_i ± ω_j − nθ their Floquet exponents share Im λ = ω_i − δ/2 (sum) or ω_i + δ/2
// (difference), modulo θ, so the unstable multiplier's phase is that times the period. That phase
// fixes ω_i only modulo θ, and several combinations can fit it (on the paper blade at F̄ = 6.25,
// θ = 750 rad/s both (ω₁ + ω₂)/2 and (ω₃ − ω₁)/4); the combination named is the one of lowest
// order n whose predicted phase matches the multiplier's (a tongue of order n opens like F̄ⁿ),
// then of least |δ|.
#include <complex>
#include <optional>

#include <Eigen/Dense>

namespace bladestab {

struct Combination {
  int mode_i = 0, mode_j = 0;  // 1-based, i < j, in the order of the mean-load frequencies
  bool sum = true;             // ω_i + ω_j (true) or ω_j − ω_i
  int order = 1;               // n
  double detuning = 0;         // δ / θ
};

// `omega`: the lowest natural frequencies [rad/s] at the mean load, ascending; `theta` the load's
// angular frequency; `rho` the unstable multiplier (complex). Combinations of orders 1 … max_order
// with |δ| ≤ θ/10 and a phase within `phase_tolerance` radians of arg ρ (either sign: ρ̄ is one
// too); none where no combination fits.
std::optional<Combination> nearest_combination(const Eigen::VectorXd& omega, double theta, std::complex<double> rho,
                                               int max_order, double phase_tolerance = 0.2);

}  // namespace bladestab
