// bladestab crosscheck SCENE: frequency domain against time domain, point by point.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/transient/crosscheck.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/blade/reduction.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "bladestab/transient/transient.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "finite_results.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "printed_digits.hpp"
#include "progress.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

// The Magnus work of the points' monodromies and transients (crosscheck_magnus_work) and the
// transients' samples, against --max-seconds; their histories against --max-memory.
void check_crosscheck_work(const Scene& scene, const CrosscheckOptions& o) {
  const double intervals = o.fmax_over_fcr.size() * o.revolutions * 200;
  const double states = 2.0 * dof_layout(scene.model, scene.blade.two_planes()).size() + 1;
  check_work(fmt::format("--points with {} values and --revolutions {:g} with model.terms = {}", o.fmax_over_fcr.size(),
                         o.revolutions, scene.model.terms),
             fmt::format("the monodromies and contacts of {} points", o.fmax_over_fcr.size()),
             (crosscheck_magnus_work(scene, o) + 2 * intervals * states * states) / dense_flops_per_second,
             transient_history_bytes(o.revolutions, 200));
}

// The table: per point and load, Floquet max|ρ| and the transient growth, each with its estimate,
// and whether they agree within the two.
void print_table(const Scene& scene, const std::vector<CrosscheckPoint>& result, double revolutions) {
  fmt::print("scene  {}\nspeed  {:g} rad/s, {:g} pulse(s) per revolution of {} shape, t̄c = {:g}; transients of {:g} revolutions\n\n",
             scene.source, scene.operation.speed_rad_s, load_periods_per_revolution(scene), to_string(scene.load.profile),
             scene.load.contact_time_rev, revolutions);
  fmt::print("{:>7} | {:>8} | {:>13} {:>8} | {:>16} {:>8} | {:>6} | {:>15} {:>11}\n", "F̄_max", "load", "Floquet max|ρ|",
             "± est.", "transient growth", "± est.", "agree", "RKF45 Φ: max|ρ|", "‖ΔΦ‖/‖Φ‖");
  for (const CrosscheckPoint& p : result) {
    fmt::print("{:>7g} | {:>8} | {:>13} {:>8} | {:>16} {:>8} | {:>6} | {:>15} {:>11.1e}\n", p.fmax_over_fcr,
               "cosine", fixed_to_error(p.floquet_cosine, p.floquet_cosine_error, 7), estimate_text(p.floquet_cosine_error),
               fixed_to_error(p.transient_cosine_growth, p.transient_cosine_error, 7), estimate_text(p.transient_cosine_error),
               p.cosine_agrees() ? "yes" : "NO",
               fixed_to_error(p.rkf45_max_abs_multiplier, p.monodromy_difference * p.rkf45_max_abs_multiplier, 7),
               p.monodromy_difference);
    fmt::print("{:>7} | {:>8} | {:>13} {:>8} | {:>16} {:>8} | {:>6} |\n", "", "pulse",
               fixed_to_error(p.floquet_pulse, p.floquet_pulse_error, 7), estimate_text(p.floquet_pulse_error),
               fixed_to_error(p.transient_pulse_growth, p.transient_pulse_error, 7), estimate_text(p.transient_pulse_error),
               p.pulse_agrees() ? "yes" : "NO");
  }
  for (const CrosscheckPoint& p : result) {
    for (const auto& [load, omitted] : {std::pair{"cosine", p.transient_cosine_omitted}, {"pulse", p.transient_pulse_omitted}}) {
      if (!omitted.empty()) fmt::print("F̄_max = {:g}, {}: the transient's growth is not resolved ({})\n", p.fmax_over_fcr, load, omitted);
    }
  }
  const CrosscheckPoint first = result.empty() ? CrosscheckPoint{} : result.front();
  fmt::print("\nTransient growth: of the state's change over each whole revolution (the forced periodic response\n"
             "cancels in it), carried on past the run by the revolution's own propagators for {} revolutions and\n"
             "fitted over their second half; its estimate bounds the fitted slope (twice its standard error, or 3R/m\n"
             "where a beat keeps the residuals within R), adds how far it moved from the first half, and the contact\n"
             "propagators' own error. Each transient runs the fast method on the model its Floquet\n"
             "multipliers use, so the two share its basis and reduction error and differ in their methods only\n"
             "(each ± is a method's error on that model, not against the continuum, which `stability` states):\n"
             "the cosine rows on {} modes (model.reduction), the pulse rows on {} modes of {} (the model of\n"
             "`stability`'s first round on the true train; `stability` then raises the terms or vectors to its\n"
             "tolerance, these rows keep the scene's). Floquet: auto method for the cosine load, the monodromy\n"
             "through each contact for the pulse train (as `stability` with load.approximation = \"exact\").\n",
             growth_continuation, first.cosine_modes, first.pulse_modes, first.model_modes);
  if (!result.empty() && result.front().load_periods_per_revolution != 1) {
    fmt::print("The multipliers are per load period, {:g} of them a revolution: the growth per revolution agrees\n"
               "with max|ρ| when its {:g}th root does.\n",
               result.front().load_periods_per_revolution, result.front().load_periods_per_revolution);
  }
}

// The points as JSON and CSV print them (printed_digits.hpp): each Floquet max|ρ| to its estimate,
// each transient growth to its estimate, the estimates and the monodromies'
// difference (a check) to 2 digits; the RKF45 monodromy's max|ρ|, which has no estimate of its own, to 6.
std::vector<CrosscheckPoint> as_printed(std::vector<CrosscheckPoint> points, const PrintedDigits& digits) {
  for (CrosscheckPoint& p : points) {
    p.floquet_cosine_error = digits.estimate(p.floquet_cosine_error);
    p.floquet_pulse_error = digits.estimate(p.floquet_pulse_error);
    p.floquet_cosine = digits.absolute(p.floquet_cosine, p.floquet_cosine_error);
    p.floquet_pulse = digits.absolute(p.floquet_pulse, p.floquet_pulse_error);
    p.monodromy_difference = digits.measure(p.monodromy_difference);
    p.transient_cosine_error = digits.estimate(p.transient_cosine_error);
    p.transient_pulse_error = digits.estimate(p.transient_pulse_error);
    p.transient_cosine_growth = digits.absolute(p.transient_cosine_growth, p.transient_cosine_error);
    p.transient_pulse_growth = digits.absolute(p.transient_pulse_growth, p.transient_pulse_error);
    p.rkf45_max_abs_multiplier = digits.unestimated(p.rkf45_max_abs_multiplier);
  }
  return points;
}

// Why a growth fit is not meaningful, or null.
Json omission(const std::string& omitted) { return omitted.empty() ? Json(nullptr) : Json(omitted); }

// The answer as JSON: each point's Floquet and transient numbers for both loads, with their estimates.
std::string crosscheck_json(const Scene& scene, const std::vector<CrosscheckPoint>& printed, double revolutions) {
  Json json = {{"scene", scene.source}, {"speed_rad_s", scene.operation.speed_rad_s},
               {"revolutions", revolutions},
               {"load_periods_per_revolution", printed.empty() ? 1.0 : printed.front().load_periods_per_revolution},
               {"points", Json::array()}};
  for (const CrosscheckPoint& p : printed) {
    json["points"].push_back(
        {{"fmax_over_fcr", p.fmax_over_fcr},
         {"cosine_approximation",
          {{"floquet_max_abs_multiplier", p.floquet_cosine},
           {"floquet_error_estimate", p.floquet_cosine_error},
           {"transient_growth_per_revolution", p.transient_cosine_growth},
           {"transient_growth_error_estimate", p.transient_cosine_error},
           {"transient_growth_omitted", omission(p.transient_cosine_omitted)},
           {"agree", p.cosine_agrees()},
           {"modes", p.cosine_modes},
           {"rkf45_monodromy_max_abs_multiplier", p.rkf45_max_abs_multiplier},
           {"monodromy_matrix_relative_difference", p.monodromy_difference}}},
         {"true_pulse",
          {{"floquet_max_abs_multiplier", p.floquet_pulse},
           {"floquet_error_estimate", p.floquet_pulse_error},
           {"transient_growth_per_revolution", p.transient_pulse_growth},
           {"transient_growth_error_estimate", p.transient_pulse_error},
           {"transient_growth_omitted", omission(p.transient_pulse_omitted)},
           {"agree", p.pulse_agrees()},
           {"modes", p.pulse_modes}}}});
  }
  return json_text(json);
}

}  // namespace

Command register_crosscheck(CLI::App& app) {
  auto* command = app.add_subcommand("crosscheck", "Floquet multipliers against transients; cosine approximation against the true pulse");
  auto options = std::make_shared<SceneOptions>();
  auto points = std::make_shared<std::vector<double>>(std::vector<double>{1, 2, 5, 10});
  auto revolutions = std::make_shared<double>(16);
  auto threads = std::make_shared<int>();
  add_scene_options(*command, *options);
  add_threads_option(*command, *threads);
  add_number_list_option(*command, "--points", *points, scene_limits::fmax_over_fcr,
                         "F̄_max values at the scene's speed (default 1,2,5,10)");
  // The growth fit needs 6 whole revolutions.
  add_number_option(*command, "--revolutions", *revolutions, AllowedRange::closed(6, 1000),
                    "length of each transient (default 16)");
  return [=] {
    const Scene scene = options->load();
    if (scene.operation.speed_rad_s <= 0) throw InputError("operation.speed_rad_s = 0: crosscheck needs a speed > 0");
    CrosscheckOptions o;
    o.fmax_over_fcr = *points;
    o.revolutions = *revolutions;
    o.threads = *threads;
    check_crosscheck_work(scene, o);
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
    const auto disagreeing = std::count_if(result.begin(), result.end(), [](const CrosscheckPoint& p) {
      return !p.cosine_agrees() || !p.pulse_agrees();
    });
    switch (options->output_format()) {
      case OutputFormat::json: print_json_answer(crosscheck_json(scene, printed, *revolutions)); break;
      case OutputFormat::csv:
        fmt::print("fmax_over_fcr,cosine_floquet,cosine_transient_growth,cosine_rkf45_monodromy,monodromy_relative_difference,"
                   "pulse_floquet,pulse_transient_growth,cosine_agrees,pulse_agrees\n");
        for (const CrosscheckPoint& p : printed) {
          fmt::print("{},{},{},{},{},{},{},{},{}\n", p.fmax_over_fcr, p.floquet_cosine, p.transient_cosine_growth,
                     p.rkf45_max_abs_multiplier, p.monodromy_difference, p.floquet_pulse, p.transient_pulse_growth,
                     p.cosine_agrees(), p.pulse_agrees());
        }
        break;
      case OutputFormat::table: print_table(scene, result, *revolutions);
    }
    if (disagreeing > 0) {
      throw AnswerIsNegative{fmt::format("crosscheck: {} of {} points disagree beyond their error estimates or have a "
                                         "transient growth the fit does not resolve", disagreeing, result.size())};
    }
  };
}

}  // namespace bladestab::cli
