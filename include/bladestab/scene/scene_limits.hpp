#pragma once
// The allowed ranges of the scene's numbers. Each is wide enough for any real blade, from a model
// fan to a wind-turbine rotor, and narrow enough that what is derived from it (ω², F_cr, the
// Rayleigh coefficients, the pulse's harmonics, the Magnus exponents) stays well inside the double
// range: a Young's modulus of 1e-308 makes every frequency 0 and NaN appear, one of 1e308 crashes
// the boundary eigensolver. A program's parameters that stand for the same quantities (speeds, pulse
// frequencies, loads, cut-offs) take the same ranges.
#include "bladestab/scene/allowed_range.hpp"

namespace bladestab::scene_limits {

inline const AllowedRange length_m = AllowedRange::closed(1e-3, 1e3);
inline const AllowedRange hub_radius_m = AllowedRange::closed(0, 1e3);
inline const AllowedRange area_m2 = AllowedRange::closed(1e-10, 1e2);
// d̄ = sqrt(I/(A L²)): a thin plate of thickness L/3000 to a stub; blade.inertia must give one too.
inline const AllowedRange slenderness = AllowedRange::below(1e-4, 1);
inline const AllowedRange youngs_modulus_pa = AllowedRange::closed(1e5, 1e13);   // soft rubber to past diamond
inline const AllowedRange density_kg_m3 = AllowedRange::closed(1, 1e5);          // foams to past osmium
inline const AllowedRange poisson = AllowedRange::open(-1, 0.5);
// κ: 5/6 for a rectangle, about a half for thin-walled and I sections; towards 0 the shear stiffness
// vanishes and the Timoshenko model with it.
inline const AllowedRange shear_coefficient = AllowedRange::closed(0.05, 1);
inline const AllowedRange stagger_deg = AllowedRange::closed(-90, 90);
inline const AllowedRange speed_rad_s = AllowedRange::closed(0, 1e5);            // ~1e6 rpm
// F_a / F_cr: far above the static buckling load of any blade spinning below its own divergence (the
// paper blade buckles at 0.999 F_cr at rest, 4.95 F_cr at 300 rad/s).
inline const AllowedRange tip_compression_over_fcr = AllowedRange::below(0, 1000);
inline const AllowedRange damping_ratio = AllowedRange::below(0, 1);
// Rayleigh's β = 2ζ/(ω₁ + ω₂): below 1 mHz it outgrows any stiffness it multiplies.
inline const AllowedRange damping_frequency_hz = AllowedRange::closed(1e-3, 1e9);
inline const AllowedRange cutoff_hz = AllowedRange::above(0, 1e9);
inline const AllowedRange fmax_over_fcr = AllowedRange::closed(0, 1000);
// t̄_c: below a millionth of a revolution a pulse's series needs millions of harmonics.
inline const AllowedRange contact_time_rev = AllowedRange::closed(1e-6, 1);
inline const AllowedRange pulse_frequency_hz = AllowedRange::above(0, 1e8);
inline const AllowedRange pulse_angular_frequency_rad_s = AllowedRange::above(0, 1e9);  // θ = 2π f_p
inline const AllowedRange friction = AllowedRange::closed(0, 2);
inline const AllowedRange clearance_m = AllowedRange::closed(0, 10);
inline const AllowedRange intrusion_m = AllowedRange::closed(0, 10);
inline const AllowedRange contact_stiffness_n_m = AllowedRange::closed(1e-3, 1e15);
// [requirements]: the operating range lies within speed_rad_s; engine orders as pulses_per_rev.
inline constexpr long max_engine_order = 1000;
inline const AllowedRange frequency_margin = AllowedRange::open(0, 1);
inline const AllowedRange max_fmax_over_fcr = fmax_over_fcr;

}  // namespace bladestab::scene_limits
