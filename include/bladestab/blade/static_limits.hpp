#pragma once
// The blade's static limits (docs/theory.md §2): the operating points where its stiffness
//
//   K(Ω, F) = K_E + Ω² K_C1 + F G      (F the static tip force, tension positive)
//
// is positive definite. Past them the blade has no stable static equilibrium to vibrate about:
// its lowest frequency has fallen to zero and its static deflection has no meaning. Two limits:
//
//   spin divergence  K_E + Ω² K_C1 is indefinite without any tip force: the spin softening −ρAΩ²
//                    of a field outweighs its stiffness; for the axial field of a uniform blade
//                    above Ω_d = (π/2)·sqrt(E/ρ)/L, where EA u'' + ρAΩ² u = 0 first has a root;
//   buckling         K_E + Ω² K_C1 is positive definite and the static compression −F makes
//                    K indefinite: above F_b(Ω) = 1/μ_max of G x = μ (K_E + Ω² K_C1) x.
//
// Every command asks here: one at a single operating point refuses a point past a limit
// (static_limit_error, exit 2 in the program), one over a range of points computes up to the
// limit and says where it lies (path_within_limits). A periodic load's mean is a static force
// too: an analysis that asks whether the blade is buckled under it asks static_margin.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/model.hpp"

namespace bladestab {

enum class StaticLimitKind { spin_divergence, buckling };

// The weakest direction's share of the elastic stiffness at (Ω, F): the least eigenvalue μ of
// K(Ω, F) x = μ K_E x. It is 1 for the unloaded blade at rest, positive within the limits, zero
// on them and negative past them, and continuous in Ω, F and every property of the blade, so each
// limit is a root of it. Concave in Ω² and in F (a least value of functions linear in them), so
// along either the points within the limits form one interval. `tip_force_n` is on top of the
// model's static tip force, as in BladeModel::stiffness.
double static_margin(const BladeModel& model, double speed_rad_s, double tip_force_n = 0);

// A limit: which, the field whose weakest direction gives way ("axial", "lateral" or "rotation",
// by its share of the mass in that direction), and where it lies (what `where` is depends on who
// gives it).
struct StaticLimit {
  StaticLimitKind kind = StaticLimitKind::buckling;
  std::string field;
  double where = 0;
};

// The compression [N] under which the blade buckles at speed Ω: F_b = 1/μ_max of
// G x = μ (K_E + Ω² K_C1) x, a generalized eigenvalue (G ≥ 0, zero on θ and u). None when the
// blade diverges at Ω without any compression.
std::optional<double> static_buckling_load(const BladeModel& model, double speed_rad_s);

// None within the limits. Past them, which limit, and `where`: for spin divergence the speed
// [rad/s] above which the unloaded blade diverges (the root of static_margin at no tip force
// between rest and Ω), for buckling the compression [N] under which it buckles at Ω.
std::optional<StaticLimit> static_limit_at(const BladeModel& model, double speed_rad_s, double tip_force_n = 0);

// The one-line refusal of an operating point at speed Ω (named `speed_key`, e.g.
// "operation.speed_rad_s") past a limit, with the model's static compression: the keys to change
// and where the limit lies. None within the limits.
std::optional<InputError> static_limit_error(const BladeModel& model, double speed_rad_s,
                                             const std::string& speed_key = "operation.speed_rad_s");

// A path of operating points against the limits: the values of one parameter (the speeds of a
// Campbell diagram, the values of a swept scene key), monotonic, in the order given. The run of
// values within the limits starts at the first one within and ends before the next one past; the
// path's limits, either side of the run, lie where static_margin along the path is zero, found by
// root search (TOMS 748) between the last value on one side and the first on the other.
struct PathWithinLimits {
  std::size_t first = 0, end = 0;    // values [first, end) are within; first == end: none is
  std::optional<StaticLimit> before; // values before `first` are past it; `where` is the parameter
  std::optional<StaticLimit> after;  // the path meets it after value end − 1 and stops there
  bool empty() const { return first == end; }
};

// `margin(v)`: static_margin at the path's point v; `limit(v)`: static_limit_at there (called
// only where the margin is not positive). A parameter that is not `continuous` (one that takes
// integers only) has no root between its values: there `where` is the first value past.
PathWithinLimits path_within_limits(const std::vector<double>& values, const std::function<double(double)>& margin,
                                    const std::function<std::optional<StaticLimit>(double)>& limit,
                                    bool continuous = true);

// The path of `speeds` [rad/s] at the model's static tip force.
PathWithinLimits speeds_within_limits(const BladeModel& model, const std::vector<double>& speeds);

// The path's limits in one clause, e.g. "the blade buckles under its static tip compression below
// 212.4 rad/s and diverges (its axial field's spin softening) above 8040.6 rad/s"; `value(v)`
// words a parameter value ("212.4 rad/s", "operation.tip_compression_over_fcr = 0.99923"). Empty
// when the path meets no limit.
std::string describe_path_limits(const PathWithinLimits& path, bool ascending,
                                 const std::function<std::string(double)>& value);

const char* to_string(StaticLimitKind kind);

}  // namespace bladestab
