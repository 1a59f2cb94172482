#pragma once
// Static buckling of the spinning blade under a constant tip compression F_a (Sinha's Fig. 9):
// the stiffness K_E + Ω² K_C1 − F_a G stops being positive definite, and the first bending
// frequency falls to zero there.
#include <optional>

#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/model.hpp"

namespace bladestab {

// The static tip compression F_b [N] at which the blade buckles at speed Ω: the smallest F_a that
// makes K_E + Ω² K_C1 − F_a G singular (K_E the elastic stiffness, without the model's own static
// force), F_b = 1/μ_max for the largest eigenvalue μ of G x = μ (K_E + Ω² K_C1) x. None when the
// blade is statically unstable at Ω without any compression (spin divergence).
std::optional<double> static_buckling_load(const BladeModel& model, double speed_rad_s);

// Nothing when `operation` has no static compression, or when the model's stiffness at its speed,
// that compression included, is positive definite; otherwise the InputError to throw, naming
// operation.tip_compression_over_fcr and the load at which this model buckles.
std::optional<InputError> static_instability(const BladeModel& model, const OperationSpec& operation);

}  // namespace bladestab
