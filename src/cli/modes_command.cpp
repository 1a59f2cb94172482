// bladestab modes SCENE: natural frequencies at the scene's speed, with error estimates.
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "bladestab/input_error.hpp"
#include "bladestab/mode_convergence.hpp"
#include "commands.hpp"
#include "error_output.hpp"
#include "json_writer.hpp"
#include "options.hpp"

namespace bladestab::cli {
namespace {

constexpr double rpm_per_rad_s = 60 / 6.28318530717958647692;

void print_modes(const SceneOptions& options, const Scene& scene, const ConvergedModes& result) {
  const ModalSolution& sol = result.solution;
  const double speed = scene.operation.speed_rad_s;
  switch (options.output_format()) {
    case OutputFormat::json: {
      JsonWriter json;
      json.begin_object()
          .value("scene", scene.source)
          .value("speed_rad_s", speed)
          .value("speed_rpm", speed * rpm_per_rad_s)
          .value("nondimensional_speed", result.model.blade.nondimensional_speed(speed))
          .value("tip_compression_over_fcr", scene.operation.tip_compression_over_fcr)
          .begin_object("model")
          .value("theory", to_string(result.model.spec.theory))
          .value("basis", to_string(result.model.spec.basis))
          .value("terms", result.model.spec.terms)
          .value("dofs", result.model.layout.size())
          .value("axial", result.model.spec.axial)
          .value("coriolis", result.model.spec.coriolis)
          .end_object()
          .value("damping", to_string(scene.damping.model))
          .value("solver", to_string(sol.solver))
          .begin_object("accuracy")
          .value("method", result.model.spec.basis == BasisKind::sine
                               ? "tail of algebraic convergence from models with N, 2N and 4N terms"
                               : "relative change against a richer model")
          .value("reference_terms", result.reference_terms)
          .value("max_relative_error", result.max_relative_error())
          .end_object();
      write_error_budget(json, result.worst_budget());
      json.begin_array("modes");
      for (std::size_t k = 0; k < sol.modes.size(); ++k) {
        const Mode& m = sol.modes[k];
        json.begin_object()
            .value("index", m.index)
            .value("family", to_string(m.family))
            .value("frequency_hz", m.frequency_hz)
            .value("lambda", m.lambda)
            .value("damping_ratio", m.damping_ratio)
            .value("relative_error", result.relative_error[k]);
        write_error_budget(json, result.budget(k));
        json.begin_object("energy_share")
            .value("rotation", m.energy_share(0))
            .value("lateral", m.energy_share(1))
            .value("axial", m.energy_share(2))
            .end_object()
            .end_object();
      }
      json.end_array().end_object();
      fmt::print("{}", json.str());
      break;
    }
    case OutputFormat::csv:
      fmt::print("index,family,frequency_hz,lambda,damping_ratio,relative_error\n");
      for (std::size_t k = 0; k < sol.modes.size(); ++k) {
        const Mode& m = sol.modes[k];
        fmt::print("{},{},{},{},{},{}\n", m.index, to_string(m.family), m.frequency_hz, m.lambda, m.damping_ratio,
                   result.relative_error[k]);
      }
      break;
    case OutputFormat::table: {
      fmt::print("scene     {}\n", scene.source);
      fmt::print("model     {}\n", describe_model(result.model));
      fmt::print("speed     {:.6g} rad/s = {:.6g} rpm, nondimensional {:.6g}; damping {}; solver {}\n", speed,
                 speed * rpm_per_rad_s, result.model.blade.nondimensional_speed(speed), to_string(scene.damping.model),
                 to_string(sol.solver));
      fmt::print("accuracy  {} against {}-term models, at most {:.1e}; digits shown are those the error supports\n\n",
                 result.model.spec.basis == BasisKind::sine ? "tail of algebraic convergence" : "relative change",
                 result.model.spec.basis == BasisKind::sine
                     ? fmt::format("{}- and {}", reference_terms(BasisKind::sine, result.model.spec.terms), result.reference_terms)
                     : fmt::format("{}", result.reference_terms),
                 result.max_relative_error());
      fmt::print("{:>4}  {:<9} {:>16} {:>16} {:>10} {:>10}\n", "mode", "family", "frequency [Hz]", "Λ", "ζ",
                 "error");
      for (std::size_t k = 0; k < sol.modes.size(); ++k) {
        const Mode& m = sol.modes[k];
        const ErrorBudget budget = result.budget(k);
        const int digits = significant_digits(budget.total());
        // ζ below 1e-12 is rounding in an undamped model's eigenvalues, not damping.
        const double zeta = std::abs(m.damping_ratio) < 1e-12 ? 0.0 : m.damping_ratio;
        fmt::print("{:>4}  {:<9} {:>#16.{}g} {:>#16.{}g} {:>10.3g} {:>10.1e}\n", m.index, to_string(m.family),
                   m.frequency_hz, digits, m.lambda, digits, zeta, budget.total());
      }
      break;
    }
  }
}

}  // namespace

Command register_modes(CLI::App& app) {
  auto* command = app.add_subcommand("modes", "natural frequencies of the rotating blade at the scene's speed");
  auto options = std::make_shared<SceneOptions>();
  auto count = std::make_shared<int>(10);
  auto tolerance = std::make_shared<double>(0);
  add_scene_options(*command, *options);
  command->add_option("--count", *count, "number of modes, lowest first (default 10)");
  command->add_option("--tolerance", *tolerance,
                      "raise the number of terms until every mode's estimated relative error is below this");
  return [options, count, tolerance, command] {
    if (*count < 1) throw InputError(fmt::format("--count {}: must be an integer >= 1", *count));
    std::optional<double> tol;
    if (command->count("--tolerance") > 0) {
      if (!(*tolerance > 0 && *tolerance < 1)) {
        throw InputError(fmt::format("--tolerance {}: must be in (0, 1)", *tolerance));
      }
      tol = *tolerance;
    }
    const Scene scene = options->load();
    print_modes(*options, scene, modes_with_error_estimate(scene, *count, options->eigen_solver(), tol));
  };
}

}  // namespace bladestab::cli
