// bladestab modes SCENE: natural frequencies at the scene's speed, with error estimates.
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "commands.hpp"
#include "notes.hpp"
#include "embedding.hpp"
#include "error_output.hpp"
#include "finite_results.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

constexpr double rpm_per_rad_s = 60 / two_pi;

void require_finite(const Scene& scene, const ConvergedModes& result) {
  const FiniteResults check("modes");
  check.require("nondimensional speed", result.model.blade.nondimensional_speed(scene.operation.speed_rad_s));
  for (std::size_t k = 0; k < result.solution.modes.size(); ++k) {
    const Mode& m = result.solution.modes[k];
    const std::string of = fmt::format(" of mode {}", m.index);
    check.require("frequency" + of, m.frequency_hz)
        .require("Λ" + of, m.lambda)
        .require("damping ratio" + of, m.damping_ratio)
        .require("error estimate" + of, result.budget(k).total());
  }
}

// The modes as JSON and CSV print them (printed_digits.hpp): frequency and Λ to the mode's estimate,
// the damping ratio to the same (absolute), the energy shares (no estimate of their own) to 6
// digits. The estimates are rounded where they are written.
ConvergedModes as_printed(ConvergedModes r, const PrintedDigits& digits) {
  for (std::size_t k = 0; k < r.solution.modes.size(); ++k) {
    Mode& m = r.solution.modes[k];
    const double estimate = digits.estimate(r.budget(k).total());
    m.frequency_hz = digits.relative(m.frequency_hz, estimate);
    m.lambda = digits.relative(m.lambda, estimate);
    m.damping_ratio = digits.absolute(m.damping_ratio, estimate);
    for (double& share : m.energy_share) share = digits.unestimated(share);
  }
  return r;
}

// The answer as JSON: the scene, the model, the accuracy and each mode with its error budget and
// energy shares.
void print_modes_json(const Scene& scene, const ConvergedModes& result, const PrintedDigits& digits) {
  const ModalSolution& sol = result.solution;
  const double speed = scene.operation.speed_rad_s;
  Json json;
  json["scene"] = scene.source;
  json["speed_rad_s"] = speed;
  json["speed_rpm"] = speed * rpm_per_rad_s;
  json["nondimensional_speed"] = result.model.blade.nondimensional_speed(speed);
  json["tip_compression_over_fcr"] = scene.operation.tip_compression_over_fcr;
  json["model"] = {{"theory", to_string(result.model.spec.theory)},
                   {"basis", to_string(result.model.spec.basis)},
                   {"terms", result.model.spec.terms},
                   {"dofs", result.model.layout.size()},
                   {"axial", result.model.spec.axial},
                   {"coriolis", result.model.spec.coriolis}};
  json["damping"] = to_string(scene.damping.model);
  json["solver"] = to_string(sol.solver);
  const BasisConvergence convergence =
      basis_convergence(scene.blade, result.model.spec.basis, result.model.spec.terms);
  json["accuracy"] = {{"method", convergence == BasisConvergence::sine
                                     ? "tail of algebraic convergence from models with N, 2N and 4N terms"
                                 : convergence == BasisConvergence::kinked
                                     ? "tail of algebraic convergence (a section table, rate 2) from a richer model"
                                 : convergence == BasisConvergence::unresolved
                                     ? "tail of algebraic convergence (a section table finer than the basis, rate "
                                       "0.75) from a richer model"
                                     : "relative change against a richer model"},
                      {"reference_terms", result.reference_terms},
                      {"max_relative_error", digits.estimate(result.max_relative_error())}};
  write_error_budget(json, result.worst_budget(), digits);
  json["modes"] = Json::array();
  for (std::size_t k = 0; k < sol.modes.size(); ++k) {
    const Mode& m = sol.modes[k];
    Json& mode = json["modes"].emplace_back(Json{{"index", m.index},
                                                 {"family", to_string(m.family)},
                                                 {"frequency_hz", m.frequency_hz},
                                                 {"lambda", m.lambda},
                                                 {"damping_ratio", m.damping_ratio},
                                                 {"relative_error", digits.estimate(result.relative_error[k])}});
    write_error_budget(mode, result.budget(k), digits);
    for (std::size_t f = 0; f < m.energy_share.size(); ++f) {
      mode["energy_share"][result.model.families[f].share_name] = m.energy_share[f];
    }
  }
  print_json_answer(json_text(json));
}

// The table for people: each frequency to the significant digits its error supports.
void print_modes_table(const Scene& scene, const ConvergedModes& result) {
  const ModalSolution& sol = result.solution;
  const double speed = scene.operation.speed_rad_s;
  fmt::print("scene     {}\n", scene.source);
  fmt::print("model     {}\n", describe_model(result.model));
  fmt::print("speed     {:.6g} rad/s = {:.6g} rpm, nondimensional {:.6g}; damping {}; solver {}\n", speed,
             speed * rpm_per_rad_s, result.model.blade.nondimensional_speed(speed), to_string(scene.damping.model),
             to_string(sol.solver));
  fmt::print("accuracy  {} against {}-term models, at most {}; digits shown are those the error supports\n\n",
             basis_convergence(scene.blade, result.model.spec.basis, result.model.spec.terms) ==
                     BasisConvergence::exponential
                 ? "relative change"
                 : "tail of algebraic convergence",
             result.model.spec.basis == BasisKind::sine
                 ? fmt::format("{}- and {}", reference_terms(BasisKind::sine, result.model.spec.terms), result.reference_terms)
                 : fmt::format("{}", result.reference_terms),
             estimate_text(result.max_relative_error()));
  fmt::print("{:>4}  {:<9} {:>16} {:>16} {:>10} {:>10}\n", "mode", "family", "frequency [Hz]", "Λ", "ζ",
             "error");
  for (std::size_t k = 0; k < sol.modes.size(); ++k) {
    const Mode& m = sol.modes[k];
    const ErrorBudget budget = result.budget(k);
    // ζ below 1e-12 is rounding in an undamped model's eigenvalues, not damping.
    const double zeta = std::abs(m.damping_ratio) < 1e-12 ? 0.0 : m.damping_ratio;
    fmt::print("{:>4}  {:<9} {:>16} {:>16} {:>10.3g} {:>10}\n", m.index, to_string(m.family),
               to_significant_digits(m.frequency_hz, budget.total()), to_significant_digits(m.lambda, budget.total()), zeta,
               estimate_text(budget.total()));
  }
}

void print_modes(const SceneOptions& options, const Scene& scene, const ConvergedModes& converged) {
  require_finite(scene, converged);
  const PrintedDigits digits = options.printed_digits();
  const bool for_people = options.output_format() == OutputFormat::table;
  const ConvergedModes result = for_people ? converged : as_printed(converged, digits);
  const ModalSolution& sol = result.solution;
  switch (options.output_format()) {
    case OutputFormat::json: print_modes_json(scene, result, digits); break;
    case OutputFormat::csv:
      fmt::print("index,family,frequency_hz,lambda,damping_ratio,relative_error\n");
      for (std::size_t k = 0; k < sol.modes.size(); ++k) {
        const Mode& m = sol.modes[k];
        fmt::print("{},{},{},{},{},{}\n", m.index, to_string(m.family), m.frequency_hz, m.lambda, m.damping_ratio,
                   digits.estimate(result.relative_error[k]));
      }
      break;
    case OutputFormat::table: print_modes_table(scene, result); break;
  }
}

// The dense eigensolves before they start: the scene's model and its richer reference models (one
// for the Legendre basis, two for the sine basis, as modes_with_error_estimate solves them),
// whole_eigensolve_flops each. model.terms = 200: estimated 7.7 s, taking 2.2 s (damped 32 s, 5.2 s).
void check_modes_work(const Scene& scene) {
  const EigensolveWork work = converged_modes_work(scene.model, scene.blade.two_planes(), scene.damping.damped());
  check_work(fmt::format("model.terms = {}", scene.model.terms),
             fmt::format("the eigensolves of {}-dof models", dof_layout(scene.model, scene.blade.two_planes()).size()),
             work.flops / dense_flops_per_second, work.bytes);
}

}  // namespace

Command register_modes(CLI::App& app) {
  auto* command = app.add_subcommand("modes", "natural frequencies of the rotating blade at the scene's speed");
  auto options = std::make_shared<SceneOptions>();
  auto count = std::make_shared<int>(10);
  auto tolerance = std::make_shared<double>(0);
  add_scene_options(*command, *options);
  add_integer_option(*command, "--count", *count, 1, max_int, "number of modes, lowest first (default 10)");
  add_number_option(*command, "--tolerance", *tolerance, AllowedRange::open(0, 1),
                    "raise the number of terms until every mode's estimated relative error is below this");
  return [options, count, tolerance, command] {
    std::optional<double> tol;
    if (command->count("--tolerance") > 0) tol = *tolerance;
    const Scene scene = options->load();
    check_modes_work(scene);
    const ConvergedModes modes = modes_with_error_estimate(scene, *count, options->eigen_solver(), tol);
    print_modes(*options, scene, modes);
    if (static_cast<int>(modes.solution.modes.size()) < *count) {
      print_note(fmt::format("--count {}: the model has {} modes ({} terms per field), all listed; their errors say "
                             "how many of them the continuum blade shares",
                             *count, modes.solution.modes.size(), modes.model.spec.terms));
    }
  };
}

}  // namespace bladestab::cli
