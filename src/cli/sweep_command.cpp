// bladestab sweep SCENE --key section.key --values a:b:n: natural frequencies against any numeric
// scene key, modes tracked by shape; table, JSON, CSV and a chart.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "support/message_text.hpp"
#include "bladestab/modal/parameter_sweep.hpp"
#include "chart.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "printed_digits.hpp"
#include "output_files.hpp"
#include "progress.hpp"
#include "static_limits_output.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

bool constant(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
}

std::string sweep_title(const Scene& scene, const ParameterSweep& s) {
  const std::string speed =
      constant(s.speeds_rad_s) ? fmt::format(", Ω = {:g} rad/s", s.speeds_rad_s.front()) : std::string();
  return fmt::format("{} — natural frequencies against {}{}", scene_title(scene), s.key, speed);
}

// The swept key as the parameter of the static limits' line and JSON.
RangeParameter key_parameter(const ParameterSweep& s) {
  const std::string key = s.key;
  return {s.ascending, [key](double value) { return fmt::format("{} = {:.7g}", key, value); }, "value"};
}

// The sweep as its files print it (printed_digits.hpp): each frequency and Λ to its estimate, the
// damping ratio to the same (absolute), the correlations (no estimate of their own) to 6 digits;
// the estimates themselves to 2.
ParameterSweep as_printed(ParameterSweep s, const PrintedDigits& digits) {
  for (SweptMode& m : s.modes) {
    m.error_estimate = digits.estimate(m.error_estimate);
    m.frequency_hz = digits.relative(m.frequency_hz, m.error_estimate);
    m.lambda = digits.relative(m.lambda, m.error_estimate);
    m.damping_ratio = digits.absolute(m.damping_ratio, m.error_estimate);
    m.correlation = digits.unestimated(m.correlation);
  }
  return s;
}

// `s` as printed (as_printed); where it meets a static limit to `digits`.
std::string sweep_json(const Scene& scene, const ParameterSweep& s, const PrintedDigits& digits) {
  Json json;
  json["title"] = sweep_title(scene, s);
  json["scene"] = scene.source;
  json["key"] = s.key;
  json["values"] = s.values;
  json["speeds_rad_s"] = s.speeds_rad_s;
  json["model"] = describe_model(s.model);
  json["dofs"] = s.dofs;
  json["reference_terms"] = s.reference_terms;
  json["damping"] = to_string(scene.damping.model);
  json["solver"] = to_string(s.solver);
  write_static_limits(json, s.static_limits, key_parameter(s), "sweep", digits);
  json["matched_by"] = Json::array();
  for (ModeMatch m : s.matched_by) json["matched_by"].push_back(to_string(m));
  json["min_correlation"] = s.min_correlation();
  json["error_estimate"] = s.max_error_estimate();
  json["modes"] = Json::array();
  for (const SweptMode& m : s.modes) {
    Json families = Json::array();
    for (ModeFamily f : m.families) families.push_back(to_string(f));
    json["modes"].push_back({{"index", m.index},
                             {"family", to_string(m.family)},
                             {"families", families},
                             {"frequency_hz", m.frequency_hz},
                             {"lambda", m.lambda},
                             {"damping_ratio", m.damping_ratio},
                             {"correlation", numbers_or_null(m.correlation)},
                             {"error_estimate", m.error_estimate}});
  }
  return json_text(json);
}

std::string sweep_csv(const ParameterSweep& s) {
  std::string csv = s.key;
  for (const char* unit : {"hz", "lambda"}) {
    for (const SweptMode& m : s.modes) csv += fmt::format(",mode_{}_{}_{}", m.index, to_string(m.family), unit);
  }
  csv += "\n";
  for (std::size_t v = 0; v < s.values.size(); ++v) {
    csv += fmt::format("{}", s.values[v]);
    for (const SweptMode& m : s.modes) csv += fmt::format(",{}", m.frequency_hz[v]);
    for (const SweptMode& m : s.modes) csv += fmt::format(",{}", m.lambda[v]);
    csv += "\n";
  }
  return csv;
}

void print_table(const Scene& scene, const ParameterSweep& s, const std::vector<std::string>& files) {
  const std::size_t nv = s.values.size();
  const auto by_order = std::count(s.matched_by.begin(), s.matched_by.end(), ModeMatch::order);
  fmt::print("scene     {}\nmodel     {} (at the first value)\n", scene.source, describe_model(s.model));
  fmt::print("sweep     {}: {} values from {:.6g} to {:.6g}; {}damping {}; solver {}\n", s.key, nv, s.values.front(),
             s.values.back(),
             constant(s.speeds_rad_s) ? fmt::format("speed {:.6g} rad/s; ", s.speeds_rad_s.front()) : std::string(),
             to_string(scene.damping.model), to_string(s.solver));
  const std::string limits = limits_line(s.static_limits, key_parameter(s), "sweep");
  if (!limits.empty()) fmt::print("limits    {}\n", limits);
  fmt::print("tracking  by shape (mass-weighted MAC), lowest {:.3f}{}\n", s.min_correlation(),
             by_order == 0 ? std::string()
                           : fmt::format("; by frequency order at {} values where the dofs change", by_order));
  fmt::print("error     {} relative, largest over the points (basis against richer models, and rounding, as `modes`)\n\n",
             estimate_text(s.max_error_estimate()));
  const std::size_t width = std::max<std::size_t>(12, s.key.size());
  fmt::print("{:>{}}", s.key, width);
  for (const SweptMode& m : s.modes) fmt::print(" {:>14}", fmt::format("{} {}", m.index, to_string(m.family)));
  fmt::print("\n{:>{}}", "", width);
  for (std::size_t k = 0; k < s.modes.size(); ++k) fmt::print(" {:>14}", "[Hz]");
  fmt::print("\n");
  for (std::size_t v = 0; v < nv; ++v) {
    fmt::print("{:>{}.6g}", s.values[v], width);
    for (const SweptMode& m : s.modes) {
      fmt::print(" {:>14}", with_figures(m.frequency_hz[v], std::min(10, significant_digits(m.error_estimate[v]))));
    }
    fmt::print("\n");
  }
  if (!files.empty()) fmt::print("\nwritten: {}\n", fmt::join(files, ", "));
}

// Each value solves its model whole with the richer ones of its error estimate, as `modes` does
// (modes_with_error_estimate). A sweep of model.terms is estimated at its largest value, one of
// the damping as damped.
void check_sweep_work(const Scene& scene, const ParameterSweepOptions& o) {
  ModelSpec spec = scene.model;
  if (o.key == "model.terms") spec.terms = static_cast<int>(*std::max_element(o.values.begin(), o.values.end()));
  const bool damped = scene.damping.damped() || o.key.rfind("damping.", 0) == 0;
  const EigensolveWork work = converged_modes_work(spec, scene.blade.two_planes(), damped);
  check_work(fmt::format("--values {} with model.terms = {}", echoed(o.values_text), spec.terms),
             fmt::format("the eigensolves of {} values", o.values.size()),
             o.values.size() * work.flops / dense_flops_per_second, work.bytes);
}

}  // namespace

Command register_sweep(CLI::App& app) {
  auto* command = app.add_subcommand("sweep", "natural frequencies against any numeric scene key, modes tracked by shape");
  auto options = std::make_shared<SceneOptions>();
  auto key = std::make_shared<std::string>();
  auto values = std::make_shared<std::string>();
  auto count = std::make_shared<int>(8);
  auto out = std::make_shared<std::string>(".");
  auto chart = std::make_shared<std::string>("png");
  auto name = std::make_shared<std::string>("sweep");
  add_scene_options(*command, *options);
  command->add_option("--key", *key, "the scene key to vary, section.key (e.g. blade.slenderness)")->required();
  command->add_option("--values", *values, "its values as start:stop:count (either direction), e.g. 0.005:0.1:20")
      ->required();
  add_integer_option(*command, "--count", *count, 1, max_int, "modes to track: the lowest at the first value (default 8)");
  auto threads = std::make_shared<int>();
  add_threads_option(*command, *threads);
  add_chart_options(*command, *out, *chart, "directory for NAME.csv, NAME.json and the chart");
  command->add_option("--name", *name, "stem of the output files (default sweep)");
  return [=] {
    ParameterSweepOptions o;
    o.key = *key;
    o.values_text = *values;
    // The key's own range is the scene's to check, value by value.
    constexpr double inf = std::numeric_limits<double>::infinity();
    o.values = parse_range("--values", *values, AllowedRange::open(-inf, inf), RangeOrder::either_way);
    o.mode_count = *count;
    o.solver = options->eigen_solver();
    o.threads = *threads;
    check_file_stem(*name);
    check_output_directory("--out", *out);
    const Scene scene = options->load();
    check_sweep_work(scene, o);
    const bool for_people = options->output_format() == OutputFormat::table;
    const ParameterSweep sweep = parameter_sweep(read_scene_file(options->path), options->path, options->overrides, o,
                                                 progress_reporter("sweep: values", for_people));
    const PrintedDigits digits = options->printed_digits();
    const ParameterSweep printed = as_printed(sweep, digits);
    const std::string json = sweep_json(scene, printed, digits);
    const std::vector<std::string> files =
        write_outputs(*out, *name, {{*name + ".csv", sweep_csv(printed)}}, json, "sweep", *chart);
    switch (options->output_format()) {
      case OutputFormat::json: print_json_answer(json); break;
      case OutputFormat::csv: fmt::print("{}", sweep_csv(printed)); break;
      case OutputFormat::table: print_table(scene, sweep, files); break;
    }
  };
}

}  // namespace bladestab::cli
