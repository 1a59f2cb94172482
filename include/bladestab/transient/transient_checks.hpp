#pragma once
// Whether a transient is a result or an artefact: its energy balance (docs/theory.md §5, (55)–(58)), which the
// Runge–Kutta steps do not preserve by construction and so cannot fake, and the range of the linear
// small-deflection model (docs/theory.md §1). A run failing either is an error, not a result.
#include <optional>
#include <string>

#include "bladestab/transient/transient.hpp"

namespace bladestab {

struct TransientChecks {
  double energy_error_j = 0;      // max |E(t) − E(0) − W(t)| over the samples
  double vibration_energy_j = 0;  // max (E(0) − E_eq + W(t)): the largest vibration energy the balance allows
  double energy_rounding_j = 0;   // the balance's rounding: 100 ε of the size of E's terms (energy_terms_j)
  double peak_lateral_m = 0;      // max |v(L)|
  double peak_axial_change_m = 0; // max |u(L) − u_eq(L)|
  // Limits. Energy: 1 % of the vibration energy, ≈ 0.5 % of an amplitude, the run's own error far above
  // any tolerance the stepper was given. Deflection: a lateral tip deflection of 0.1 L tilts the tip by
  // ≈ 0.15 rad, where the small-slope geometry (½∫v'², sin ψ ≈ ψ) no longer holds; an axial change of
  // 0.01 L is a mean strain of 1 %, past the elastic limit of blade alloys (titanium yields near 0.8 %).
  static constexpr double max_energy_error = 1e-2, max_lateral_over_length = 0.1, max_axial_strain = 1e-2;
};

TransientChecks check_transient(const TransientResult& result);

// The first failed check, in one phrase; `integration`: the energy balance (the steps are at fault),
// else the deflection (the response left the model).
struct TransientFailure {
  bool integration = false;
  std::string what;
};
std::optional<TransientFailure> transient_failure(const TransientChecks& checks, double blade_length_m);

}  // namespace bladestab
