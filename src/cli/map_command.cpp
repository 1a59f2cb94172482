// bladestab map SCENE --plane theta-fmax|speed-fmax: stability map, CSV/JSON data and a chart.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include <fmt/format.h>

#include "bladestab/damping.hpp"
#include "bladestab/input_error.hpp"
#include "bladestab/modes.hpp"
#include "bladestab/stability_map.hpp"
#include "chart.hpp"
#include "error_output.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "options.hpp"
#include "progress.hpp"

namespace bladestab::cli {
namespace {

// The refined shading: the leaves of the refinement on the fine lattice ([i, j, width, height,
// max|ρ| of the corners]; lattice point i lies in grid cell i >> k, linearly between its points).
void write_refinement(JsonWriter& json, const StabilityMap& m) {
  json.begin_object("refinement")
      .value("cells_x", m.cells_x)
      .value("cells_y", m.cells_y)
      .value("x_lo", m.grid_x.front())
      .value("x_hi", m.grid_x.back())
      .value("y_lo", m.grid_fbar.front())
      .value("y_hi", m.grid_fbar.back())
      .begin_array("cells");
  for (const MapCell& c : m.cells) {
    json.numbers_or_null(nullptr, {static_cast<double>(c.i), static_cast<double>(c.j), static_cast<double>(c.width),
                                   static_cast<double>(c.height), c.max_abs_multiplier});
  }
  json.end_array().end_object();
}

std::string map_json(const Scene& scene, const BladeModel& model, const MapOptions& o, const StabilityMap& m) {
  const bool theta = m.plane == MapPlane::theta_fmax;
  const std::string stem = scene_title(scene);
  JsonWriter json;
  json.begin_object()
      .value("title", theta ? fmt::format("{} — stability map at Ω = {:g} rad/s", stem, scene.operation.speed_rad_s)
                            : fmt::format("{} — stability map, θ = {}·Ω", stem, o.engine_order))
      .value("plane", theta ? "theta-fmax" : "speed-fmax")
      .value("scene", scene.source)
      .value("model", describe_model(model))
      .value("x_label", theta ? "pulse frequency θ [rad/s]" : "rotor speed Ω [rad/s]")
      .value("y_label", "F̄_max = F_max / F_cr")
      .value("approximation", m.curve_fidelity.approximation)
      .value("max_order", o.max_order)
      .value("shading_method", "Floquet multipliers, method auto")
      .value("shading_max_relative_error", m.max_error_estimate)
      .value("shading_reduction_vectors", m.shading_fidelity.reduction_vectors)
      .value("shading_reduction_error", m.shading_fidelity.reduction_error)
      // Within the shading's accuracy, max|ρ| this close to 1 cannot be told from stable.
      .value("stable_below", 1 + std::max(o.tolerance, m.max_error_estimate))
      .begin_object("grid")
      .numbers("x", m.grid_x)
      .numbers("y", m.grid_fbar)
      .begin_array("max_abs_multiplier");
  for (Eigen::Index j = 0; j < m.max_abs_multiplier.rows(); ++j) {
    const Eigen::RowVectorXd row = m.max_abs_multiplier.row(j);
    json.numbers_or_null(nullptr, std::vector<double>(row.data(), row.data() + row.size()));
  }
  json.end_array().end_object();
  if (!m.cells.empty()) write_refinement(json, m);
  json.begin_array("samples");
  for (const MapSample& p : m.samples) {
    json.begin_object().value("x", p.x).value("y", p.fbar);
    if (std::isnan(p.max_abs_multiplier)) {
      json.null_value("max_abs_multiplier");
    } else {
      json.value("max_abs_multiplier", p.max_abs_multiplier);
    }
    json.end_object();
  }
  json.end_array();
  const CurveFidelity& f = m.curve_fidelity;
  json.begin_object("curve_fidelity")
      .value("reduction", to_string(f.reduction.kind))
      .value("reduction_vectors", f.reduction.vectors)
      .value("approximation", f.approximation)
      .numbers("checked_at", f.checked_at)
      .value("tolerance_met", f.tolerance_met)
      .value("drawn", f.drawn)
      .value("error_measure", m.plane == MapPlane::theta_fmax ? "distance in θ over the window's θ span"
                                                               : "distance in F̄ over the window's F̄ span");
  write_error_budget(json, f.budget);
  json.end_object().begin_array("curves");
  for (const BoundaryCurve& c : m.curves) {
    json.begin_object()
        .value("multiplier", c.multiplier)
        .value("mode", c.mode)
        .value("order", c.order)
        .numbers("x", c.x)
        .numbers("y", c.fbar)
        .end_object();
  }
  json.end_array();
  if (m.scene_point) {  // where the scene itself sits
    const MapPoint& p = *m.scene_point;
    std::string label = fmt::format("scene: max|ρ| = {:.4g}", p.max_abs_multiplier);
    if (p.nearest_boundary) {
      label += fmt::format("\nnearest boundary ({:+d}) at F̄ = {:.4g}, ΔF̄ = {:+.3g}", p.nearest_boundary->multiplier,
                           p.nearest_boundary->fbar, p.nearest_boundary->fbar - p.fbar);
    }
    json.begin_array("markers")
        .begin_object()
        .value("x", p.x)
        .value("y", p.fbar)
        .value("label", label)
        .end_object()
        .end_array();
    json.begin_object("scene_point").value("x", p.x).value("y", p.fbar).value("max_abs_multiplier", p.max_abs_multiplier);
    if (p.nearest_boundary) {
      json.value("nearest_boundary_fbar", p.nearest_boundary->fbar)
          .value("nearest_boundary_multiplier", p.nearest_boundary->multiplier)
          .value("nearest_boundary_mode", p.nearest_boundary->mode)
          .value("nearest_boundary_order", p.nearest_boundary->order);
    } else {
      json.null_value("nearest_boundary_fbar");
    }
    json.end_object();
  }
  json.end_object();
  return json.str();
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
  command->add_option("--trace", *trace, "parameter values for tracing the boundary curves (default 201)");
  command->add_option("--engine-order", *order, "k in θ = kΩ (default: load.pulses_per_rev)");
  command->add_option("--approximation", *approximation, "harmonics per family in the boundary equations (default 4)");
  command->add_option("--max-order", *max_order,
                      "boundary curves of orders n <= this (theta ~ 2 omega / n; default 4); harmonics are raised to "
                      "converge them");
  command->add_option("--tolerance", *tolerance, "accuracy of max|ρ| in the shading (default 1e-3)");
  auto threads = std::make_shared<int>(std::max(1u, std::thread::hardware_concurrency()));
  command->add_option("--threads", *threads, "worker threads (default: the machine's cores)");
  auto resolution = std::make_shared<std::string>("400x200");
  command->add_option("--resolution", *resolution,
                      "effective cells NXxNY of the refined shading (default 400x200; the grid's cells are split "
                      "where stability changes)");
  add_chart_options(*command, *out, *chart, "directory for map_<plane>.json, _curves.csv, _grid.csv and the chart");
  return [=] {
    Scene scene = options->load();
    const bool theta_plane = *plane == "theta-fmax";
    MapOptions o;
    o.plane = theta_plane ? MapPlane::theta_fmax : MapPlane::speed_fmax;
    o.grid_fbar = parse_range("--fmax", *fmax);
    if (o.grid_fbar.front() < 0) throw InputError(fmt::format("--fmax {}: F̄_max must be >= 0", *fmax));
    if (*trace < 2 || *trace > 100000) throw InputError(fmt::format("--trace {}: must be an integer in [2, 100000]", *trace));
    if (*approximation < 1 || *approximation > 40) {
      throw InputError(fmt::format("--approximation {}: must be an integer in [1, 40]", *approximation));
    }
    if (!(*tolerance > 0 && *tolerance < 1)) throw InputError(fmt::format("--tolerance {}: must be in (0, 1)", *tolerance));
    o.engine_order = *order > 0 ? *order : scene.load.pulses_per_rev;
    if (*order < 0) throw InputError(fmt::format("--engine-order {}: must be an integer >= 1", *order));
    o.approximation = *approximation;
    if (*max_order < 1 || *max_order > 40) {
      throw InputError(fmt::format("--max-order {}: must be an integer in [1, 40]", *max_order));
    }
    o.max_order = *max_order;
    o.tolerance = *tolerance;
    {
      int rx = 0, ry = 0;
      char sep = 0, extra = 0;
      if (std::sscanf(resolution->c_str(), "%d%c%d%c", &rx, &sep, &ry, &extra) != 3 || sep != 'x' || rx < 1 ||
          ry < 1 || rx > 4096 || ry > 4096) {
        throw InputError(fmt::format("--resolution {}: must be NXxNY with integers in [1, 4096], e.g. 400x200",
                                     *resolution));
      }
      o.resolution_x = rx;
      o.resolution_y = ry;
    }
    if (*threads < 1 || *threads > 256) {
      throw InputError(fmt::format("--threads {}: must be an integer in [1, 256]", *threads));
    }
    o.threads = *threads;
    const BladeModel model = assemble_model(scene);
    if (theta_plane) {
      if (scene.operation.speed_rad_s <= 0 && scene.damping.model == DampingModel::paper) {
        throw InputError("damping.model = \"paper\" needs operation.speed_rad_s > 0");
      }
      if (theta->empty()) {
        const double w1 = solve_modes(model, system_at(model, scene.operation.speed_rad_s, Eigen::MatrixXd::Zero(model.layout.size(), model.layout.size())),
                                      scene.operation.speed_rad_s, 1, EigenSolverKind::dense).modes.at(0).eigenvalue.imag();
        o.grid_x = parse_range("--theta", fmt::format("{}:{}:41", w1 / 4, 2.5 * w1));
      } else {
        o.grid_x = parse_range("--theta", *theta);
      }
      if (o.grid_x.front() <= 0) throw InputError(fmt::format("--theta {}: pulse frequencies must be > 0", *theta));
      o.trace = parse_range("--fmax", fmt::format("{}:{}:{}", o.grid_fbar.front(), o.grid_fbar.back(), *trace));
    } else {
      if (speeds->empty()) throw InputError("--speeds: required for --plane speed-fmax (start:stop:count in rad/s)");
      o.grid_x = parse_range("--speeds", *speeds);
      if (o.grid_x.front() <= 0) throw InputError(fmt::format("--speeds {}: speeds must be > 0", *speeds));
      o.trace = parse_range("--speeds", fmt::format("{}:{}:{}", o.grid_x.front(), o.grid_x.back(), *trace));
    }
    const bool for_people = options->output_format() == OutputFormat::table;
    const StabilityMap m = stability_map(scene, o, progress_reporter("map: points", for_people));

    const std::string json = map_json(scene, model, o, m);
    const std::string base = theta_plane ? "map_theta_fmax" : "map_speed_fmax";
    const std::vector<std::string> files = write_outputs(
        *out, base, {{base + "_curves.csv", curves_csv(m)}, {base + "_grid.csv", grid_csv(m)}}, json, "map", *chart);
    switch (options->output_format()) {
      case OutputFormat::json: fmt::print("{}", json); break;
      case OutputFormat::csv: fmt::print("{}", curves_csv(m)); break;
      case OutputFormat::table: {
        int unstable = 0, points = 0;
        for (Eigen::Index k = 0; k < m.max_abs_multiplier.size(); ++k) {
          const double v = m.max_abs_multiplier.data()[k];
          if (!std::isnan(v)) ++points, unstable += v > 1 + std::max(o.tolerance, m.max_error_estimate);
        }
        fmt::print("scene     {}\nmodel     {}\nplane     {}{}\n", scene.source, describe_model(model), *plane,
                   theta_plane ? fmt::format(" at Ω = {:g} rad/s", scene.operation.speed_rad_s)
                               : fmt::format(", θ = {}·Ω", o.engine_order));
        const CurveFidelity& f = m.curve_fidelity;
        if (!f.drawn) {
          fmt::print("curves    none: a pulse's own series needs many more harmonics in the boundary equations, not "
                     "monotonically; the shading (Floquet) shows the regions\n");
        } else {
          fmt::print("curves    {} boundary curves ({} harmonics per family, {} model{}); error over the window's "
                     "span {}{}\n",
                     m.curves.size(), f.approximation, to_string(f.reduction.kind),
                     f.reduction.kind == ReductionKind::automatic ? fmt::format(", {} vectors per load level", f.reduction.vectors)
                                                                  : "",
                     describe_error_budget(f.budget), f.tolerance_met ? "" : fmt::format(" — above --tolerance {}", o.tolerance));
        }
        const ShadingFidelity& sf = m.shading_fidelity;
        fmt::print("shading   {} of {} grid points unstable; refined to {} × {} cells with {} Floquet points; "
                   "max|ρ| relative error ≤ {:.1e} (method, every point){}\n",
                   unstable, points, m.cells_x, m.cells_y, m.samples.size(), m.max_error_estimate,
                   sf.reduction_vectors > 0
                       ? fmt::format(" + {:.1e} (reduction to {} vectors per load level, {} grid points checked "
                                     "against twice as many)", sf.reduction_error, sf.reduction_vectors,
                                     sf.checked.size())
                       : std::string("; the whole Ritz model (fewer vectors missed the tolerance)"));
        if (m.scene_point) {
          const MapPoint& p = *m.scene_point;
          fmt::print("scene     ({:g}, F̄ = {:g}): max|ρ| = {:.6g}{}\n", p.x, p.fbar, p.max_abs_multiplier,
                     p.nearest_boundary ? fmt::format("; nearest boundary along F̄ at {:.6g} ({:+d}, mode {}, order {}), "
                                                      "ΔF̄ = {:+.3g}",
                                                      p.nearest_boundary->fbar, p.nearest_boundary->multiplier,
                                                      p.nearest_boundary->mode, p.nearest_boundary->order,
                                                      p.nearest_boundary->fbar - p.fbar)
                                        : "; no boundary along F̄ in the window");
        }
        fmt::print("written   {}\n", fmt::join(files, ", "));
      }
    }
  };
}

}  // namespace bladestab::cli
