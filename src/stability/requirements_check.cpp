#include "bladestab/stability/requirements_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "bladestab/blade/blade_properties.hpp"
#include "bladestab/stability/boundaries.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/stability/instability_regions.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "support/scalar_search.hpp"
#include "bladestab/stability/stability_analysis.hpp"

namespace bladestab {
namespace {

// Speeds of the Campbell diagram over the range, and of the onset's scan.
constexpr int margin_speeds = 201;
constexpr int scan_speeds = 41;
// Harmonics per multiplier sign of the scan's boundary equations (the converged analysis raises its own).
constexpr int scan_approximation = 4;
// Regions of order n ≤ this (θ ≈ 2ω/n) are sought: higher orders are thin tongues that any damping
// closes, and new ones appear with every harmonic (boundaries.hpp).
constexpr int sought_order = 4;
// Tolerance of the Floquet checks on max|ρ| (as instability_regions' middles).
constexpr double floquet_tolerance = 1e-4;

const RequirementsSpec& requirements_of(const Scene& scene) {
  if (!scene.requirements) throw InputError(fmt::format("{}: [requirements]: missing section", scene.source));
  return *scene.requirements;
}

// The scene at speed Ω with the pulses at θ = kΩ and the load F̄.
Scene at_speed(const Scene& scene, double speed, double fbar) {
  return scene_at(scene, speed, scene.load.pulses_per_rev * speed, fbar);
}

// The Floquet answer at (speed, F̄) with a verdict where one is to be had: the automatic reduction's,
// or, where its estimate leaves the verdict open, the whole Ritz model's (the reduction's part is
// fixed by its richest level: 8 terms at 129 rad/s, F̄ = 5 gave 1.0487 ± 0.095 on 3 vectors, 1 on
// the whole model).
StabilityAnswer decided_floquet(const Scene& scene, double speed, double fbar, double work_flops) {
  StabilityRequest floquet{FloquetMethod::automatic, 0, floquet_tolerance};
  floquet.work_flops = work_flops;
  Scene at = at_speed(scene, speed, fbar);
  StabilityAnswer answer = analyse_stability(at, floquet);
  // Open: a growth above the rounding of |ρ| = 1, but within the estimate.
  const double growth = answer.floquet.max_abs_multiplier - 1;
  const bool open = growth > 1e-9 && growth <= answer.budget.total();
  if (!open || at.model.reduction.kind == ReductionKind::none) return answer;
  at.model.reduction = {ReductionKind::none, 0, 0};
  return analyse_stability(at, floquet);
}

// Speeds of the Floquet sweep at the requirement across the range: the regions sought end at an
// order, and a thin region of higher order opens where they do not look (mode 3, order 49, from
// F̄ = 3.8 at 130 rad/s on the paper blade).
constexpr int floquet_sweep_speeds = 9;

// The least F̄ of a boundary of order ≤ sought_order at speed Ω with θ = kΩ (the first one met
// going up from the stable unloaded blade opens a region), from the boundary equations along F̄
// on the automatic reduction of `vectors` modes per load level; `window` where there is none up
// to it.
struct Onset {
  double fbar = 0;
  int multiplier = 0, mode = 0, order = 0;
};
Onset scanned_onset(const Scene& scene, const BladeModel& model, int vectors, double speed, double window) {
  const double fcr = model.blade.critical_load(), theta = scene.load.pulses_per_rev * speed;
  const Scene at = at_speed(scene, speed, window);
  const PeriodicSystem sys =
      periodic_system(model, at, load_series(at), {ReductionKind::automatic, vectors, 0});
  Onset onset{window};
  for (const Boundary& b : boundary_loads(sys, window * fcr, theta, scan_approximation)) {
    const double fbar = b.peak_force_n / fcr;
    if (b.order <= sought_order && fbar < onset.fbar) onset = {fbar, b.multiplier, b.mode, b.order};
  }
  return onset;
}

// A tip of an undamped region: 2ω_m(Ω)/n = kΩ (docs/theory.md §4: principal regions at θ ≈ 2ω/n).
struct Tip {
  double speed = 0;
  int mode = 0, order = 0;
};

// The tips inside [lo, hi] for orders n ≤ sought_order, on the undamped gyroscopic frequencies of
// the whole Ritz model (the boundary equations' own at F = 0). The m-th frequency in order of size
// is continuous in Ω, so each sign change of 2ω_m − nkΩ on `speeds` brackets a tip.
std::vector<Tip> undamped_tips(const Scene& scene, const BladeModel& model, const std::vector<double>& speeds) {
  const int k = scene.load.pulses_per_rev;
  const double lo = speeds.front(), hi = speeds.back();
  const Eigen::MatrixXd no_damping = Eigen::MatrixXd::Zero(model.M.rows(), model.M.cols());
  const auto omegas = [&](double speed, int count) {
    const ModalSolution s = solve_modes(model, system_at(model, speed, no_damping), speed, count, EigenSolverKind::dense);
    std::vector<double> w;
    for (const Mode& m : s.modes) w.push_back(two_pi * m.frequency_hz);
    return w;
  };
  // A tip needs ω_m = nkΩ/2 ≤ sought_order·k·Ω_hi/2: the modes below that at either end.
  const double highest = sought_order * k * hi / 2;
  int count = 0;
  for (double speed : {lo, hi}) {
    const std::vector<double> w = omegas(speed, 0);
    count = std::max(count, static_cast<int>(std::count_if(w.begin(), w.end(), [&](double x) { return x <= highest; })));
  }
  std::vector<Tip> tips;
  if (count == 0) return tips;
  std::vector<std::vector<double>> at;
  for (double speed : speeds) at.push_back(omegas(speed, count));
  for (int m = 0; m < count; ++m) {
    for (int n = 1; n <= sought_order; ++n) {
      const auto gap = [&](double speed) { return 2 * omegas(speed, count)[m] - n * k * speed; };
      for (std::size_t s = 0; s + 1 < speeds.size(); ++s) {
        const double g0 = 2 * at[s][m] - n * k * speeds[s], g1 = 2 * at[s + 1][m] - n * k * speeds[s + 1];
        if (g0 == 0) tips.push_back({speeds[s], m + 1, n});
        if ((g0 < 0 && g1 > 0) || (g0 > 0 && g1 < 0)) {
          tips.push_back({bracketed_root(gap, speeds[s], g0, speeds[s + 1], g1), m + 1, n});
        }
        if (s + 2 == speeds.size() && g1 == 0) tips.push_back({speeds[s + 1], m + 1, n});
      }
    }
  }
  return tips;
}

// `count` speeds from lo to hi, the last exactly hi.
std::vector<double> speed_grid(double lo, double hi, int count) {
  std::vector<double> speeds(count);
  for (int s = 0; s < count; ++s) speeds[s] = s + 1 == count ? hi : lo + (hi - lo) * s / (count - 1);
  return speeds;
}

// The worst speed of the range for the stability requirement: the least onset along a scan of
// evenly spaced speeds, or, undamped, the lowest-order tip inside the range (onset 0), refined by a
// search on the continuous scan around it. `progress` after each scanned speed.
struct WorstSpeed {
  double speed = 0;
  std::optional<Tip> tip;
  int scanned = 0;  // speeds scanned
};
WorstSpeed worst_speed(const Scene& scene, const BladeModel& model, int vectors, double lo, double hi,
                       double window, const std::function<void(int, int)>& progress) {
  // The scan along the range.
  const std::vector<double> speeds = speed_grid(lo, hi, scan_speeds);
  std::vector<Onset> onsets(scan_speeds);
  for (int s = 0; s < scan_speeds; ++s) {
    onsets[s] = scanned_onset(scene, model, vectors, speeds[s], window);
    if (progress) progress(s + 1, scan_speeds);
  }
  const double step = (hi - lo) / (scan_speeds - 1);
  // Undamped, a tip inside the range is the worst point (onset 0); the lowest order first.
  std::optional<Tip> tip;
  if (!scene.damping.damped()) {
    for (const Tip& t : undamped_tips(scene, model, speeds)) {
      if (!tip || t.order < tip->order || (t.order == tip->order && t.mode < tip->mode)) tip = t;
    }
  }
  // The least onset, refined on the continuous scan around the tip or the scan's least point.
  const double centre =
      tip ? tip->speed
          : speeds[std::min_element(onsets.begin(), onsets.end(),
                                    [](const Onset& a, const Onset& b) { return a.fbar < b.fbar; }) - onsets.begin()];
  const double a = std::max(lo, centre - step), b = std::min(hi, centre + step);
  const double refined = golden_minimum(
      [&](double speed) { return scanned_onset(scene, model, vectors, speed, window).fbar; }, a, b, 1e-6 * step);
  return {refined, tip, scan_speeds + 1};
}

// The onset the requirement reports: a tip's (at F̄ = 0, of its mode and order), else the lowest
// region's lower edge with its error estimate.
void name_onset(RubStabilityResult& r, const std::optional<Tip>& tip, const InstabilityRegion* lowest,
                const BoundaryAnalysis& analysis, double fcr) {
  if (tip) {
    r.tip = true;
    r.onset_fmax_over_fcr = 0;
    r.mode = tip->mode;
    r.order = tip->order;
    r.multiplier = tip->order % 2 == 1 ? -1 : 1;  // odd orders: 2T-periodic (−1); even: T-periodic (+1)
  } else if (lowest) {
    r.onset_fmax_over_fcr = lowest->lower / fcr;
    r.mode = lowest->mode;
    r.order = lowest->order;
    r.multiplier = lowest->multiplier;
    r.onset_converged = !lowest->lower_unconverged;
    for (const EstimatedBoundary& e : analysis.boundaries) {
      if (e.boundary.peak_force_n == lowest->lower) r.onset_error_estimate = e.budget.total();
    }
  }
}

}  // namespace

StaticLimitsResult check_static_limits(const Scene& scene) {
  const RequirementsSpec& req = requirements_of(scene);
  const std::vector<double> speeds = speed_grid(req.speed_lo_rad_s, req.speed_hi_rad_s, margin_speeds);
  const BladeModel model = assemble_model_at_any_speed(scene, scene.model);
  StaticLimitsResult r;
  r.path = speeds_within_limits(model, speeds);
  if (r.path.end - r.path.first < 2) {
    // A speed past a limit: the first of the grid, or the one next to the single speed within.
    const std::size_t next = r.path.empty() || r.path.first == 0 ? r.path.end : r.path.first - 1;
    const double past = speeds[next == speeds.size() ? 0 : next];
    throw InputError(fmt::format("requirements.speed_range_rad_s = [{:g}, {:g}]: {} of its {} speeds checked is "
                                 "within the blade's static limits; {}",
                                 req.speed_lo_rad_s, req.speed_hi_rad_s, r.path.empty() ? "none" : "only one",
                                 margin_speeds, static_limit_error(model, past, "Ω")->what()));
  }
  r.passed = !r.path.before && !r.path.after;
  r.speed_lo_rad_s = speeds[r.path.first];
  r.speed_hi_rad_s = speeds[r.path.end - 1];
  return r;
}

FrequencyMarginResult check_frequency_margin(const Scene& scene, double tolerance,
                                             const std::function<void(int, int)>& progress, double work_flops) {
  const RequirementsSpec& req = requirements_of(scene);
  if (!req.frequency_margin) throw InputError(fmt::format("{}: requirements.frequency_margin: missing", scene.source));
  const StaticLimitsResult within = check_static_limits(scene);
  FrequencyMarginResult result;
  result.required = *req.frequency_margin;
  result.tolerance = tolerance;
  result.speeds = margin_speeds;
  result.speed_lo_rad_s = within.speed_lo_rad_s;
  result.speed_hi_rad_s = within.speed_hi_rad_s;
  const int k_max = *std::max_element(req.engine_orders.begin(), req.engine_orders.end());
  // |f − kΩ/2π| < margin·f needs f < kΩ/(2π(1 − margin)).
  result.threshold_hz = k_max * result.speed_hi_rad_s / (two_pi * (1 - result.required));
  CampbellOptions options;
  options.speeds_rad_s = speed_grid(result.speed_lo_rad_s, result.speed_hi_rad_s, margin_speeds);
  options.engine_orders = req.engine_orders;
  options.closest_approaches = true;
  int dofs = dof_layout(scene.model, scene.blade.two_planes()).size();
  // Track more modes until the highest one tracked stays above the threshold over the whole range.
  // A point where the mode does not oscillate (overdamped, 0 Hz: the paper's damping (37) on the
  // stiff modes) meets no engine-order line: the lowest frequency is over the points that
  // oscillate, and a mode overdamped throughout is above every threshold, as are the stiffer ones
  // after it (by |λ|, modes.cpp), whose damping is heavier still.
  const int resolvable = resolvable_mode_count(scene.blade, scene.model);
  for (int count = std::min({4, dofs, resolvable});; count = std::min({2 * count, dofs, resolvable})) {
    options.mode_count = count;
    options.work_flops = work_flops;
    const CampbellWithErrors campbell = campbell_with_error_estimate(scene, options, tolerance, progress);
    work_flops -= campbell.work_flops;
    const auto lowest = [](const CampbellCurve& c) {
      double least = std::numeric_limits<double>::infinity();
      for (double f : c.frequency_hz) {
        if (f > 0) least = std::min(least, f);
      }
      return least;
    };
    const std::vector<CampbellCurve>& curves = campbell.diagram.curves;
    // The diagram's model has the terms raised to the tolerance: as many modes as its dofs.
    dofs = dof_layout(campbell.model.spec, scene.blade.two_planes()).size();
    if (lowest(curves.back()) < result.threshold_hz && count < dofs) {
      if (count < resolvable) continue;
      throw InputError(fmt::format("requirements.engine_orders: the margin to engine order {} needs every mode below "
                                   "{:.6g} Hz, more than the {} modes that raising the terms can resolve",
                                   k_max, result.threshold_hz, resolvable));
    }
    std::vector<int> checked;  // the curves below the threshold, at least the lowest
    for (const CampbellCurve& c : curves) {
      if (lowest(c) < result.threshold_hz || checked.empty()) checked.push_back(c.mode);
    }
    result.modes_checked = static_cast<int>(checked.size());
    result.terms = campbell.model.spec.terms;
    bool found = false;
    for (std::size_t a = 0; a < campbell.diagram.approaches.size(); ++a) {
      const EngineOrderApproach& x = campbell.diagram.approaches[a];
      if (std::find(checked.begin(), checked.end(), x.mode) == checked.end()) continue;
      if (!found || x.distance < result.worst.distance) {
        result.worst = x;
        result.error_estimate = campbell.approach_budget[a].total();
        found = true;
      }
    }
    if (!found) {
      throw NumericalError("frequency margin: no checked mode oscillates inside the speed range (all overdamped)");
    }
    result.passed = result.worst.distance >= result.required;
    return result;
  }
}

RubStabilityResult check_rub_stability(const Scene& scene, const std::function<void(int, int)>& progress,
                                       double work_flops) {
  const RequirementsSpec& req = requirements_of(scene);
  if (!req.max_fmax_over_fcr) throw InputError(fmt::format("{}: requirements.max_fmax_over_fcr: missing", scene.source));
  if (scene.load.approximation == LoadApproximation::exact) {
    throw InputError(fmt::format("{}: load.approximation = \"exact\": the stability requirement needs the load as a "
                                 "series for its boundary equations; use \"cosine\" or \"fourier\"", scene.source));
  }
  const StaticLimitsResult within = check_static_limits(scene);
  RubStabilityResult r;
  r.required = *req.max_fmax_over_fcr;
  r.pulses_per_rev = scene.load.pulses_per_rev;
  r.max_order = sought_order;
  r.window_fmax_over_fcr = 2 * r.required;
  r.speed_lo_rad_s = within.speed_lo_rad_s;
  r.speed_hi_rad_s = within.speed_hi_rad_s;
  r.speed_rad_s = r.speed_lo_rad_s;
  if (r.required == 0) {  // only the unloaded blade: nothing can open a region
    r.passed = true;
    return r;
  }
  const double lo = r.speed_lo_rad_s, hi = r.speed_hi_rad_s, window = r.window_fmax_over_fcr;
  const BladeModel model = assemble_model_at_any_speed(scene, scene.model);
  const double fcr = model.blade.critical_load();
  const int vectors = tongue_vectors(model, at_speed(scene, lo, 0), r.pulses_per_rev * hi, sought_order);

  const WorstSpeed worst_at = worst_speed(scene, model, vectors, lo, hi, window, progress);
  const std::optional<Tip>& tip = worst_at.tip;
  const double worst_speed = worst_at.speed;
  r.speeds_scanned = worst_at.scanned;

  // The onset there, converged with its error; each candidate region checked by Floquet.
  const Scene worst = at_speed(scene, worst_speed, window);
  BoundaryRequest request;
  request.theta_rad_s = r.pulses_per_rev * worst_speed;
  request.window = std::make_pair(0.0, window * fcr);
  request.max_order = sought_order;
  request.work_flops = work_flops;
  const BoundaryAnalysis analysis = boundaries_with_error_estimate(worst, request);
  const std::vector<InstabilityRegion> regions = instability_regions(worst, request, analysis, floquet_tolerance);
  r.approximation = analysis.approximation;
  r.unconverged_boundaries = static_cast<int>(analysis.unconverged.size());
  r.check_speed_rad_s = worst_speed;
  r.speed_rad_s = tip ? tip->speed : worst_speed;
  const InstabilityRegion* lowest = regions.empty() ? nullptr : &regions.front();  // sorted by their lower end
  name_onset(r, tip, lowest, analysis, fcr);
  const bool onset_within = r.onset_fmax_over_fcr && *r.onset_fmax_over_fcr <= r.required;
  // Floquet: inside the lowest region (below the requirement) where it fails, at the requirement where it holds.
  if (onset_within && lowest) {
    r.check_fmax_over_fcr = 0.5 * (lowest->lower + std::min(lowest->upper, r.required * fcr)) / fcr;
  } else {
    r.check_fmax_over_fcr = r.required;
  }
  StabilityAnswer answer = decided_floquet(scene, worst_speed, r.check_fmax_over_fcr, work_flops / 4);
  // Where it holds there, across the range at the requirement (the first unstable speed is the check's).
  for (int k = 0; k < floquet_sweep_speeds && !onset_within && answer.stable && hi > lo; ++k) {
    const double speed = lo + (hi - lo) * k / (floquet_sweep_speeds - 1);
    StabilityAnswer there = decided_floquet(scene, speed, r.required, work_flops / (4 * floquet_sweep_speeds));
    ++r.floquet_speeds;
    if (!there.stable) answer = std::move(there), r.check_speed_rad_s = speed;
  }
  r.max_abs_multiplier = answer.floquet.max_abs_multiplier;
  r.check_stable = answer.stable;
  r.check_tolerance_unmet = answer.tolerance_unmet;
  // A tip is certain (the region's edges meet F̄ = 0 there); a region from the boundaries must be
  // unstable inside.
  if (onset_within && answer.stable && !tip) {
    throw NumericalError(fmt::format(
        "stability requirement: the boundary equations open a region at F̄_max = {:.6g} (Ω = {:.6g} rad/s) but the "
        "Floquet multipliers at F̄_max = {:.6g} inside it are stable (max|ρ| = {:.8g}): no verdict",
        *r.onset_fmax_over_fcr, worst_speed, r.check_fmax_over_fcr, r.max_abs_multiplier));
  }
  r.passed = !onset_within && answer.stable;
  return r;
}

}  // namespace bladestab
