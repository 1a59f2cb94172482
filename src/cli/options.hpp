#pragma once
// Command-line pieces shared by the subcommands.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bladestab/scene/allowed_range.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/scene/scene.hpp"
#include "printed_digits.hpp"

namespace bladestab::cli {

enum class OutputFormat { table, json, csv };

struct SceneOptions {
  std::string path;
  std::vector<std::string> overrides;  // --set section.key=value
  std::string format = "table";
  std::string solver = "auto";
  std::string digits = "estimate";  // --digits

  // The scene with its overrides (from an embedded run's text where it has one, embedding.hpp); a modal cut-off of its own (model.cutoff_hz) is checked as
  // check_modal_cutoff says.
  Scene load() const;
  OutputFormat output_format() const;
  EigenSolverKind eigen_solver() const;
  PrintedDigits printed_digits() const;
};

// The value of an enumeration named `name` by the library's to_string, among `values`; the first
// of them for a name that is none of theirs (the option's check has refused those). And the names,
// for that check.
template <class Enum>
Enum named(const std::string& name, std::initializer_list<Enum> values) {
  for (Enum v : values) {
    if (name == to_string(v)) return v;
  }
  return *values.begin();
}
template <class Enum>
std::vector<std::string> names_of(std::initializer_list<Enum> values) {
  std::vector<std::string> names;
  for (Enum v : values) names.emplace_back(to_string(v));
  return names;
}

// Adds SCENE, --set, --format, --solver and --digits to a subcommand; --format takes one of `formats`, the
// first the default (a command with outputs of its own, like `check`, lists them).
void add_scene_options(CLI::App& command, SceneOptions& options,
                       const std::vector<std::string>& formats = {"table", "json", "csv"});

// A command line CLI11 refused, as the one-line message says it; an unexpected argument that
// looks like an override is pointed at --set, which takes one section.key=value each time.
std::string parse_error_text(const CLI::ParseError& error);

// --threads N for a command that runs parts side by side; `threads` starts at one per core.
void add_threads_option(CLI::App& command, int& threads);

// "start:stop:count" → count evenly spaced values, start and stop in `values`; InputError naming
// `option` otherwise. Increasing (start < stop) unless `order` allows either way (start != stop).
enum class RangeOrder { increasing, either_way };
std::vector<double> parse_range(const std::string& option, const std::string& text, const AllowedRange& values,
                                RangeOrder order = RangeOrder::increasing);

// A modal cut-off keeps the unloaded modes below it, and at least the first: InputError naming
// `named` ("--cutoff-hz 0.5", "model.cutoff_hz = 0.5") where it lies at or below the first mode's
// frequency at the scene's speed, so the first would be kept alone whatever the cut-off said.
void check_modal_cutoff(const Scene& scene, double cutoff_hz, const std::string& named);

// One line describing the model, e.g. "timoshenko, legendre basis, 16 terms/field (48 dofs), axial on, coriolis on",
// with ", static tip compression 0.5 F_cr" when the scene has one.
std::string describe_model(const BladeModel& model);

// The reduction a periodic system is built on, e.g. "automatic: 3 modes at F = 0 and at the peak load +
// gyroscopic corrections → 9 of 48 dofs".
std::string describe_reduction(const ReductionSpec& reduction, int reduced_dofs, int full_dofs);

// "sinha2005/blade" for stability_maps/sinha2005/blade.toml: the scene's name in chart titles.
std::string scene_title(const Scene& scene);

}  // namespace bladestab::cli
