#include "options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "support/message_text.hpp"
#include "support/work_pool.hpp"
#include "embedding.hpp"
#include "number_options.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {

Scene SceneOptions::load() const {
  const EmbeddedRun* run = embedded_run();
  Scene scene = run != nullptr && !run->scene_text.empty() ? parse_scene(run->scene_text, path, overrides)
                                                          : load_scene(path, overrides);
  const ReductionSpec& reduction = scene.model.reduction;
  if (reduction.kind == ReductionKind::modal && reduction.cutoff_hz > 0) {
    check_modal_cutoff(scene, reduction.cutoff_hz, fmt::format("model.cutoff_hz = {:g}", reduction.cutoff_hz));
  }
  return scene;
}

void check_modal_cutoff(const Scene& scene, double cutoff_hz, const std::string& named) {
  const double speed = scene.operation.speed_rad_s;
  const UndampedModes first = undamped_modes(assemble_model(scene), speed, 0, 1, false);
  if (first.omega2(0) <= 0) return;  // statically unstable: the analysis says so itself
  const double first_hz = std::sqrt(first.omega2(0)) / two_pi;
  if (cutoff_hz <= first_hz) {
    throw InputError(fmt::format("{}: at or below the first mode, {:.6g} Hz at operation.speed_rad_s = {:g}; must be "
                                 "above it to keep any mode (0: all modes)",
                                 named, first_hz, speed));
  }
}

OutputFormat SceneOptions::output_format() const {
  if (format == "json") return OutputFormat::json;
  if (format == "csv") return OutputFormat::csv;
  return OutputFormat::table;
}

namespace {
constexpr std::initializer_list<EigenSolverKind> solvers{EigenSolverKind::automatic, EigenSolverKind::dense,
                                                         EigenSolverKind::arpack};
}  // namespace

EigenSolverKind SceneOptions::eigen_solver() const { return named(solver, solvers); }

PrintedDigits SceneOptions::printed_digits() const {
  return PrintedDigits(digits == "full" ? DigitsRule::full : DigitsRule::estimate);
}

std::string parse_error_text(const CLI::ParseError& error) {
  const std::string text = error.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&error) && text.find('=') != std::string::npos) {
    return text + "; give each override its own --set section.key=value";
  }
  return text;
}

void add_scene_options(CLI::App& command, SceneOptions& options, const std::vector<std::string>& formats) {
  command.add_option("scene", options.path, "scene file (TOML)")->required();
  command.add_option("--set", options.overrides, "override a scene key: section.key=value (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);  // one value per --set: a scene path after it stays the scene
  std::string others;
  for (std::size_t i = 1; i < formats.size(); ++i) {
    others += (i == 1 ? "" : i + 1 == formats.size() ? " or " : ", ") + formats[i];
  }
  options.format = formats.front();
  command.add_option("--format", options.format, fmt::format("output: {} (default), {}", formats.front(), others))
      ->check(CLI::IsMember(formats));
  command.add_option("--solver", options.solver, "eigensolver: auto (default), dense (LAPACK) or arpack")
      ->check(CLI::IsMember(names_of(solvers)));
  command.add_option("--digits", options.digits,
                     "digits of the numbers in JSON and CSV: estimate (default: those their error estimates support, "
                     "docs/outputs.md) or full (every double as it is)")
      ->check(CLI::IsMember({"estimate", "full"}));
  add_work_limit_options(command);
}

void add_threads_option(CLI::App& command, int& threads) {
  threads = worker_threads(0);
  add_integer_option(command, "--threads", threads, 1, 256,
                     fmt::format("worker threads (default: one per core, {} here)", threads));
}

std::vector<double> parse_range(const std::string& option, const std::string& text, const AllowedRange& values,
                                RangeOrder order) {
  constexpr long max_count = 100000;
  const bool either = order == RangeOrder::either_way;
  const auto refuse = [&] {
    const bool bounded = std::isfinite(values.lo) || std::isfinite(values.hi);
    throw InputError(fmt::format("{} {}: must be start:stop:count with finite start {} stop{}, and an integer count "
                                 "in [2, {}]", option, echoed(text), either ? "!=" : "<",
                                 bounded ? ", both in " + values.text() : "", max_count));
  };
  const std::size_t first = text.find(':'), second = first == std::string::npos ? first : text.find(':', first + 1);
  if (second == std::string::npos) refuse();
  const std::optional<double> start = read_decimal(text.substr(0, first));
  const std::optional<double> stop = read_decimal(text.substr(first + 1, second - first - 1));
  const std::optional<long> count = read_integer(text.substr(second + 1));
  if (!start || !stop || !count || !(either ? *start != *stop : *start < *stop) || !values.contains(*start) ||
      !values.contains(*stop) || *count < 2 || *count > max_count) {
    refuse();
  }
  std::vector<double> grid(*count);
  for (long i = 0; i < *count; ++i) grid[i] = *start + (*stop - *start) * static_cast<double>(i) / (*count - 1);
  grid.back() = *stop;
  return grid;
}

std::string describe_reduction(const ReductionSpec& reduction, int reduced_dofs, int full_dofs) {
  switch (reduction.kind) {
    case ReductionKind::automatic:
      return fmt::format("automatic: {} modes at F = 0 and at the peak load + gyroscopic corrections → {} of {} dofs",
                         reduction.vectors, reduced_dofs, full_dofs);
    case ReductionKind::modal:
      return reduction.cutoff_hz > 0 ? fmt::format("modal: {} modes below {:g} Hz of {} dofs", reduced_dofs,
                                                   reduction.cutoff_hz, full_dofs)
                                     : fmt::format("modal: all {} modes", full_dofs);
    case ReductionKind::none: return fmt::format("none: all {} dofs", full_dofs);
  }
  return "";
}

std::string describe_model(const BladeModel& model) {
  const ModelSpec& s = model.spec;
  const std::string compression =
      model.static_tip_force_n == 0
          ? ""
          : fmt::format(", static tip compression {:.6g} F_cr", -model.static_tip_force_n / model.blade.critical_load());
  // A tabled blade (docs/theory.md §9): two bending planes and its own buckling load as F_cr.
  const std::string planes =
      model.layout.planes == 1
          ? ""
          : fmt::format(", section table: two bending planes, F_cr = {:.6g} N (its Euler-Bernoulli buckling load at rest)",
                        model.blade.critical_load());
  return fmt::format("{}, {} basis, {} terms/field ({} dofs), axial {}, coriolis {}{}{}", to_string(s.theory),
                     to_string(s.basis), s.terms, model.layout.size(), s.axial ? "on" : "off",
                     s.coriolis ? "on" : "off", planes, compression);
}

std::string scene_title(const Scene& scene) {
  const std::filesystem::path p(scene.source);
  const std::string folder = p.parent_path().filename().string();
  return (folder.empty() ? "" : folder + "/") + p.stem().string();
}

}  // namespace bladestab::cli
