// bladestab map SCENE --plane theta-fmax|speed-fmax: stability map, CSV/JSON data and a chart.
#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "bladestab/blade/damping.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/stability/boundaries.hpp"
#include "bladestab/stability/stability_map.hpp"
#include "chart.hpp"
#include "error_output.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "notes.hpp"
#include "output_files.hpp"
#include "progress.hpp"
#include "static_limits_output.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

// The threshold of instability on the map's model, 1 + max(tolerance, the method part): within the
// shading's own accuracy, max|ρ| this close to 1 cannot be told from stable (JSON `stable_below`,
// the chart's threshold).
double stable_below(const StabilityMap& m, double tolerance) { return 1 + std::max(tolerance, m.max_error_estimate); }

// The shading's whole error (method, reduction, basis), relative to max(1, max|ρ|), at least the
// tolerance: the digits of max|ρ| follow it, and a point above stable_below but within it may
// change its verdict with more terms.
double shading_error(const StabilityMap& m, double tolerance) {
  return std::max(tolerance, m.max_error_estimate + m.shading_fidelity.reduction_error + m.shading_fidelity.basis_error);
}

// The map as its files print it (printed_digits.hpp): max|ρ| to the shading's accuracy, the larger
// of the tolerance and its estimate (method and reduction), and so a combination's detuning (a
// fraction of θ read from the angles of multipliers that carry that error); each curve's points to
// the curves' estimate, a fraction of the window's span, in both coordinates. The shading's
// estimates get their 2 digits here, the curves' budget where it is written.
StabilityMap as_printed(StabilityMap m, double tolerance, const PrintedDigits& digits) {
  const double shading = digits.estimate(shading_error(m, tolerance));
  const auto rho = [&](double& v) { v = digits.relative(v, shading); };
  for (Eigen::Index k = 0; k < m.max_abs_multiplier.size(); ++k) rho(m.max_abs_multiplier.data()[k]);
  for (MapSample& p : m.samples) rho(p.max_abs_multiplier);
  for (MapCell& c : m.cells) rho(c.max_abs_multiplier);
  for (CombinationRegion& r : m.combinations) {
    rho(r.max_abs_multiplier);
    r.combination.detuning = digits.absolute(r.combination.detuning, shading);
  }
  const double curves = digits.estimate(m.curve_fidelity.budget.total());
  const double x_error = curves * (m.grid_x.back() - m.grid_x.front());
  const double y_error = curves * (m.grid_fbar.back() - m.grid_fbar.front());
  for (BoundaryCurve& c : m.curves) {
    c.x = digits.absolute(c.x, x_error);
    c.fbar = digits.absolute(c.fbar, y_error);
  }
  if (m.scene_point) {
    rho(m.scene_point->max_abs_multiplier);
    if (m.scene_point->nearest_boundary) {
      m.scene_point->nearest_boundary->fbar = digits.absolute(m.scene_point->nearest_boundary->fbar, y_error);
    }
  }
  m.max_error_estimate = digits.estimate(m.max_error_estimate);
  m.shading_fidelity.reduction_error = digits.estimate(m.shading_fidelity.reduction_error);
  m.shading_fidelity.basis_error = digits.estimate(m.shading_fidelity.basis_error);
  return m;
}

// The refined shading: the leaves of the refinement on the fine lattice ([i, j, width, height,
// max|ρ| of the corners]; lattice point i lies in grid cell i >> k, linearly between its points).
Json refinement_json(const StabilityMap& m) {
  Json cells = Json::array();
  for (const MapCell& c : m.cells) {
    cells.push_back({c.i, c.j, c.width, c.height, number_or_null(c.max_abs_multiplier)});
  }
  return {{"cells_x", m.cells_x}, {"cells_y", m.cells_y}, {"x_lo", m.grid_x.front()}, {"x_hi", m.grid_x.back()},
          {"y_lo", m.grid_fbar.front()}, {"y_hi", m.grid_fbar.back()}, {"cells", cells}};
}

// Why the curves' estimate is above --tolerance, after it: "" when it is not.
std::string curves_unmet(const CurveFidelity& f, double tolerance) {
  if (f.tolerance_met) return "";
  if (!f.work_limited) return fmt::format(" — above --tolerance {}", tolerance);
  return fmt::format(" — above --tolerance {}: a richer curve model's check would pass the work --max-seconds {:g} "
                     "allows", tolerance, work_limits().seconds);
}

Json curve_fidelity_json(const StabilityMap& m, const PrintedDigits& digits) {
  const CurveFidelity& f = m.curve_fidelity;
  Json json = {{"reduction", to_string(f.reduction.kind)},
               {"reduction_vectors", f.reduction.vectors},
               {"approximation", f.approximation},
               {"checked_at", f.checked_at},
               {"tolerance_met", f.tolerance_met},
               {"work_limited", f.work_limited},
               {"drawn", f.drawn},
               {"error_measure", m.plane == MapPlane::theta_fmax ? "distance in θ over the window's θ span"
                                                                  : "distance in F̄ over the window's top F̄ (the "
                                                                    "curves are traced from F̄ = 0)"}};
  write_error_budget(json, f.budget, digits);
  return json;
}

// Where the scene itself sits: a labelled marker for the chart and the point's numbers.
void write_scene_point(Json& json, const MapPoint& p) {
  std::string label = p.undecided.empty() ? fmt::format("scene: max|ρ| = {:.4g}", p.max_abs_multiplier)
                                          : std::string("scene: max|ρ| undecided");
  if (p.nearest_boundary) {
    label += fmt::format("\nnearest boundary ({:+d}) at F̄ = {:.4g}, ΔF̄ = {:+.3g}", p.nearest_boundary->multiplier,
                         p.nearest_boundary->fbar, p.nearest_boundary->fbar - p.fbar);
  }
  json["markers"] = Json::array({{{"x", p.x}, {"y", p.fbar}, {"label", label}}});
  Json point = {{"x", p.x},
                {"y", p.fbar},
                {"max_abs_multiplier", number_or_null(p.max_abs_multiplier)},
                {"undecided", p.undecided.empty() ? Json(nullptr) : Json(p.undecided)}};
  if (p.nearest_boundary) {
    point["nearest_boundary_fbar"] = p.nearest_boundary->fbar;
    point["nearest_boundary_multiplier"] = p.nearest_boundary->multiplier;
    point["nearest_boundary_mode"] = p.nearest_boundary->mode;
    point["nearest_boundary_order"] = p.nearest_boundary->order;
  } else {
    point["nearest_boundary_fbar"] = nullptr;
  }
  json["scene_point"] = point;
}

// `m` as printed (as_printed).
std::string map_json(const Scene& scene, const BladeModel& model, const MapOptions& o, const StabilityMap& m,
                     const PrintedDigits& digits) {
  const bool theta = m.plane == MapPlane::theta_fmax;
  const std::string stem = scene_title(scene);
  Json json;
  json["title"] = theta ? fmt::format("{} — stability map at Ω = {:g} rad/s", stem, scene.operation.speed_rad_s)
                        : fmt::format("{} — stability map, θ = {}·Ω", stem, o.engine_order);
  json["plane"] = theta ? "theta-fmax" : "speed-fmax";
  json["scene"] = scene.source;
  json["model"] = describe_model(model);
  json["x_label"] = theta ? "pulse frequency θ [rad/s]" : "rotor speed Ω [rad/s]";
  json["y_label"] = "F̄_max = F_max / F_cr";
  json["approximation"] = m.curve_fidelity.approximation;
  json["max_order"] = o.max_order;
  json["shading_method"] = "Floquet multipliers, method auto";
  json["shading_max_relative_error"] = m.max_error_estimate;
  json["shading_reduction_vectors"] = m.shading_fidelity.reduction_vectors;
  json["shading_reduction_error"] = m.shading_fidelity.reduction_error;
  json["shading_basis_error"] = m.shading_fidelity.basis_error;
  json["shading_basis_points"] = m.shading_fidelity.basis_checked.size();
  json["stable_below"] = stable_below(m, o.tolerance);
  Json rows = Json::array();
  for (Eigen::Index j = 0; j < m.max_abs_multiplier.rows(); ++j) {
    const Eigen::RowVectorXd row = m.max_abs_multiplier.row(j);
    rows.push_back(numbers_or_null(std::vector<double>(row.data(), row.data() + row.size())));
  }
  json["grid"] = {{"x", m.grid_x}, {"y", m.grid_fbar}, {"max_abs_multiplier", rows}};
  if (!m.cells.empty()) json["refinement"] = refinement_json(m);
  json["samples"] = Json::array();
  for (const MapSample& p : m.samples) {
    json["samples"].push_back({{"x", p.x}, {"y", p.fbar}, {"max_abs_multiplier", number_or_null(p.max_abs_multiplier)}});
  }
  json["undecided_points"] = Json::array();
  for (const MapSample& p : m.undecided) json["undecided_points"].push_back({{"x", p.x}, {"y", p.fbar}});
  json["undecided_reason"] = m.undecided.empty() ? Json(nullptr) : Json(with_max_seconds(m.undecided_reason));
  json["curve_fidelity"] = curve_fidelity_json(m, digits);
  json["curves"] = Json::array();
  for (const BoundaryCurve& c : m.curves) {
    json["curves"].push_back(
        {{"multiplier", c.multiplier}, {"mode", c.mode}, {"order", c.order}, {"x", c.x}, {"y", c.fbar}});
  }
  json["combination_regions"] = Json::array();
  for (const CombinationRegion& r : m.combinations) {
    const Combination& c = r.combination;
    json["combination_regions"].push_back({{"mode_i", c.mode_i},
                                           {"mode_j", c.mode_j},
                                           {"kind", c.sum ? "sum" : "difference"},
                                           {"order", c.order},
                                           {"detuning", c.detuning},
                                           {"x", r.x},
                                           {"y", r.fbar},
                                           {"max_abs_multiplier", r.max_abs_multiplier},
                                           {"samples", r.samples}});
  }
  if (m.scene_point) write_scene_point(json, *m.scene_point);
  return json_text(json);
}

std::string curves_csv(const StabilityMap& m) {
  std::string csv = "curve,multiplier,mode,order,x_rad_s,fmax_over_fcr\n";
  for (std::size_t k = 0; k < m.curves.size(); ++k) {
    const BoundaryCurve& c = m.curves[k];
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      csv += fmt::format("{},{},{},{},{},{}\n", k + 1, c.multiplier, c.mode, c.order, c.x[i], c.fbar[i]);
    }
  }
  return csv;
}

std::string grid_csv(const StabilityMap& m) {
  std::string csv = "x_rad_s,fmax_over_fcr,max_abs_multiplier\n";
  for (std::size_t j = 0; j < m.grid_fbar.size(); ++j) {
    for (std::size_t i = 0; i < m.grid_x.size(); ++i) {
      const double v = m.max_abs_multiplier(j, i);
      csv += fmt::format("{},{},{}\n", m.grid_x[i], m.grid_fbar[j], std::isnan(v) ? std::string() : fmt::format("{}", v));
    }
  }
  return csv;
}

// --resolution NXxNY: two plain integers in [1, 4096] (number_options.hpp).
std::pair<int, int> parse_resolution(const std::string& text) {
  const std::size_t x = text.find('x');
  const std::optional<long> nx = x == std::string::npos ? std::nullopt : read_integer(text.substr(0, x));
  const std::optional<long> ny = x == std::string::npos ? std::nullopt : read_integer(text.substr(x + 1));
  if (!nx || !ny || *nx < 1 || *ny < 1 || *nx > 4096 || *ny > 4096) {
    throw InputError(fmt::format("--resolution {}: must be NXxNY with integers in [1, 4096], e.g. 400x200",
                                 echoed(text)));
  }
  return {static_cast<int>(*nx), static_cast<int>(*ny)};
}

// The map's work before it starts, from unit costs measured on the paper blade (N = 8, one core)
// and scaled. A traced line solves both families' boundary equations, (2k + 1)·n unknowns for
// n ≈ 20 reduced modes, ~26 (unknowns)³ flops each (measured ~0.1 s a line at the k = 8 the paper's
// maps are raised to). A shading point reduces the whole model at its load (~20 n³ flops for n
// dofs) and runs a Floquet monodromy on the reduced one (4 ms); the refinement adds points along
// the boundaries, about 10 per effective cell of the resolution's width and height (12 500 on the
// paper's 400 × 200 map, where the estimate takes 6000). The true pulse train (exact_pulse) is
// shaded on the whole model, its monodromy ~170 (2n)³ flops a point for 2n states (35 ms at 16
// terms), and its narrow tongues take about twice the refinement (4395 points at 100 × 50). Curves
// (the cosine approximation) are first checked against the whole Ritz model at min(K, 4)
// harmonics on three of the lines (check_curves, boundary_level_flops): on the fan blade at 46
// terms (230 dofs) ~40 s, where a line of the reduced model takes 0.1 s.
void check_map_work(const BladeModel& model, const MapOptions& o, LoadApproximation load) {
  const bool exact_pulse = load == LoadApproximation::exact;
  const double reduced_modes = 20, dofs = model.layout.size(), states = 2 * dofs;
  const double unknowns = (2 * o.approximation + 1) * reduced_modes;
  const bool curves_checked = !o.trace.empty() && load == LoadApproximation::cosine;
  const double whole_check_seconds =
      curves_checked ? 3 * boundary_level_flops(std::min(o.approximation, 4), static_cast<int>(dofs), true) /
                           dense_flops_per_second
                     : 0;
  const double line_seconds = 2 * 26 * unknowns * unknowns * unknowns / dense_flops_per_second;
  const double point_seconds = exact_pulse ? 170 * states * states * states / dense_flops_per_second
                                           : 4e-3 + 20 * dofs * dofs * dofs / dense_flops_per_second;
  const double grid = static_cast<double>(o.grid_x.size()) * o.grid_fbar.size();
  const double points = grid + (exact_pulse ? 20.0 : 10.0) * (o.resolution_x + o.resolution_y);
  // On one thread: a refusal that depended on --threads would be an answer that does.
  const double curve_seconds = o.trace.size() * line_seconds + whole_check_seconds;
  const double seconds = curve_seconds + points * point_seconds;
  // The grid of max|ρ|, the samples and cells of the refinement, and each traced line's boundaries.
  const double bytes = points * 64 + o.trace.size() * 4096.0;
  const std::string cause = points * point_seconds > curve_seconds
                                ? fmt::format("a grid of {} × {} points refined to --resolution {}x{}", o.grid_x.size(),
                                              o.grid_fbar.size(), o.resolution_x, o.resolution_y)
                                : fmt::format("--trace {} at --approximation {}", o.trace.size(), o.approximation);
  check_work(fmt::format("{} with model.terms = {}", cause, model.spec.terms),
             fmt::format("the map of a {}-dof model", model.layout.size()), seconds, bytes);
}

// Every speed of the speed plane within the blade's static limits, before any point is solved:
// the speeds within form one interval, so its ends suffice, and the refusal does not depend on
// which point a thread reaches first.
void check_plane_speeds(const BladeModel& model, const std::vector<double>& speeds, const std::string& text) {
  const PathWithinLimits limits = speeds_within_limits(model, {speeds.front(), speeds.back()});
  if (limits.first == 0 && limits.end == 2) return;
  const std::string where = limits.empty() ? static_limit_error(model, speeds.front(), "Ω")->what()
                                           : describe_path_limits(limits, true, speed_parameter().words);
  throw InputError(fmt::format("--speeds {}: {}; the plane's speeds must lie within the blade's static limits",
                               echoed(text), where));
}

// The options that shape the plane's grids, as given.
struct PlaneTexts {
  std::string theta, speeds;
  int trace;
};

// The plane's x grid (θ, default ω1/4 to 2.5 ω1, or Ω within the blade's static limits) and the
// values along which the boundary curves are traced.
void set_plane_grids(const CLI::App& command, const Scene& scene, const BladeModel& model, const PlaneTexts& texts,
                     MapOptions& o) {
  const bool theta_plane = o.plane == MapPlane::theta_fmax;
  if (theta_plane && command.count("--speeds") > 0) {
    throw InputError(fmt::format("--speeds {}: only with --plane speed-fmax; the theta-fmax plane is at the scene's "
                                 "speed (--set operation.speed_rad_s=…)", texts.speeds));
  }
  if (!theta_plane && command.count("--theta") > 0) {
    throw InputError(fmt::format("--theta {}: only with --plane theta-fmax; in the speed-fmax plane θ = k·Ω "
                                 "(--engine-order k)", texts.theta));
  }
  if (theta_plane) {
    if (command.count("--theta") == 0) {
      const double speed = scene.operation.speed_rad_s;
      const Eigen::MatrixXd no_tip_load = Eigen::MatrixXd::Zero(model.layout.size(), model.layout.size());
      const double w1 = solve_modes(model, system_at(model, speed, no_tip_load), speed, 1, EigenSolverKind::dense)
                            .modes.at(0).eigenvalue.imag();
      o.grid_x = parse_range("--theta", fmt::format("{}:{}:41", w1 / 4, 2.5 * w1),
                             scene_limits::pulse_angular_frequency_rad_s);
    } else {
      o.grid_x = parse_range("--theta", texts.theta, scene_limits::pulse_angular_frequency_rad_s);
    }
    o.trace = parse_range("--fmax", fmt::format("{}:{}:{}", o.grid_fbar.front(), o.grid_fbar.back(), texts.trace),
                          scene_limits::fmax_over_fcr);
  } else {
    if (command.count("--speeds") == 0) throw InputError("--speeds: required for --plane speed-fmax (start:stop:count in rad/s)");
    o.grid_x = parse_range("--speeds", texts.speeds, AllowedRange::above(0, scene_limits::speed_rad_s.hi));
    o.trace = parse_range("--speeds", fmt::format("{}:{}:{}", o.grid_x.front(), o.grid_x.back(), texts.trace),
                          AllowedRange::above(0, scene_limits::speed_rad_s.hi));
    check_plane_speeds(model, o.grid_x, texts.speeds);
  }
}

// The table for people: the scene, the curves' and the shading's fidelity, the scene's own point.
void print_map_table(const Scene& scene, const BladeModel& model, const std::string& plane, const MapOptions& o,
                     const StabilityMap& m, const std::vector<std::string>& files) {
  const bool theta_plane = o.plane == MapPlane::theta_fmax;
  int unstable = 0, points = 0, within = 0;  // within: unstable by less than the shading's whole error
  for (Eigen::Index k = 0; k < m.max_abs_multiplier.size(); ++k) {
    const double v = m.max_abs_multiplier.data()[k];
    if (std::isnan(v)) continue;
    ++points;
    const bool above = v > stable_below(m, o.tolerance);
    unstable += above;
    within += above && v <= 1 + shading_error(m, o.tolerance);
  }
  fmt::print("scene     {}\nmodel     {}\nplane     {}{}\n", scene.source, describe_model(model), plane,
             theta_plane ? fmt::format(" at Ω = {:g} rad/s", scene.operation.speed_rad_s)
                         : fmt::format(", θ = {}·Ω", o.engine_order));
  const CurveFidelity& f = m.curve_fidelity;
  if (!f.drawn) {
    fmt::print("curves    none: they are drawn for the cosine approximation (42); the pulse's own series (load."
               "approximation \"fourier\", or \"exact\") needs many more harmonics in the boundary equations, not "
               "monotonically; the shading (Floquet) shows the regions\n");
  } else {
    fmt::print("curves    {} boundary curves ({} harmonics per family, {} model{}); error over {} {}{}\n",
               m.curves.size(), f.approximation, to_string(f.reduction.kind),
               f.reduction.kind == ReductionKind::automatic ? fmt::format(", {} vectors per load level", f.reduction.vectors)
                                                            : "",
               theta_plane ? std::string("the window's θ span") : fmt::format("F̄ from 0 to the window's top {:g}", m.grid_fbar.back()),
               describe_error_budget(f.budget), curves_unmet(f, o.tolerance));
  }
  const ShadingFidelity& sf = m.shading_fidelity;
  fmt::print("shading   {} of {} grid points unstable{}; refined to {} × {} cells with {} Floquet points; "
             "max|ρ| relative error ≤ {} (method, every point){}\n",
             unstable, points, within > 0 ? fmt::format(" ({} of them by less than the error below)", within) : "",
             m.cells_x, m.cells_y, m.samples.size(), estimate_text(m.max_error_estimate),
             sf.reduction_vectors > 0
                 ? fmt::format(" + {} (reduction to {} vectors per load level, {} grid points checked "
                               "against twice as many)", estimate_text(sf.reduction_error), sf.reduction_vectors,
                               sf.checked.size())
                 : std::string("; the whole Ritz model (fewer vectors missed the tolerance)"));
  fmt::print("          + {} (basis: {} grid points against {} terms{})\n", estimate_text(sf.basis_error),
             sf.basis_checked.size(),
             reference_terms(scene.model.basis, scene.model.terms),
             scene.model.basis == BasisKind::sine ? fmt::format(" and {} Legendre terms", scene.model.terms) : "");
  if (!m.undecided.empty()) {
    fmt::print("undecided {} shading points, shaded blank: {}\n", m.undecided.size(), with_max_seconds(m.undecided_reason));
  }
  if (m.scene_point) {
    const MapPoint& p = *m.scene_point;
    fmt::print("scene     ({:g}, F̄ = {:g}): max|ρ| {}{}\n", p.x, p.fbar,
               p.undecided.empty() ? fmt::format("= {:.{}g}", p.max_abs_multiplier,
                                                 significant_digits(std::max(o.tolerance, m.max_error_estimate)))
                                   : "undecided: " + with_max_seconds(p.undecided),
               p.nearest_boundary ? fmt::format("; nearest boundary along F̄ at {:.6g} ({:+d}, mode {}, order {}), "
                                                "ΔF̄ = {:+.3g}",
                                                p.nearest_boundary->fbar, p.nearest_boundary->multiplier,
                                                p.nearest_boundary->mode, p.nearest_boundary->order,
                                                p.nearest_boundary->fbar - p.fbar)
                                  : "; no boundary along F̄ in the window");
  }
  fmt::print("written   {}\n", fmt::join(files, ", "));
}

}  // namespace

Command register_map(CLI::App& app) {
  auto* command = app.add_subcommand("map", "stability map: instability regions in (θ, F̄) or (Ω, F̄)");
  auto options = std::make_shared<SceneOptions>();
  auto plane = std::make_shared<std::string>();
  auto theta = std::make_shared<std::string>();
  auto speeds = std::make_shared<std::string>();
  auto fmax = std::make_shared<std::string>("0:10:21");
  auto trace = std::make_shared<int>(201);
  auto order = std::make_shared<int>(0);
  auto approximation = std::make_shared<int>(4);
  auto max_order = std::make_shared<int>(4);
  auto tolerance = std::make_shared<double>(1e-3);
  auto out = std::make_shared<std::string>(".");
  auto chart = std::make_shared<std::string>("png");
  add_scene_options(*command, *options);
  command->add_option("--plane", *plane, "theta-fmax (at the scene's speed) or speed-fmax (θ = kΩ)")
      ->required()
      ->check(CLI::IsMember({"theta-fmax", "speed-fmax"}));
  command->add_option("--theta", *theta, "θ grid [rad/s] start:stop:count (default: ω1/4 to 2.5 ω1, 41 points)");
  command->add_option("--speeds", *speeds, "Ω grid [rad/s] start:stop:count (speed-fmax plane; required there)");
  command->add_option("--fmax", *fmax, "F̄_max grid start:stop:count (default 0:10:21)");
  add_integer_option(*command, "--trace", *trace, 2, 100000,
                     "parameter values for tracing the boundary curves (default 201)");
  add_integer_option(*command, "--engine-order", *order, 1, 1000, "k in θ = kΩ (default: load.pulses_per_rev)");
  add_integer_option(*command, "--approximation", *approximation, 1, 40,
                     "harmonics per family in the boundary equations (default 4)");
  add_integer_option(*command, "--max-order", *max_order, 1, 40,
                     "boundary curves of orders n <= this (theta ~ 2 omega / n; default 4); harmonics are raised to "
                     "converge them");
  add_number_option(*command, "--tolerance", *tolerance, AllowedRange::open(0, 1),
                    "accuracy of max|ρ| in the shading (default 1e-3)");
  auto threads = std::make_shared<int>();
  add_threads_option(*command, *threads);
  auto resolution = std::make_shared<std::string>("400x200");
  command->add_option("--resolution", *resolution,
                      "effective cells NXxNY of the refined shading (default 400x200; the grid's cells are split "
                      "where stability changes)");
  add_chart_options(*command, *out, *chart, "directory for map_<plane>.json, _curves.csv, _grid.csv and the chart");
  return [=] {
    const bool theta_plane = *plane == "theta-fmax";
    MapOptions o;
    o.plane = theta_plane ? MapPlane::theta_fmax : MapPlane::speed_fmax;
    o.grid_fbar = parse_range("--fmax", *fmax, scene_limits::fmax_over_fcr);
    o.approximation = *approximation;
    o.max_order = *max_order;
    o.tolerance = *tolerance;
    std::tie(o.resolution_x, o.resolution_y) = parse_resolution(*resolution);
    o.threads = *threads;
    o.work_flops = work_limits().seconds * dense_flops_per_second;
    check_output_directory("--out", *out);
    const Scene scene = options->load();
    o.engine_order = *order > 0 ? *order : scene.load.pulses_per_rev;
    const BladeModel model = assemble_model(scene);
    set_plane_grids(*command, scene, model, {*theta, *speeds, *trace}, o);
    check_map_work(model, o, scene.load.approximation);
    const bool for_people = options->output_format() == OutputFormat::table;
    const StabilityMap m = stability_map(scene, o, progress_reporter("map: points", for_people));

    const PrintedDigits digits = options->printed_digits();
    const StabilityMap printed = as_printed(m, o.tolerance, digits);
    const std::string json = map_json(scene, model, o, printed, digits);
    const std::string base = theta_plane ? "map_theta_fmax" : "map_speed_fmax";
    const std::vector<std::string> files =
        write_outputs(*out, base, {{base + "_curves.csv", curves_csv(printed)}, {base + "_grid.csv", grid_csv(printed)}},
                      json, "map", *chart);
    if (!m.undecided.empty()) {
      print_note(fmt::format("map: {} of the {} shading points are undecided (listed in undecided_points): {}",
                             m.undecided.size(), m.samples.size(), with_max_seconds(m.undecided_reason)));
    }
    switch (options->output_format()) {
      case OutputFormat::json: print_json_answer(json); break;
      case OutputFormat::csv: fmt::print("{}", curves_csv(printed)); break;
      case OutputFormat::table: print_map_table(scene, model, *plane, o, m, files); break;
    }
  };
}

}  // namespace bladestab::cli
