#pragma once
// Does a blade design meet the [requirements] of its scene (scene.hpp) over its operating range
// [Ω_lo, Ω_hi]? Two requirements, each optional:
//
//  1. Campbell margin: every mode keeps |f(Ω) − kΩ/2π| ≥ margin · f(Ω) from every engine-order
//     line k inside the range. The modes that can come that near are those below
//     k_max·Ω_hi / (2π(1 − margin)) (f(1 − margin) < kΩ/2π is needed), at least the lowest one.
//     The Campbell diagram (campbell.hpp) follows them by shape with its tolerance-driven basis;
//     each curve's closest approach to each line is located on the continuous curve and evaluated
//     on the whole Ritz model (EngineOrderApproach).
//  2. Stability under rub: stable for every F̄_max ∈ [0, max_fmax_over_fcr] at every Ω of the
//     range, with θ = k·Ω (k = load.pulses_per_rev) and the scene's load and damping. The lowest
//     F̄ at which a region of instability opens (the onset) is scanned along the range from the
//     boundary eigenproblem in F̄_max (boundaries.hpp, docs/theory.md §4, (B.15)–(B.23)), refined around its
//     least value, and converged there with its error (boundaries_with_error_estimate,
//     instability_regions). Undamped, a region of order n touches F̄ = 0 at its tip θ = 2ω_m/n
//     (Bolotin): a tip inside the range means an onset of 0. The verdict is confirmed by the
//     Floquet multipliers (stability_analysis.hpp) at the worst speed: inside the lowest region
//     where the requirement fails, at max_fmax_over_fcr where it holds.
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "bladestab/blade/static_limits.hpp"
#include "bladestab/modal/campbell.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

// The range against the blade's static limits (static_limits.hpp) at the scene's static tip
// compression, on the Campbell margin's grid of speeds: a design that buckles or diverges inside
// its operating range fails. The other requirements are checked over the part within the limits.
struct StaticLimitsResult {
  bool passed = true;      // every speed of the range is within the limits
  PathWithinLimits path;   // over the grid; each limit's `where` in rad/s
  double speed_lo_rad_s = 0, speed_hi_rad_s = 0;  // the part of the range within the limits
};

// InputError naming requirements.speed_range_rad_s when fewer than two speeds of the grid are
// within the limits (nothing to check).
StaticLimitsResult check_static_limits(const Scene& scene);

struct FrequencyMarginResult {
  double required = 0;            // requirements.frequency_margin
  bool passed = false;            // worst.distance ≥ required
  EngineOrderApproach worst;      // the closest approach of a checked mode to a line; its distance is the margin
  double error_estimate = 0;      // absolute on the margin (EngineOrderApproach's budget)
  double threshold_hz = 0;        // the modes below it were checked
  int modes_checked = 0;
  int terms = 0;                  // shape functions per field of the curves' model
  double tolerance = 0;           // relative on every frequency
  int speeds = 0;                 // of the diagram over the range
  double speed_lo_rad_s = 0, speed_hi_rad_s = 0;  // the range checked: its part within the static limits
};

// `progress(done, total)` counts the diagram's speeds. `work_flops`: what the Campbell diagrams may
// take together (CampbellOptions::work_flops), each with more modes tracked than the one before.
FrequencyMarginResult check_frequency_margin(const Scene& scene, double tolerance,
                                             const std::function<void(int, int)>& progress = {},
                                             double work_flops = std::numeric_limits<double>::infinity());

struct RubStabilityResult {
  double required = 0;          // requirements.max_fmax_over_fcr
  bool passed = false;
  int pulses_per_rev = 1;       // θ = pulses_per_rev · Ω
  double window_fmax_over_fcr = 0;  // onsets are sought up to here (twice the requirement)
  int max_order = 4;            // regions of order n ≤ max_order (θ ≈ 2ω/n) are sought
  int speeds_scanned = 0;       // boundary eigenproblems solved along the range
  // The worst speed: where the onset is lowest (a tip's speed where there is one).
  double speed_rad_s = 0;
  std::optional<double> onset_fmax_over_fcr;  // unset: no region opens below the window's top
  double onset_error_estimate = 0;            // relative on the onset (0 at a tip, or not converged)
  // False where the lowest region opens at a boundary that did not converge in the harmonics
  // (BoundaryAnalysis::unconverged): the onset is its value at the highest k reached.
  bool onset_converged = true;
  int unconverged_boundaries = 0;             // at the worst speed, in the window (they still divide regions)
  int multiplier = 0, mode = 0, order = 0;    // the region that opens there
  bool tip = false;             // undamped: the region's tip θ = 2ω_m/n = kΩ lies in the range
  int approximation = 0;        // harmonics per multiplier sign of the converged boundaries
  // The Floquet check at (check_speed, check_fmax): inside the lowest region where the
  // requirement fails, at the required load where it holds.
  double check_speed_rad_s = 0, check_fmax_over_fcr = 0;
  double max_abs_multiplier = 0;
  bool check_stable = true;
  // Floquet answers at the requirement across the range where the check holds at the worst speed
  // (evenly, the ends included): the first unstable one becomes the check's.
  int floquet_speeds = 0;
  // Where the check's estimate stays above its tolerance (StabilityAnswer::tolerance_unmet): why.
  std::string check_tolerance_unmet;
  double speed_lo_rad_s = 0, speed_hi_rad_s = 0;  // the range checked: its part within the static limits
};

// `progress(done, total)` counts the speeds scanned. `work_flops`: the boundaries' work at the worst
// speed (BoundaryRequest::work_flops), and a quarter of it for the Floquet check there.
RubStabilityResult check_rub_stability(const Scene& scene, const std::function<void(int, int)>& progress = {},
                                       double work_flops = std::numeric_limits<double>::infinity());

}  // namespace bladestab
