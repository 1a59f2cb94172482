// bladestab boundaries SCENE: boundary pulse frequencies at the scene's (Ω, F_max), or boundary
// loads at a given θ (--at-theta), each with an estimate of its whole error; k is raised until the
// boundaries converge to --tolerance.
#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "bladestab/boundaries.hpp"
#include "bladestab/input_error.hpp"
#include "bladestab/instability_regions.hpp"
#include "commands.hpp"
#include "error_output.hpp"
#include "json_writer.hpp"
#include "options.hpp"

namespace bladestab::cli {
namespace {

void print(const SceneOptions& options, const Scene& scene, const BladeModel& model, const BoundaryRequest& request,
           const BoundaryAnalysis& result, const std::vector<InstabilityRegion>& regions) {
  const double fcr = model.blade.critical_load();
  const bool in_load = request.theta_rad_s.has_value();
  const double unit = in_load ? fcr : 1.0;  // the window in θ [rad/s] or F̄_max
  switch (options.output_format()) {
    case OutputFormat::json: {
      JsonWriter json;
      json.begin_object()
          .value("scene", scene.source)
          .value("speed_rad_s", scene.operation.speed_rad_s)
          .value("fmax_over_fcr", scene.load.fmax_over_fcr)
          .value("approximation", result.approximation)
          .value("tolerance", request.tolerance)
          .value("cutoff_hz", request.cutoff_hz)
          .value("model", describe_model(model))
          .value("max_order", request.max_order)
          .value("window_low", result.window.first / unit)
          .value("window_high", result.window.second / unit)
          .value("estimate_measure", in_load ? "relative on fmax_over_fcr" : "relative on theta_rad_s");
      write_error_budget(json, result.total());
      json.begin_array("checks");
      for (const BoundaryCheck& c : result.checks) {
        json.begin_object()
            .value("theta_rad_s", c.boundary.theta_rad_s)
            .value("fmax_over_fcr", c.boundary.peak_force_n / fcr)
            .value("multiplier", c.boundary.multiplier)
            .value("cutoff_hz", c.cutoff_hz)
            .value("multiplier_gap", c.gap)
            .value("allowed", c.allowed)
            .end_object();
      }
      json.end_array().begin_array("boundaries");
      for (const EstimatedBoundary& e : result.boundaries) {
        const Boundary& b = e.boundary;
        json.begin_object()
            .value("theta_rad_s", b.theta_rad_s)
            .value("fmax_over_fcr", b.peak_force_n / fcr)
            .value("multiplier", b.multiplier)
            .value("mode", b.mode)
            .value("order", b.order)
            .value("approximation", e.approximation);
        write_error_budget(json, e.budget);
        json.end_object();
      }
      json.end_array().begin_array("regions");
      for (const InstabilityRegion& r : regions) {
        json.begin_object()
            .value("lower", r.lower / unit)
            .value("upper", r.upper / unit)
            .value("lower_at_window", r.lower_open)
            .value("upper_at_window", r.upper_open)
            .value("multiplier", r.multiplier)
            .value("mode", r.mode)
            .value("order", r.order)
            .value("middle_max_abs_multiplier", r.middle_max_abs_multiplier)
            .end_object();
      }
      json.end_array().end_object();
      fmt::print("{}", json.str());
      break;
    }
    case OutputFormat::csv:
      fmt::print("theta_rad_s,fmax_over_fcr,multiplier,mode,order,approximation,error_estimate,basis,reduction,load,method\n");
      for (const EstimatedBoundary& e : result.boundaries) {
        const Boundary& b = e.boundary;
        fmt::print("{},{},{},{},{},{},{},{},{},{},{}\n", b.theta_rad_s, b.peak_force_n / fcr, b.multiplier, b.mode,
                   b.order, e.approximation, e.budget.total(), e.budget.basis, e.budget.reduction, e.budget.load,
                   e.budget.method);
      }
      break;
    case OutputFormat::table:
      fmt::print("scene          {}\nmodel          {}{}\n", scene.source, describe_model(model),
                 request.cutoff_hz > 0 ? fmt::format(", modes below {:g} Hz", request.cutoff_hz) : "");
      fmt::print("operation      Ω = {:.6g} rad/s{}\n", scene.operation.speed_rad_s,
                 in_load ? fmt::format(", θ = {:.6g} rad/s", *request.theta_rad_s)
                         : fmt::format(", F̄_max = {:.6g}", scene.load.fmax_over_fcr));
      fmt::print("approximation  k = {} harmonics per family: every boundary of order <= {} with {} in [{:.6g}, {:.6g}] converged to "
                 "{:.1e} against k + 2\n",
                 result.approximation, request.max_order, in_load ? "F̄_max" : "θ", result.window.first / unit, result.window.second / unit,
                 request.tolerance);
      fmt::print("error          {} relative on {}, largest over the boundaries\n", describe_error_budget(result.total()),
                 in_load ? "F̄_max" : "θ");
      for (const BoundaryCheck& c : result.checks) {
        fmt::print("check          θ = {:.6g} rad/s, F̄_max = {:.6g}: RKF45 monodromy{} has a multiplier {:.1e} from {} "
                   "(allowed {:.1e})\n",
                   c.boundary.theta_rad_s, c.boundary.peak_force_n / fcr,
                   c.cutoff_hz > 0 ? fmt::format(" (modes below {:.0f} Hz)", c.cutoff_hz) : "", c.gap,
                   c.boundary.multiplier > 0 ? "+1" : "-1", c.allowed);
      }
      fmt::print("\n{:>16} {:>14} {:>10} {:>5} {:>6} {:>9}\n", "θ [rad/s]", "F̄_max", "multiplier", "mode", "order",
                 "error");
      for (const EstimatedBoundary& e : result.boundaries) {
        const Boundary& b = e.boundary;
        // Only the digits the estimate supports, on the quantity it is relative to; the other is given.
        const int digits = significant_digits(e.budget.total());
        const auto shown = [digits](double value, bool estimated) {
          return estimated ? fmt::format("{:#.{}g}", value, digits) : fmt::format("{:.6g}", value);
        };
        fmt::print("{:>16} {:>14} {:>10} {:>5} {:>6} {:>9.1e}\n", shown(b.theta_rad_s, !in_load),
                   shown(b.peak_force_n / fcr, in_load), b.multiplier > 0 ? "+1" : "-1", b.mode, b.order,
                   e.budget.total());
      }
      if (result.boundaries.empty()) fmt::print("(none of order <= {} in the window)\n", request.max_order);
      fmt::print("\nregions in {} (each checked unstable at its middle by the Floquet multipliers)\n",
                 in_load ? "F̄_max" : "θ [rad/s]");
      for (const InstabilityRegion& r : regions) {
        fmt::print("  {}{:.6g} … {:.6g}{}  multiplier {}  mode {}  order {}  (max|ρ| = {:.4g} at the middle)\n",
                   r.lower_open ? "(window) " : "", r.lower / unit, r.upper / unit, r.upper_open ? " (window)" : "",
                   r.multiplier > 0 ? "+1" : "-1", r.mode, r.order, r.middle_max_abs_multiplier);
      }
      if (regions.empty()) fmt::print("  (none in the window)\n");
      fmt::print("\nCombination resonances are not boundaries of this kind: check them with `bladestab stability` or `map`.\n");
      break;
  }
}

}  // namespace

Command register_boundaries(CLI::App& app) {
  auto* command = app.add_subcommand("boundaries", "boundaries of the instability regions (multiplier ±1)");
  auto options = std::make_shared<SceneOptions>();
  auto request = std::make_shared<BoundaryRequest>();
  auto at_theta = std::make_shared<double>(0);
  auto range = std::make_shared<std::string>();
  add_scene_options(*command, *options);
  command->add_option("--approximation", request->first_approximation,
                      "harmonics k per family to start from (1 = Bolotin's first; default 2); raised by 2 until converged");
  command->add_option("--tolerance", request->tolerance,
                      "relative change of every boundary from k to k + 2 harmonics that ends the raising (default 1e-6)");
  command->add_option("--at-theta", *at_theta, "instead: all boundary F̄_max at this pulse frequency θ [rad/s]");
  command->add_option("--cutoff-hz", request->cutoff_hz, "keep only the modes below this frequency (default: all)");
  command->add_option("--max-order", request->max_order,
                      "highest order n (θ ≈ 2ω/n) reported and converged (default 4)");
  command->add_option("--range", *range,
                      "LO:HI, the θ window [rad/s] (F̄_max with --at-theta) reported and converged "
                      "(default θ/2:2θ of the scene; 0:2F̄_max)");
  return [=] {
    if (request->first_approximation < 1 || request->first_approximation > request->max_approximation - 4) {
      throw InputError(fmt::format("--approximation {}: must be an integer in [1, {}]", request->first_approximation,
                                   request->max_approximation - 4));
    }
    if (!(request->tolerance > 0 && request->tolerance < 1)) {
      throw InputError(fmt::format("--tolerance {}: must be in (0, 1)", request->tolerance));
    }
    if (request->max_order < 0 || request->max_order > 2 * request->max_approximation - 3) {
      throw InputError(fmt::format("--max-order {}: must be an integer in [0, {}]", request->max_order,
                                   2 * request->max_approximation - 3));
    }
    if (!(request->cutoff_hz >= 0)) throw InputError(fmt::format("--cutoff-hz {}: must be >= 0 Hz", request->cutoff_hz));
    const bool in_load = command->count("--at-theta") > 0;
    if (in_load && !(*at_theta > 0)) throw InputError(fmt::format("--at-theta {}: must be > 0 rad/s", *at_theta));
    if (in_load) request->theta_rad_s = *at_theta;
    const Scene scene = options->load();
    const BladeModel model = assemble_model(scene);
    if (!range->empty()) {
      double lo = 0, hi = 0;
      char colon = 0, extra = 0;
      if (std::sscanf(range->c_str(), "%lf %c %lf %c", &lo, &colon, &hi, &extra) != 3 || colon != ':' ||
          !(lo >= 0 && hi > lo)) {
        throw InputError(fmt::format("--range {}: must be LO:HI with 0 <= LO < HI", *range));
      }
      const double unit = in_load ? model.blade.critical_load() : 1.0;  // F̄_max → N
      request->window = std::make_pair(lo * unit, hi * unit);
    }
    const BoundaryAnalysis analysis = boundaries_with_error_estimate(scene, *request);
    print(*options, scene, model, *request, analysis, instability_regions(scene, *request, analysis));
  };
}

}  // namespace bladestab::cli
