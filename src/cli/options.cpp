#include "options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "bladestab/input_error.hpp"

namespace bladestab::cli {

OutputFormat SceneOptions::output_format() const {
  if (format == "json") return OutputFormat::json;
  if (format == "csv") return OutputFormat::csv;
  return OutputFormat::table;
}

EigenSolverKind SceneOptions::eigen_solver() const {
  if (solver == "dense") return EigenSolverKind::dense;
  if (solver == "arpack") return EigenSolverKind::arpack;
  return EigenSolverKind::automatic;
}

void add_scene_options(CLI::App& command, SceneOptions& options) {
  command.add_option("scene", options.path, "scene file (TOML)")->required();
  command.add_option("--set", options.overrides, "override a scene key: section.key=value (repeatable)")
      ->type_name("KEY=VALUE");
  command.add_option("--format", options.format, "output: table (default), json or csv")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  command.add_option("--solver", options.solver, "eigensolver: auto (default), dense (LAPACK) or arpack")
      ->check(CLI::IsMember({"auto", "dense", "arpack"}));
}

std::vector<double> parse_range(const std::string& option, const std::string& text, RangeOrder order) {
  const bool either = order == RangeOrder::either_way;
  const std::string allowed = fmt::format("must be start:stop:count with finite start {} stop and an integer count >= 2",
                                          either ? "!=" : "<");
  double start = 0, stop = 0;
  long count = 0;
  char c1 = 0, c2 = 0;
  std::size_t used = 0;
  bool ok = false;
  try {
    std::size_t p1 = text.find(':'), p2 = text.find(':', p1 == std::string::npos ? p1 : p1 + 1);
    if (p1 != std::string::npos && p2 != std::string::npos) {
      c1 = c2 = ':';
      start = std::stod(text.substr(0, p1), &used);
      ok = used == p1;
      stop = std::stod(text.substr(p1 + 1, p2 - p1 - 1), &used);
      ok = ok && used == p2 - p1 - 1;
      count = std::stol(text.substr(p2 + 1), &used);
      ok = ok && used == text.size() - p2 - 1;
    }
  } catch (const std::exception&) {
    ok = false;
  }
  if (!ok || c1 != ':' || c2 != ':' || !std::isfinite(start) || !std::isfinite(stop) ||
      !(either ? start != stop : start < stop) || count < 2 || count > 100000) {
    throw InputError(fmt::format("{} {}: {}", option, text, allowed));
  }
  std::vector<double> values(count);
  for (long i = 0; i < count; ++i) values[i] = start + (stop - start) * static_cast<double>(i) / (count - 1);
  values.back() = stop;
  return values;
}

int significant_digits(double error) {
  return std::clamp(static_cast<int>(std::floor(-std::log10(std::max(error, 1e-15)))) + 1, 3, 12);
}

std::string describe_model(const BladeModel& model) {
  const ModelSpec& s = model.spec;
  const std::string compression =
      model.static_tip_force_n == 0
          ? ""
          : fmt::format(", static tip compression {:.6g} F_cr", -model.static_tip_force_n / model.blade.critical_load());
  return fmt::format("{}, {} basis, {} terms/field ({} dofs), axial {}, coriolis {}{}", to_string(s.theory),
                     to_string(s.basis), s.terms, model.layout.size(), s.axial ? "on" : "off",
                     s.coriolis ? "on" : "off", compression);
}

std::string scene_title(const Scene& scene) {
  const std::filesystem::path p(scene.source);
  const std::string folder = p.parent_path().filename().string();
  return (folder.empty() ? "" : folder + "/") + p.stem().string();
}

void write_file(const std::string& path, const std::string& text) {
  const std::filesystem::path p(path);
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  std::ofstream out(path);
  out << text;
  if (!out) throw InputError(fmt::format("{}: cannot write this file", path));
}

}  // namespace bladestab::cli
