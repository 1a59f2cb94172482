// bladestab boundaries SCENE: boundary pulse frequencies at the scene's (Ω, F_max), or boundary
// loads at a given θ (--at-theta), each with an estimate of its whole error; k is raised until the
// boundaries converge to --tolerance.
#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/stability/instability_regions.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "support/message_text.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "error_output.hpp"
#include "finite_results.hpp"
#include "json_output.hpp"
#include "notes.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

void require_finite(const BoundaryAnalysis& result, const std::vector<InstabilityRegion>& regions) {
  const FiniteResults check("boundaries");
  check.require("window", result.window.first).require("window", result.window.second);
  for (const EstimatedBoundary& e : result.boundaries) {
    check.require("boundary θ", e.boundary.theta_rad_s)
        .require("boundary F_max", e.boundary.peak_force_n)
        .require("boundary error estimate", e.budget.total());
  }
  for (const UnconvergedBoundary& u : result.unconverged) {
    check.require("unconverged boundary θ", u.boundary.theta_rad_s)
        .require("unconverged boundary F_max", u.boundary.peak_force_n)
        .require("unconverged boundary's change", u.change.value_or(0));
  }
  for (const InstabilityRegion& r : regions) {
    check.require("region edge", r.lower).require("region edge", r.upper)
        .require("max|ρ| in a region", r.middle_max_abs_multiplier);
  }
}

// An unconverged boundary's JSON object: where it was at the highest k reached (no estimate: 6
// digits, printed_digits.hpp), what it is and that k.
Json unconverged_json(const Boundary& b, int approximation, double fcr, const PrintedDigits& digits) {
  return Json{{"theta_rad_s", digits.unestimated(b.theta_rad_s)},
              {"fmax_over_fcr", digits.unestimated(b.peak_force_n / fcr)},
              {"multiplier", b.multiplier},
              {"mode", b.mode},
              {"order", b.order},
              {"approximation", approximation}};
}

// The boundaries that did not converge: where each was at the highest k reached and its last change.
void print_unconverged(const BoundaryAnalysis& result, double fcr) {
  if (result.unconverged.empty()) return;
  fmt::print("\nnot converged: the value at k harmonics per family and its relative change to k + 2 (none: no "
             "counterpart there; check: converged, but its multiplier check failed)\n");
  fmt::print("{:>16} {:>14} {:>10} {:>5} {:>6} {:>4} {:>9}\n", "θ [rad/s]", "F̄_max", "multiplier", "mode", "order",
             "k", "change");
  for (const UnconvergedBoundary& u : result.unconverged) {
    const Boundary& b = u.boundary;
    fmt::print("{:>16.6g} {:>14.6g} {:>10} {:>5} {:>6} {:>4} {:>9}\n", b.theta_rad_s, b.peak_force_n / fcr,
               b.multiplier > 0 ? "+1" : "-1", b.mode, b.order, u.approximation,
               u.check_failed ? std::string("check") : u.change ? fmt::format("{:.1e}", *u.change) : std::string("none"));
  }
}

// The Floquet check of each region's middle (instability_regions.hpp), relative above max|ρ| = 1.
constexpr double region_check_tolerance = 1e-4;

// A boundary's numbers as JSON and CSV print them (printed_digits.hpp): the quantity solved for — θ,
// or F̄_max with --at-theta — to the estimate (relative), the given one as it is.
std::pair<double, double> shown_boundary(const Boundary& b, double estimate, double fcr, bool in_load,
                                         const PrintedDigits& digits) {
  const double fbar = b.peak_force_n / fcr;
  return in_load ? std::pair{b.theta_rad_s, digits.relative(fbar, estimate)}
                 : std::pair{digits.relative(b.theta_rad_s, estimate), fbar};
}

// What the three formats print from: the answer and how it is shown.
struct BoundaryOutput {
  const Scene& scene;
  const BladeModel& model;
  const BoundaryRequest& request;
  const BoundaryAnalysis& result;
  const std::vector<InstabilityRegion>& regions;
  const std::optional<std::string>& unmet;  // why the whole estimate is above --tolerance
  double fcr = 0;
  bool in_load = false;  // boundaries in F̄_max at a given θ, else in θ
  double unit = 1;       // the window in θ [rad/s] or F̄_max
  PrintedDigits digits;

  // The estimate of a region's end: its boundary's own (an unconverged one's, or one not found:
  // the largest).
  double end_error(double end) const {
    const auto own = std::find_if(result.boundaries.begin(), result.boundaries.end(), [&](const EstimatedBoundary& e) {
      return (in_load ? e.boundary.peak_force_n : e.boundary.theta_rad_s) == end;
    });
    return own != result.boundaries.end() ? own->budget.total() : result.total().total();
  }
  // A region's end in JSON: the window's as it is, a boundary's to its estimate (printed_digits.hpp).
  double region_end(double end, bool at_window) const {
    return at_window ? end / unit : digits.relative(end / unit, end_error(end));
  }
  // The same in the table, to the digits of the boundaries listed above it (a thin tongue's two
  // ends may differ below the JSON's finest resolution, 1e-7 of the value).
  std::string region_end_text(double end, bool at_window) const {
    if (at_window) return fmt::format("{:g}", end / unit);
    return to_significant_digits(end / unit, end_error(end));
  }
  // max|ρ| at a region's middle to its check's estimate.
  double middle_rho(const InstabilityRegion& r) const {
    return digits.relative(r.middle_max_abs_multiplier,
                           r.middle_error_estimate / std::max(1.0, r.middle_max_abs_multiplier));
  }
};

void print_json(const BoundaryOutput& o) {
  Json json;
  json["scene"] = o.scene.source;
  json["speed_rad_s"] = o.scene.operation.speed_rad_s;
  json["fmax_over_fcr"] = o.scene.load.fmax_over_fcr;
  json["approximation"] = o.result.approximation;
  json["max_approximation"] = o.request.max_approximation;
  json["work_limited"] = o.result.work_limited;
  json["tolerance"] = o.request.tolerance;
  json["converged"] = o.result.unconverged.empty();
  json["tolerance_met"] = o.result.unconverged.empty() && !o.unmet;
  json["tolerance_unmet"] = o.unmet ? Json(*o.unmet) : Json(nullptr);
  json["cutoff_hz"] = o.result.reduction.cutoff_hz;
  json["reduction"] = to_string(o.result.reduction.kind);
  json["reduction_vectors"] = o.result.reduction.vectors;
  json["reduced_dofs"] = o.result.reduced_size;
  json["full_dofs"] = o.result.full_size;
  json["model"] = describe_model(o.model);
  json["max_order"] = o.request.max_order;
  json["window_low"] = o.result.window.first / o.unit;
  json["window_high"] = o.result.window.second / o.unit;
  json["estimate_measure"] = o.in_load ? "relative on fmax_over_fcr" : "relative on theta_rad_s";
  write_error_budget(json, o.result.total(), o.digits);
  json["checks"] = Json::array();
  for (const BoundaryCheck& c : o.result.checks) {
    const auto [theta, fbar] = shown_boundary(c.boundary, o.result.total().total(), o.fcr, o.in_load, o.digits);
    json["checks"].push_back({{"theta_rad_s", theta},
                              {"fmax_over_fcr", fbar},
                              {"multiplier", c.boundary.multiplier},
                              {"cutoff_hz", c.cutoff_hz},
                              {"made", c.made},
                              {"multiplier_gap", c.made ? Json(o.digits.estimate(c.gap)) : Json(nullptr)},
                              {"allowed", o.digits.estimate(c.allowed)}});
  }
  json["boundaries"] = Json::array();
  for (const EstimatedBoundary& e : o.result.boundaries) {
    const Boundary& b = e.boundary;
    const auto [theta, fbar] = shown_boundary(b, e.budget.total(), o.fcr, o.in_load, o.digits);
    Json& boundary = json["boundaries"].emplace_back(Json{{"theta_rad_s", theta},
                                                          {"fmax_over_fcr", fbar},
                                                          {"multiplier", b.multiplier},
                                                          {"mode", b.mode},
                                                          {"order", b.order},
                                                          {"approximation", e.approximation}});
    write_error_budget(boundary, e.budget, o.digits);
  }
  json["unconverged"] = Json::array();
  for (const UnconvergedBoundary& u : o.result.unconverged) {
    Json& boundary = json["unconverged"].emplace_back(unconverged_json(u.boundary, u.approximation, o.fcr, o.digits));
    boundary["last_change"] = u.change ? Json(o.digits.estimate(*u.change)) : Json(nullptr);
    boundary["check_failed"] = u.check_failed;
  }
  json["regions"] = Json::array();
  for (const InstabilityRegion& r : o.regions) {
    json["regions"].push_back({{"lower", o.region_end(r.lower, r.lower_open)},
                               {"upper", o.region_end(r.upper, r.upper_open)},
                               {"lower_at_window", r.lower_open},
                               {"upper_at_window", r.upper_open},
                               {"lower_unconverged", r.lower_unconverged},
                               {"upper_unconverged", r.upper_unconverged},
                               {"multiplier", r.multiplier},
                               {"mode", r.mode},
                               {"order", r.order},
                               {"decided", r.undecided.empty()},
                               {"undecided", r.undecided.empty() ? Json(nullptr) : Json(r.undecided)},
                               {"middle_max_abs_multiplier",
                                r.undecided.empty() ? Json(o.middle_rho(r)) : Json(nullptr)},
                               {"middle_error_estimate",
                                r.undecided.empty() ? Json(o.digits.estimate(r.middle_error_estimate)) : Json(nullptr)},
                               {"inner_boundaries", Json::array()}});
    for (const double inner : r.inner) json["regions"].back()["inner_boundaries"].push_back(o.region_end(inner, false));
  }
  print_json_answer(json_text(json));
}

void print_csv(const BoundaryOutput& o) {
  // The unconverged boundaries follow with converged = false, their change from k to k + 2
  // (empty: no counterpart), whether their multiplier check failed, and no error estimate.
  fmt::print("theta_rad_s,fmax_over_fcr,multiplier,mode,order,approximation,error_estimate,basis,reduction,load,"
             "method,converged,last_change,check_failed\n");
  for (const EstimatedBoundary& e : o.result.boundaries) {
    const Boundary& b = e.boundary;
    const auto [theta, fbar] = shown_boundary(b, e.budget.total(), o.fcr, o.in_load, o.digits);
    const ErrorBudget& budget = e.budget;
    fmt::print("{},{},{},{},{},{},{},{},{},{},{},true,,false\n", theta, fbar, b.multiplier, b.mode, b.order,
               e.approximation, o.digits.estimate(budget.total()), o.digits.estimate(budget.basis),
               o.digits.estimate(budget.reduction), o.digits.estimate(budget.load), o.digits.estimate(budget.method));
  }
  for (const UnconvergedBoundary& u : o.result.unconverged) {
    const Boundary& b = u.boundary;
    fmt::print("{},{},{},{},{},{},,,,,,false,{},{}\n", o.digits.unestimated(b.theta_rad_s),
               o.digits.unestimated(b.peak_force_n / o.fcr), b.multiplier, b.mode, b.order, u.approximation,
               u.change ? fmt::format("{}", o.digits.estimate(*u.change)) : "", u.check_failed);
  }
}

// How far the harmonics went for the boundaries that did not converge: the largest k allowed, or
// the largest the work limit (BoundaryRequest::work_flops, from --max-seconds) affords.
std::string harmonics_reached(const BoundaryAnalysis& result, const BoundaryRequest& request) {
  if (!result.work_limited) return fmt::format("with up to {} harmonics per family", request.max_approximation);
  return with_max_seconds(
      fmt::format("with up to {} harmonics per family, all that the work limit affords", result.approximation + 2));
}

void print_table(const BoundaryOutput& o) {
  fmt::print("scene          {}\nmodel          {}\nreduction      {}\n", o.scene.source, describe_model(o.model),
             describe_reduction(o.result.reduction, o.result.reduced_size, o.result.full_size));
  fmt::print("operation      Ω = {:.6g} rad/s{}\n", o.scene.operation.speed_rad_s,
             o.in_load ? fmt::format(", θ = {:.6g} rad/s", *o.request.theta_rad_s)
                       : fmt::format(", F̄_max = {:.6g}", o.scene.load.fmax_over_fcr));
  fmt::print("approximation  k = {} harmonics per family: {} boundary of order <= {} with {} in [{:.6g}, {:.6g}] converged to "
             "{:.1e} against k + 2\n",
             o.result.approximation, o.result.unconverged.empty() ? "every" : "each listed", o.request.max_order,
             o.in_load ? "F̄_max" : "θ", o.result.window.first / o.unit, o.result.window.second / o.unit, o.request.tolerance);
  if (!o.result.unconverged.empty()) {
    fmt::print("not converged  {} more did not converge {} (listed after the boundaries)\n",
               o.result.unconverged.size(), harmonics_reached(o.result, o.request));
  }
  fmt::print("error          {} relative on {}, largest over the boundaries{}\n",
             describe_error_budget(o.result.total()), o.in_load ? "F̄_max" : "θ",
             o.unmet ? fmt::format(" — above --tolerance {:g}", o.request.tolerance) : "");
  for (const BoundaryCheck& c : o.result.checks) {
    const std::string found =
        c.made ? fmt::format("has a multiplier {:.1e} from {} (allowed {:.1e})", c.gap,
                             c.boundary.multiplier > 0 ? "+1" : "-1", c.allowed)
               : fmt::format("did not settle within the steps a check may take ({} Magnus steps, or what is left of "
                             "the checks' quarter of the work --max-seconds {:g} allows): not made, the boundary is "
                             "listed as not converged",
                             max_magnus_steps, work_limits().seconds);
    fmt::print("check          θ = {:.6g} rad/s, F̄_max = {:.6g}: Magnus monodromy{} {}\n", c.boundary.theta_rad_s,
               c.boundary.peak_force_n / o.fcr, c.cutoff_hz > 0 ? fmt::format(" (modes below {:.0f} Hz)", c.cutoff_hz) : "",
               found);
  }
  fmt::print("\n{:>16} {:>14} {:>10} {:>5} {:>6} {:>9}\n", "θ [rad/s]", "F̄_max", "multiplier", "mode", "order",
             "error");
  for (const EstimatedBoundary& e : o.result.boundaries) {
    const Boundary& b = e.boundary;
    // Only the digits the estimate supports, on the quantity it is relative to; the other is given.
    const auto shown = [&e](double value, bool estimated) {
      return estimated ? to_significant_digits(value, e.budget.total()) : fmt::format("{:.6g}", value);
    };
    fmt::print("{:>16} {:>14} {:>10} {:>5} {:>6} {:>9}\n", shown(b.theta_rad_s, !o.in_load),
               shown(b.peak_force_n / o.fcr, o.in_load), b.multiplier > 0 ? "+1" : "-1", b.mode, b.order,
               estimate_text(e.budget.total()));
  }
  if (o.result.boundaries.empty()) {
    fmt::print("(none {}of order <= {} in the window)\n", o.result.unconverged.empty() ? "" : "converged ",
               o.request.max_order);
  }
  print_unconverged(o.result, o.fcr);
  fmt::print("\nregions in {} (each checked unstable at its middle by the Floquet multipliers)\n",
             o.in_load ? "F̄_max" : "θ [rad/s]");
  for (const InstabilityRegion& r : o.regions) {
    const auto end = [](bool open, bool unconverged) {
      return open ? "(window)" : unconverged ? "(not converged)" : "";
    };
    // A growth below the printed digits' floor (finest_resolution) is shown as 1 + its excess: at
    // F̄ = 0.001 a region's middle is 1.0000000051, which would print as 1.
    const double excess = r.middle_max_abs_multiplier - 1;
    const std::string rho = std::abs(excess) < 1e-6 ? fmt::format("1 + {:.2g}", excess) : fmt::format("{}", o.middle_rho(r));
    std::string inner;
    for (const double x : r.inner) inner += (inner.empty() ? "; a boundary inside at " : ", ") + o.region_end_text(x, false);
    const std::string verdict = r.undecided.empty()
                                    ? fmt::format("max|ρ| = {} ± {:.1g} at the middle{}", rho, r.middle_error_estimate, inner)
                                    : "undecided: the check at the middle failed, " + r.undecided;
    fmt::print("  {}{}{} … {}{}{}  multiplier {}  mode {}  order {}  ({})\n",
               end(r.lower_open, r.lower_unconverged), r.lower_open || r.lower_unconverged ? " " : "",
               o.region_end_text(r.lower, r.lower_open), o.region_end_text(r.upper, r.upper_open),
               r.upper_open || r.upper_unconverged ? " " : "",
               end(r.upper_open, r.upper_unconverged), r.multiplier > 0 ? "+1" : "-1", r.mode, r.order, verdict);
  }
  if (o.regions.empty()) fmt::print("  (none in the window)\n");
  fmt::print("\nCombination resonances are not boundaries of this kind: check them with `bladestab stability` or `map`.\n");
}

void print(const SceneOptions& options, const Scene& scene, const BladeModel& model, const BoundaryRequest& request,
           const BoundaryAnalysis& result, const std::vector<InstabilityRegion>& regions,
           const std::optional<std::string>& unmet) {
  require_finite(result, regions);
  const double fcr = model.blade.critical_load();
  const bool in_load = request.theta_rad_s.has_value();
  const BoundaryOutput output{scene, model, request, result, regions, unmet, fcr, in_load, in_load ? fcr : 1.0,
                              options.printed_digits()};
  switch (options.output_format()) {
    case OutputFormat::json: print_json(output); break;
    case OutputFormat::csv: print_csv(output); break;
    case OutputFormat::table: print_table(output); break;
  }
}

// The boundary eigenproblems' cost before they start: the real balance has H·n unknowns (H
// harmonics: 2k for the −1 family, 2k + 1 for +1; n dofs of the reduced model), linearized to
// twice that in θ. Every run solves both families at k and k + 2 on the scene's model and at k on
// the richer basis, and an automatic reduction's at min(k, 4) on the whole model: a lower bound of
// the work (boundary_level_flops) and the memory of the largest (boundary_level_bytes).
void check_boundary_work(const Scene& scene, const BladeModel& model, const BoundaryRequest& request) {
  const ReductionSpec reduction = boundary_reduction(model, scene, request);
  const PeriodicSystem sys = periodic_system(model, scene, load_series(scene), reduction);
  const int k = request.first_approximation, n = sys.kept_modes;
  const int richer = richer_basis_dofs(scene.model, n, sys.all_modes);
  const bool in_theta = !request.theta_rad_s;
  const bool whole_compared = reduction.kind == ReductionKind::automatic && n < sys.all_modes;
  const int k_whole = std::min(k, whole_model_approximation);
  const double flops = boundary_level_flops(k, n, in_theta) + boundary_level_flops(k + 2, n, in_theta) +
                       boundary_level_flops(k, richer, in_theta) +
                       (whole_compared ? boundary_level_flops(k_whole, sys.all_modes, in_theta) : 0.0);
  const double bytes = std::max(boundary_level_bytes(k + 2, std::max(n, richer), in_theta),
                                whole_compared ? boundary_level_bytes(k_whole, sys.all_modes, in_theta) : 0.0);
  check_work(fmt::format("--approximation {} with model.terms = {}", k, scene.model.terms),
             whole_compared ? fmt::format("the boundary equations of {} dofs and the reduction's comparison with the whole "
                                          "model of {} dofs at k = {}", n, sys.all_modes, k_whole)
                             : fmt::format("the boundary equations of {} dofs", n), flops / dense_flops_per_second,
             bytes);
}

// --at-theta θ puts the pulses at θ (boundaries.hpp); the scene's contact, t̄_c of a revolution at
// its speed, must fit in their period 2π/θ, so θ ≤ Ω/t̄_c. (At rest t̄_c is a fraction of the pulse
// period itself, which the scene has checked.)
void check_pulse_fits(const Scene& scene, double theta) {
  const double speed = scene.operation.speed_rad_s, highest = speed / scene.load.contact_time_rev;
  if (speed > 0 && theta > highest * (1 + 1e-12)) {
    throw InputError(fmt::format("--at-theta {:g}: the pulses would be shorter apart than their contact, "
                                 "load.contact_time_rev = {:g} of a revolution at operation.speed_rad_s = {:g}; "
                                 "must be at most Ω/t̄_c = {:.6g} rad/s",
                                 theta, scene.load.contact_time_rev, speed, highest));
  }
}

// --tolerance bounds the harmonics' part, which k is raised to meet, and the automatic reduction's
// part, whose vectors are raised to meet half of it; the basis, a reduction the scene or
// --cutoff-hz sets and the load series are reported, not raised. Where the whole
// estimate of the converged boundaries is above the tolerance, one line says which part, and for
// the basis whether more terms could reach it (basis_can_reach, as `stability` raises them).
std::optional<std::string> tolerance_unmet(const Scene& scene, const BoundaryRequest& request,
                                           const BoundaryAnalysis& analysis) {
  const ErrorBudget total = analysis.total();
  if (total.total() <= request.tolerance) return std::nullopt;
  std::string part;
  if (total.basis >= std::max({total.reduction, total.load, total.method})) {
    const ModelSpec& spec = scene.model;
    part = fmt::format("its basis part {:.1e} with model.basis = \"{}\" and {} terms per field: {}", total.basis,
                       to_string(spec.basis), spec.terms,
                       basis_can_reach(scene.blade, spec, total.basis, request.tolerance)
                           ? "raise model.terms"
                           : spec.basis == BasisKind::sine ? "more terms cannot reach it; use model.basis = \"legendre\""
                                                           : "more terms cannot reach it (a section table converges "
                                                             "algebraically); use a looser tolerance");
  } else if (total.reduction >= std::max(total.load, total.method)) {
    part = fmt::format("its reduction part {:.1e}: {}", total.reduction,
                       analysis.reduction.kind == ReductionKind::modal ? "raise --cutoff-hz (or model.cutoff_hz)"
                                                                       : "raise model.reduction_vectors");
  } else if (total.load >= total.method) {
    part = fmt::format("its load part {:.1e}: the pulse's series (load.approximation = \"fourier\")", total.load);
  } else {
    part = fmt::format("its method part {:.1e}", total.method);
  }
  return fmt::format("the whole estimate {:.1e} is above --tolerance {:g}, which bounds the harmonics' and the automatic reduction's parts; "
                     "mostly {}", total.total(), request.tolerance, part);
}

// What the answer lacks, on one stderr line: boundaries that did not converge, and a whole estimate
// above the tolerance. Boundaries that did not converge do not sink those that did: with some
// converged the answer stands (exit 0, the line a note); with none converged the answer, which
// lists them, is a failure (exit 1, the line the failure's).
void report_shortfalls(const BoundaryAnalysis& analysis, const std::vector<InstabilityRegion>& regions,
                       const BoundaryRequest& request, const std::optional<std::string>& unmet) {
  std::vector<std::string> parts;
  if (!analysis.unconverged.empty()) {
    const bool none = analysis.boundaries.empty();
    parts.push_back(fmt::format("{} of the {} boundaries in the window {} to --tolerance {:g} {} (listed as not "
                                "converged)",
                                none ? "none" : std::to_string(analysis.unconverged.size()),
                                analysis.unconverged.size() + analysis.boundaries.size(),
                                none ? "converged" : "did not converge", request.tolerance,
                                harmonics_reached(analysis, request)));
  }
  if (unmet) parts.push_back(*unmet);
  const auto undecided = std::count_if(regions.begin(), regions.end(), [](const auto& r) { return !r.undecided.empty(); });
  if (undecided > 0) {
    parts.push_back(fmt::format("{} of the intervals between boundaries have no verdict (listed as undecided with why)",
                                undecided));
  }
  if (analysis.work_limited && analysis.unconverged.empty()) {
    parts.push_back(fmt::format("the reduction was not raised further: more would exceed the work --max-seconds {:g} "
                                "allows", work_limits().seconds));
  }
  if (parts.empty()) return;
  const std::string line = fmt::format("boundaries: {}", fmt::join(parts, "; "));
  if (analysis.boundaries.empty() && !analysis.unconverged.empty()) throw AnswerIsNegative{line};
  print_note(line);
}

// --range LO:HI: two plain numbers (number_options.hpp) with 0 <= LO < HI.
std::pair<double, double> parse_window(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::optional<double> lo = colon == std::string::npos ? std::nullopt : read_decimal(text.substr(0, colon));
  const std::optional<double> hi = colon == std::string::npos ? std::nullopt : read_decimal(text.substr(colon + 1));
  if (!lo || !hi || !(*lo >= 0 && *hi > *lo)) {
    throw InputError(fmt::format("--range {}: must be LO:HI with 0 <= LO < HI", echoed(text)));
  }
  return {*lo, *hi};
}

}  // namespace

Command register_boundaries(CLI::App& app) {
  auto* command = app.add_subcommand("boundaries", "boundaries of the instability regions (multiplier ±1)");
  auto options = std::make_shared<SceneOptions>();
  auto request = std::make_shared<BoundaryRequest>();
  auto at_theta = std::make_shared<double>(0);
  auto range = std::make_shared<std::string>();
  add_scene_options(*command, *options);
  add_integer_option(*command, "--approximation", request->first_approximation, 1, request->max_approximation - 4,
                     "harmonics k per family to start from (1 = Bolotin's first; default 2); raised by 2 until converged");
  add_number_option(*command, "--tolerance", request->tolerance, AllowedRange::open(0, 1),
                    "relative change of every boundary from k to k + 2 harmonics that ends the raising (default 1e-6)");
  add_number_option(*command, "--at-theta", *at_theta, scene_limits::pulse_angular_frequency_rad_s,
                    "instead: all boundary F̄_max at this pulse frequency θ [rad/s]");
  add_number_option(*command, "--cutoff-hz", request->cutoff_hz, AllowedRange::closed(0, scene_limits::cutoff_hz.hi),
                    "keep only the modes below this frequency (default 0: all)");
  add_integer_option(*command, "--max-order", request->max_order, 1, 2 * request->max_approximation - 3,
                     "highest order n (θ ≈ 2ω/n) reported and converged (default 4)");
  add_threads_option(*command, request->threads);
  command->add_option("--range", *range,
                      "LO:HI, the θ window [rad/s] (F̄_max with --at-theta) reported and converged "
                      "(default θ/2:2θ of the scene; 0:2F̄_max)");
  return [=] {
    const bool in_load = command->count("--at-theta") > 0;
    if (in_load) request->theta_rad_s = *at_theta;
    const std::optional<std::pair<double, double>> window =
        command->count("--range") > 0 ? std::optional(parse_window(*range)) : std::nullopt;
    const Scene scene = options->load();
    refuse_impulse_jump(scene);  // the regions' middles are Floquet answers for the continuum
    if (in_load) check_pulse_fits(scene, *at_theta);
    if (request->cutoff_hz > 0) {
      check_modal_cutoff(scene, request->cutoff_hz, fmt::format("--cutoff-hz {:g}", request->cutoff_hz));
    }
    const BladeModel model = assemble_model(scene);
    if (window) {
      const double unit = in_load ? model.blade.critical_load() : 1.0;  // F̄_max → N
      request->window = std::make_pair(window->first * unit, window->second * unit);
    }
    check_boundary_work(scene, model, *request);
    request->work_flops = work_limits().seconds * dense_flops_per_second;
    request->progress = progress_reporter("boundaries: harmonic levels solved", options->output_format() == OutputFormat::table);
    const BoundaryAnalysis analysis = boundaries_with_error_estimate(scene, *request);
    const std::optional<std::string> unmet = tolerance_unmet(scene, *request, analysis);
    const std::vector<InstabilityRegion> regions = instability_regions(scene, *request, analysis, region_check_tolerance);
    print(*options, scene, model, *request, analysis, regions, unmet);
    report_shortfalls(analysis, regions, *request, unmet);
  };
}

}  // namespace bladestab::cli
