// bladestab crosscheck SCENE: frequency domain against time domain, point by point.
#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/transient/crosscheck.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "bladestab/transient/transient.hpp"
#include "commands.hpp"
#include "finite_results.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

// Two transients per point (the cosine load and the true pulse, adaptive RKF45 at 1e-8) dominate:
// their steps never exceed the stiffest mode's cap (transient.hpp).
void check_crosscheck_work(const Scene& scene, std::size_t points, double revolutions) {
  const BladeModel model = assemble_model(scene);
  TransientOptions o;
  const double duration = revolutions * two_pi / scene.operation.speed_rad_s;
  const double steps = 2 * points * duration / transient_step(model, scene, o, duration).step_s;
  check_work(fmt::format("--points with {} values and --revolutions {:g} with model.terms = {}", points, revolutions,
                         scene.model.terms),
             fmt::format("{:.3g} RKF45 steps of a {}-dof model", steps, model.layout.size()),
             rkf45_seconds(steps, model.layout.size()), transient_history_bytes(revolutions, o.samples_per_revolution));
}

// The points as JSON and CSV print them (printed_digits.hpp): each Floquet max|ρ| to its estimate,
// the estimates, the series' tail and the monodromies' difference (a check) to 2 digits; the transients'
// growth and the RKF45 monodromy's max|ρ|, which have no estimate of their own, to 6.
std::vector<CrosscheckPoint> as_printed(std::vector<CrosscheckPoint> points, const PrintedDigits& digits) {
  for (CrosscheckPoint& p : points) {
    p.floquet_cosine_error = digits.estimate(p.floquet_cosine_error);
    p.floquet_pulse_error = digits.estimate(p.floquet_pulse_error);
    p.floquet_cosine = digits.absolute(p.floquet_cosine, p.floquet_cosine_error);
    p.floquet_pulse = digits.absolute(p.floquet_pulse, p.floquet_pulse_error);
    p.pulse_series_tail = digits.estimate(p.pulse_series_tail);
    p.monodromy_difference = digits.measure(p.monodromy_difference);
    p.transient_cosine_growth = digits.unestimated(p.transient_cosine_growth);
    p.transient_pulse_growth = digits.unestimated(p.transient_pulse_growth);
    p.rkf45_max_abs_multiplier = digits.unestimated(p.rkf45_max_abs_multiplier);
  }
  return points;
}

}  // namespace

Command register_crosscheck(CLI::App& app) {
  auto* command = app.add_subcommand("crosscheck", "Floquet multipliers against transients; cosine approximation against the true pulse");
  auto options = std::make_shared<SceneOptions>();
  auto points = std::make_shared<std::vector<double>>(std::vector<double>{1, 2, 5, 10});
  auto revolutions = std::make_shared<double>(16);
  add_scene_options(*command, *options);
  add_number_list_option(*command, "--points", *points, scene_limits::fmax_over_fcr,
                         "F̄_max values at the scene's speed (default 1,2,5,10)");
  // The growth fit needs 6 whole revolutions.
  add_number_option(*command, "--revolutions", *revolutions, AllowedRange::closed(6, 1000),
                    "length of each transient (default 16)");
  return [=] {
    const Scene scene = options->load();
    if (scene.operation.speed_rad_s <= 0) throw InputError("operation.speed_rad_s = 0: crosscheck needs a speed > 0");
    check_crosscheck_work(scene, points->size(), *revolutions);
    CrosscheckOptions o;
    o.fmax_over_fcr = *points;
    o.revolutions = *revolutions;
    o.progress = progress_reporter("crosscheck: points", options->output_format() == OutputFormat::table);
    const std::vector<CrosscheckPoint> result = crosscheck(scene, o);
    const FiniteResults check("crosscheck");
    for (const CrosscheckPoint& p : result) {
      check.require("cosine Floquet max|ρ|", p.floquet_cosine)
          .require("cosine transient growth", p.transient_cosine_growth)
          .require("RKF45 monodromy max|ρ|", p.rkf45_max_abs_multiplier)
          .require("monodromy difference", p.monodromy_difference)
          .require("pulse Floquet max|ρ|", p.floquet_pulse)
          .require("pulse transient growth", p.transient_pulse_growth);
    }
    const std::vector<CrosscheckPoint> printed = as_printed(result, options->printed_digits());
    switch (options->output_format()) {
      case OutputFormat::json: {
        Json json = {{"scene", scene.source}, {"speed_rad_s", scene.operation.speed_rad_s},
                     {"revolutions", *revolutions}, {"points", Json::array()}};
        for (const CrosscheckPoint& p : printed) {
          json["points"].push_back(
              {{"fmax_over_fcr", p.fmax_over_fcr},
               {"cosine_approximation",
                {{"floquet_max_abs_multiplier", p.floquet_cosine},
                 {"floquet_error_estimate", p.floquet_cosine_error},
                 {"transient_growth_per_revolution", p.transient_cosine_growth},
                 {"rkf45_monodromy_max_abs_multiplier", p.rkf45_max_abs_multiplier},
                 {"monodromy_matrix_relative_difference", p.monodromy_difference}}},
               {"true_pulse",
                {{"floquet_max_abs_multiplier", p.floquet_pulse},
                 {"floquet_error_estimate", p.floquet_pulse_error},
                 {"load_harmonics", p.pulse_harmonics},
                 {"load_relative_tail", p.pulse_series_tail},
                 {"transient_growth_per_revolution", p.transient_pulse_growth}}}});
        }
        fmt::print("{}", json_text(json));
        break;
      }
      case OutputFormat::csv:
        fmt::print("fmax_over_fcr,cosine_floquet,cosine_transient_growth,cosine_rkf45_monodromy,monodromy_relative_difference,"
                   "pulse_floquet,pulse_transient_growth,pulse_harmonics\n");
        for (const CrosscheckPoint& p : printed) {
          fmt::print("{},{},{},{},{},{},{},{}\n", p.fmax_over_fcr, p.floquet_cosine, p.transient_cosine_growth,
                     p.rkf45_max_abs_multiplier, p.monodromy_difference, p.floquet_pulse, p.transient_pulse_growth,
                     p.pulse_harmonics);
        }
        break;
      case OutputFormat::table:
        fmt::print("scene  {}\nspeed  {:g} rad/s, {} pulse(s) per revolution of {} shape, t̄c = {:g}; transients of {:g} revolutions\n\n",
                   scene.source, scene.operation.speed_rad_s, scene.load.pulses_per_rev, to_string(scene.load.profile),
                   scene.load.contact_time_rev, *revolutions);
        fmt::print("{:>7} | {:^60} | {:^40}\n", "", "paper's cosine approximation (42)", "true pulse train");
        fmt::print("{:>7} | {:>15} {:>16} {:>15} {:>11} | {:>15} {:>8} {:>15}\n", "F̄_max", "Floquet max|ρ|",
                   "transient growth", "RKF45 Φ: max|ρ|", "‖ΔΦ‖/‖Φ‖", "Floquet max|ρ|", "harm.", "transient growth");
        for (const CrosscheckPoint& p : result) {
          fmt::print("{:>7g} | {:>15.7f} {:>16.5f} {:>15.7f} {:>11.1e} | {:>15.7f} {:>8} {:>15.5f}\n", p.fmax_over_fcr,
                     p.floquet_cosine, p.transient_cosine_growth, p.rkf45_max_abs_multiplier, p.monodromy_difference,
                     p.floquet_pulse, p.pulse_harmonics, p.transient_pulse_growth);
        }
        fmt::print("\nTransient growth: of the state's change over each whole revolution, fitted over the second half of\n"
                   "the run (the forced periodic response cancels in the change). Floquet: auto method for the cosine load, monodromy for the pulse series.\n");
    }
  };
}

}  // namespace bladestab::cli
