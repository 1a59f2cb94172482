#include "bladestab/transient/transient_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace bladestab {

TransientChecks check_transient(const TransientResult& r) {
  TransientChecks c;
  c.energy_rounding_j = 100 * std::numeric_limits<double>::epsilon() * r.energy_terms_j;
  for (const TransientSample& s : r.samples) {
    // std::max would drop a NaN; a failed run must not pass for a quiet one.
    const auto worst = [](double& m, double x) { m = (std::isnan(x) || x > m) ? x : m; };
    worst(c.energy_error_j, std::abs(s.energy_balance_error_j));
    worst(c.vibration_energy_j, r.initial_vibration_energy_j + s.work_j);
    worst(c.peak_lateral_m, std::abs(s.tip_lateral_m));
    worst(c.peak_axial_change_m, std::abs(s.tip_axial_m - r.static_tip_axial_m));
  }
  return c;
}

std::optional<TransientFailure> transient_failure(const TransientChecks& c, double L) {
  // Written as !(x ≤ limit) so that NaN fails. A vibration far below the static energy (a feather
  // touch) is checked down to the rounding of E itself.
  if (!(c.energy_error_j <= TransientChecks::max_energy_error * c.vibration_energy_j + c.energy_rounding_j)) {
    return TransientFailure{true, fmt::format("the energy balance broke: E(t) − E(0) − W(t) reached {:.3g} J against a vibration energy of "
                       "{:.3g} J (allowed {:g} of it and E's rounding, {:.2g} J)",
                       c.energy_error_j, c.vibration_energy_j, TransientChecks::max_energy_error, c.energy_rounding_j)};
  }
  if (!(c.peak_lateral_m <= TransientChecks::max_lateral_over_length * L)) {
    return TransientFailure{false, fmt::format("the lateral tip deflection reached {:.3g} m = {:.3g} L, beyond the small-deflection model "
                       "(allowed {:g} L)",
                       c.peak_lateral_m, c.peak_lateral_m / L, TransientChecks::max_lateral_over_length)};
  }
  if (!(c.peak_axial_change_m <= TransientChecks::max_axial_strain * L)) {
    return TransientFailure{false, fmt::format("the axial tip deflection changed by {:.3g} m, a mean strain of {:.3g}, beyond the elastic "
                       "model (allowed {:g})",
                       c.peak_axial_change_m, c.peak_axial_change_m / L, TransientChecks::max_axial_strain)};
  }
  return std::nullopt;
}

}  // namespace bladestab
