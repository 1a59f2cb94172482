// bladestab campbell SCENE --speeds a:b:n: frequencies versus speed, engine-order crossings,
// CSV/JSON data and a chart.

#include <fmt/format.h>

#include "bladestab/campbell.hpp"
#include "bladestab/input_error.hpp"
#include "bladestab/mode_convergence.hpp"
#include "chart.hpp"
#include "commands.hpp"
#include "error_output.hpp"
#include "json_writer.hpp"
#include "options.hpp"
#include "progress.hpp"

namespace bladestab::cli {
namespace {

constexpr double rpm_per_rad_s = 60 / 6.28318530717958647692;

// Per speed, the error of the `count` lowest modes there (each part the largest over them), from
// the same richer-basis comparison as `modes`.
std::vector<ErrorBudget> errors_by_speed(const Scene& scene, const CampbellDiagram& d, int count, EigenSolverKind solver) {
  std::vector<ErrorBudget> errors;
  for (double speed : d.speeds_rad_s) {
    Scene at = scene;
    at.operation.speed_rad_s = speed;
    errors.push_back(modes_with_error_estimate(at, count, solver).worst_budget());
  }
  return errors;
}

std::string campbell_json(const Scene& scene, const BladeModel& model, const CampbellDiagram& d,
                          const std::vector<ErrorBudget>& errors) {
  JsonWriter json;
  json.begin_object()
      .value("title", fmt::format("{} — Campbell diagram", scene_title(scene)))
      .value("scene", scene.source)
      .value("model", describe_model(model))
      .value("damping", to_string(scene.damping.model))
      .value("solver", to_string(d.solver))
      .numbers("speeds_rad_s", d.speeds_rad_s)
      .numbers("engine_orders", d.engine_orders);
  ErrorBudget worst;  // over the speeds
  for (const ErrorBudget& e : errors) {
    worst.basis = std::max(worst.basis, e.basis);
    worst.method = std::max(worst.method, e.method);
  }
  write_error_budget(json, worst);
  json.begin_array("error_by_speed");
  for (std::size_t s = 0; s < errors.size(); ++s) {
    json.begin_object().value("speed_rad_s", d.speeds_rad_s[s]);
    write_error_budget(json, errors[s]);
    json.end_object();
  }
  json.end_array().begin_array("curves");
  for (const CampbellCurve& c : d.curves) {
    json.begin_object()
        .value("mode", c.mode)
        .value("family", to_string(c.family))
        .numbers("frequency_hz", c.frequency_hz)
        .numbers("damping_ratio", c.damping_ratio)
        .numbers("correlation", c.correlation)
        .end_object();
  }
  json.end_array().begin_array("crossings");
  for (const EngineOrderCrossing& x : d.crossings) {
    json.begin_object()
        .value("engine_order", x.engine_order)
        .value("mode", x.mode)
        .value("speed_rad_s", x.speed_rad_s)
        .value("speed_rpm", x.speed_rad_s * rpm_per_rad_s)
        .value("frequency_hz", x.frequency_hz)
        .end_object();
  }
  json.end_array().end_object();
  return json.str();
}

std::string curves_csv(const CampbellDiagram& d) {
  std::string csv = "speed_rad_s,speed_rpm";
  for (const CampbellCurve& c : d.curves) csv += fmt::format(",mode_{}_{}_hz", c.mode, to_string(c.family));
  csv += "\n";
  for (std::size_t s = 0; s < d.speeds_rad_s.size(); ++s) {
    csv += fmt::format("{},{}", d.speeds_rad_s[s], d.speeds_rad_s[s] * rpm_per_rad_s);
    for (const CampbellCurve& c : d.curves) csv += fmt::format(",{}", c.frequency_hz[s]);
    csv += "\n";
  }
  return csv;
}

std::string crossings_csv(const CampbellDiagram& d) {
  std::string csv = "engine_order,mode,speed_rad_s,speed_rpm,frequency_hz\n";
  for (const EngineOrderCrossing& x : d.crossings) {
    csv += fmt::format("{},{},{},{},{}\n", x.engine_order, x.mode, x.speed_rad_s, x.speed_rad_s * rpm_per_rad_s,
                       x.frequency_hz);
  }
  return csv;
}

void print_table(const Scene& scene, const BladeModel& model, const CampbellDiagram& d,
                 const std::vector<std::string>& files) {
  fmt::print("scene     {}\nmodel     {}\nspeeds    {} from {:.6g} to {:.6g} rad/s; damping {}; solver {}\n\n",
             scene.source, describe_model(model), d.speeds_rad_s.size(), d.speeds_rad_s.front(),
             d.speeds_rad_s.back(), to_string(scene.damping.model), to_string(d.solver));
  fmt::print("{:>4}  {:<9} {:>14} {:>14} {:>9}\n", "mode", "family", "f first [Hz]", "f last [Hz]", "min MAC");
  for (const CampbellCurve& c : d.curves) {
    double worst = 1;
    for (double m : c.correlation) worst = std::min(worst, m);
    fmt::print("{:>4}  {:<9} {:>14.6g} {:>14.6g} {:>9.3f}\n", c.mode, to_string(c.family), c.frequency_hz.front(),
               c.frequency_hz.back(), worst);
  }
  fmt::print("\nengine-order crossings ({}):\n", d.crossings.size());
  fmt::print("{:>4} {:>5} {:>14} {:>12} {:>14}\n", "EO", "mode", "speed [rad/s]", "speed [rpm]", "frequency [Hz]");
  for (const EngineOrderCrossing& x : d.crossings) {
    fmt::print("{:>4} {:>5} {:>14.8g} {:>12.7g} {:>14.8g}\n", x.engine_order, x.mode, x.speed_rad_s,
               x.speed_rad_s * rpm_per_rad_s, x.frequency_hz);
  }
  if (!files.empty()) fmt::print("\nwritten: {}\n", fmt::join(files, ", "));
}

}  // namespace

Command register_campbell(CLI::App& app) {
  auto* command = app.add_subcommand("campbell", "frequencies versus rotor speed with engine-order crossings");
  auto options = std::make_shared<SceneOptions>();
  auto speeds = std::make_shared<std::string>();
  auto orders = std::make_shared<std::vector<int>>(std::vector<int>{1, 2, 3, 4});
  auto count = std::make_shared<int>(8);
  auto out = std::make_shared<std::string>(".");
  auto chart = std::make_shared<std::string>("png");
  add_scene_options(*command, *options);
  command->add_option("--speeds", *speeds, "rotor speeds in rad/s as start:stop:count, e.g. 0:600:61")->required();
  command->add_option("--engine-orders", *orders, "engine orders k of the lines f = kΩ/2π (default 1,2,3,4)")
      ->delimiter(',');
  command->add_option("--count", *count, "modes to track, lowest first (default 8)");
  add_chart_options(*command, *out, *chart, "directory for campbell.csv, campbell_crossings.csv, campbell.json and the chart");
  return [=] {
    const std::vector<double> speed_list = parse_range("--speeds", *speeds);
    if (speed_list.front() < 0) throw InputError(fmt::format("--speeds {}: speeds must be >= 0 rad/s", *speeds));
    if (*count < 1) throw InputError(fmt::format("--count {}: must be an integer >= 1", *count));
    for (int k : *orders) {
      if (k < 1) throw InputError(fmt::format("--engine-orders: {} is not allowed; engine orders are integers >= 1", k));
    }
    const Scene scene = options->load();
    const BladeModel model = assemble_model(scene.blade, scene.model);
    CampbellOptions campbell{speed_list, *orders, *count, options->eigen_solver()};
    const bool for_people = options->output_format() == OutputFormat::table;
    const CampbellDiagram diagram =
        campbell_diagram(model, scene.damping, campbell, progress_reporter("campbell: speeds", for_people));

    const std::string json =
        campbell_json(scene, model, diagram, errors_by_speed(scene, diagram, *count, options->eigen_solver()));
    const std::vector<std::string> files =
        write_outputs(*out, "campbell", {{"campbell.csv", curves_csv(diagram)}, {"campbell_crossings.csv", crossings_csv(diagram)}},
                      json, "campbell", *chart);
    switch (options->output_format()) {
      case OutputFormat::json: fmt::print("{}", json); break;
      case OutputFormat::csv: fmt::print("{}", curves_csv(diagram)); break;
      case OutputFormat::table: print_table(scene, model, diagram, files); break;
    }
  };
}

}  // namespace bladestab::cli
