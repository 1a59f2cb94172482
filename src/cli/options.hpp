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

  Scene load() const { return load_scene(path, overrides); }
  OutputFormat output_format() const;
  EigenSolverKind eigen_solver() const;
  PrintedDigits printed_digits() const;
};

// Adds SCENE, --set, --format, --solver and --digits to a subcommand; --format takes one of `formats`, the
// first the default (a command with outputs of its own, like `check`, lists them).
void add_scene_options(CLI::App& command, SceneOptions& options,
                       const std::vector<std::string>& formats = {"table", "json", "csv"});

// --threads N for a command that runs parts side by side; `threads` starts at one per core.
void add_threads_option(CLI::App& command, int& threads);

// "start:stop:count" → count evenly spaced values, start and stop in `values`; InputError naming
// `option` otherwise. Increasing (start < stop) unless `order` allows either way (start != stop).
enum class RangeOrder { increasing, either_way };
std::vector<double> parse_range(const std::string& option, const std::string& text, const AllowedRange& values,
                                RangeOrder order = RangeOrder::increasing);

// Significant digits worth printing for a value with relative error `error` (3 to 12).
int significant_digits(double error);

// One line describing the model, e.g. "timoshenko, legendre basis, 16 terms/field (48 dofs), axial on, coriolis on",
// with ", static tip compression 0.5 F_cr" when the scene has one.
std::string describe_model(const BladeModel& model);

// "sinha2005/blade" for stability_maps/sinha2005/blade.toml: the scene's name in chart titles.
std::string scene_title(const Scene& scene);

}  // namespace bladestab::cli
