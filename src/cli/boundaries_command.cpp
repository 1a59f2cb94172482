// bladestab boundaries SCENE: boundary pulse frequencies at the scene's (Ω, F_max), or boundary
// loads at a given θ (--at-theta).
#include <fmt/format.h>

#include "bladestab/boundaries.hpp"
#include "bladestab/input_error.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "options.hpp"

namespace bladestab::cli {
namespace {

void print(const SceneOptions& options, const Scene& scene, const BladeModel& model, int approximation,
           const std::vector<Boundary>& boundaries, bool in_load) {
  const double fcr = model.blade.critical_load();
  switch (options.output_format()) {
    case OutputFormat::json: {
      JsonWriter json;
      json.begin_object()
          .value("scene", scene.source)
          .value("speed_rad_s", scene.operation.speed_rad_s)
          .value("fmax_over_fcr", scene.load.fmax_over_fcr)
          .value("approximation", approximation)
          .value("model", describe_model(model))
          .begin_array("boundaries");
      for (const Boundary& b : boundaries) {
        json.begin_object()
            .value("theta_rad_s", b.theta_rad_s)
            .value("fmax_over_fcr", b.peak_force_n / fcr)
            .value("multiplier", b.multiplier)
            .value("mode", b.mode)
            .value("order", b.order)
            .end_object();
      }
      json.end_array().end_object();
      fmt::print("{}", json.str());
      break;
    }
    case OutputFormat::csv:
      fmt::print("theta_rad_s,fmax_over_fcr,multiplier,mode,order\n");
      for (const Boundary& b : boundaries) {
        fmt::print("{},{},{},{},{}\n", b.theta_rad_s, b.peak_force_n / fcr, b.multiplier, b.mode, b.order);
      }
      break;
    case OutputFormat::table:
      fmt::print("scene          {}\nmodel          {}\n", scene.source, describe_model(model));
      fmt::print("operation      Ω = {:.6g} rad/s{}\n", scene.operation.speed_rad_s,
                 in_load ? "" : fmt::format(", F̄_max = {:.6g}", scene.load.fmax_over_fcr));
      fmt::print("approximation  {} harmonics per family (the −1 and +1 boundary equations)\n\n", approximation);
      fmt::print("{:>16} {:>14} {:>10} {:>5} {:>6}\n", "θ [rad/s]", "F̄_max", "multiplier", "mode", "order");
      for (const Boundary& b : boundaries) {
        fmt::print("{:>16.10g} {:>14.8g} {:>10} {:>5} {:>6}\n", b.theta_rad_s, b.peak_force_n / fcr,
                   b.multiplier > 0 ? "+1" : "-1", b.mode, b.order);
      }
      fmt::print("\nCombination resonances are not boundaries of this kind: check them with `bladestab stability` or `map`.\n");
      break;
  }
}

}  // namespace

Command register_boundaries(CLI::App& app) {
  auto* command = app.add_subcommand("boundaries", "boundaries of the instability regions (multiplier ±1)");
  auto options = std::make_shared<SceneOptions>();
  auto approximation = std::make_shared<int>(4);
  auto at_theta = std::make_shared<double>(0);
  auto cutoff = std::make_shared<double>(0);
  add_scene_options(*command, *options);
  command->add_option("--approximation", *approximation, "harmonics k per family (1 = Bolotin's first; default 4)");
  command->add_option("--at-theta", *at_theta, "instead: all boundary F̄_max at this pulse frequency θ [rad/s]");
  command->add_option("--cutoff-hz", *cutoff, "keep only the modes below this frequency (default: all)");
  return [=] {
    if (*approximation < 1 || *approximation > 40) {
      throw InputError(fmt::format("--approximation {}: must be an integer in [1, 40]", *approximation));
    }
    const bool in_load = command->count("--at-theta") > 0;
    if (in_load && !(*at_theta > 0)) throw InputError(fmt::format("--at-theta {}: must be > 0 rad/s", *at_theta));
    Scene scene = options->load();
    const BladeModel model = assemble_model(scene.blade, scene.model);
    if (in_load && scene.load.fmax_over_fcr == 0) scene.load.fmax_over_fcr = 1;  // the load's shape is what matters
    const double peak = scene.load.fmax_over_fcr * model.blade.critical_load();
    const PeriodicSystem sys =
        periodic_system(model, scene, load_series(scene), {ReductionKind::modal, 0, *cutoff});
    const std::vector<Boundary> found = in_load ? boundary_loads(sys, peak, *at_theta, *approximation)
                                                : boundary_frequencies(sys, peak, *approximation);
    print(*options, scene, model, *approximation, found, in_load);
  };
}

}  // namespace bladestab::cli
