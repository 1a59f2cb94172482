// bladestab campbell SCENE --speeds a:b:n: frequencies versus speed, engine-order crossings,
// CSV/JSON data and a chart.

#include <fmt/format.h>

#include "bladestab/modal/campbell.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/scene/scene_limits.hpp"
#include "chart.hpp"
#include "commands.hpp"
#include "embedding.hpp"
#include "error_output.hpp"
#include "json_output.hpp"
#include "number_options.hpp"
#include "options.hpp"
#include "output_files.hpp"
#include "progress.hpp"
#include "static_limits_output.hpp"
#include "work_limits.hpp"

namespace bladestab::cli {
namespace {

constexpr double rpm_per_rad_s = 60 / two_pi;

// The totals of a row of budgets.
std::vector<double> totals(const std::vector<ErrorBudget>& budgets) {
  std::vector<double> out;
  for (const ErrorBudget& b : budgets) out.push_back(b.total());
  return out;
}

// The diagram as its files print it (printed_digits.hpp): each frequency to its estimate and its
// damping ratio to the same (absolute: ζ moves by about the relative error of λ), a crossing's speed
// and frequency to the crossing's estimate; correlations and amplifications, which have no estimate
// of their own, to 6 digits. Estimates and speeds in rpm are rounded where they are written.
CampbellWithErrors as_printed(CampbellWithErrors r, const PrintedDigits& digits) {
  for (std::size_t i = 0; i < r.diagram.curves.size(); ++i) {
    CampbellCurve& c = r.diagram.curves[i];
    const std::vector<double> estimate = digits.estimate(totals(r.budget[i]));
    c.frequency_hz = digits.relative(c.frequency_hz, estimate);
    c.damping_ratio = digits.absolute(c.damping_ratio, estimate);
    c.correlation = digits.unestimated(c.correlation);
  }
  for (std::size_t k = 0; k < r.diagram.crossings.size(); ++k) {
    EngineOrderCrossing& x = r.diagram.crossings[k];
    x.speed_rad_s = digits.relative(x.speed_rad_s, r.crossing_budget[k].total());
    x.frequency_hz = digits.relative(x.frequency_hz, r.crossing_budget[k].total());
    x.amplification = digits.unestimated(x.amplification);
  }
  return r;
}

// Crossing k's speed in rpm, to its estimate.
double crossing_rpm(const CampbellWithErrors& r, std::size_t k, const PrintedDigits& digits) {
  return digits.relative(r.diagram.crossings[k].speed_rad_s * rpm_per_rad_s, r.crossing_budget[k].total());
}

// `r` as printed (as_printed).
std::string campbell_json(const Scene& scene, const CampbellWithErrors& r, const PrintedDigits& digits) {
  const CampbellDiagram& d = r.diagram;
  Json json;
  json["title"] = fmt::format("{} — Campbell diagram", scene_title(scene));
  json["scene"] = scene.source;
  json["model"] = describe_model(r.model);
  json["terms"] = r.model.spec.terms;
  json["reference_terms"] = r.reference_terms;
  json["damping"] = to_string(scene.damping.model);
  json["solver"] = to_string(d.solver);
  json["reduction"] = {{"method", d.reduced ? "reduced basis, every frequency bounded against the whole Ritz model"
                                            : "none: every speed solved whole"},
                       {"vectors", d.basis_vectors},
                       {"sample_speeds_rad_s", d.sample_speeds_rad_s}};
  json["tolerance"] = r.tolerance;
  json["speeds_rad_s"] = d.speeds_rad_s;
  json["engine_orders"] = d.engine_orders;
  write_static_limits(json, r.static_limits, speed_parameter(), "diagram", digits);
  write_error_budget(json, r.worst(), digits);
  json["error_by_speed"] = Json::array();
  for (std::size_t s = 0; s < d.speeds_rad_s.size(); ++s) {
    Json& at = json["error_by_speed"].emplace_back(Json{{"speed_rad_s", d.speeds_rad_s[s]}});
    write_error_budget(at, r.worst_at(s), digits);
  }
  json["curves"] = Json::array();
  for (std::size_t i = 0; i < d.curves.size(); ++i) {
    const CampbellCurve& c = d.curves[i];
    std::vector<std::string> families;
    for (ModeFamily f : c.families) families.push_back(to_string(f));
    json["curves"].push_back({{"mode", c.mode},
                              {"family", to_string(c.family)},
                              {"families", families},
                              {"frequency_hz", c.frequency_hz},
                              {"damping_ratio", c.damping_ratio},
                              {"correlation", c.correlation},
                              {"error_estimate", digits.estimate(totals(r.budget[i]))}});
  }
  json["crossings"] = Json::array();
  for (std::size_t k = 0; k < d.crossings.size(); ++k) {
    const EngineOrderCrossing& x = d.crossings[k];
    Json& crossing = json["crossings"].emplace_back(Json{{"engine_order", x.engine_order},
                                                         {"mode", x.mode},
                                                         {"speed_rad_s", x.speed_rad_s},
                                                         {"speed_rpm", crossing_rpm(r, k, digits)},
                                                         {"frequency_hz", x.frequency_hz},
                                                         {"amplification", x.amplification}});
    write_error_budget(crossing, r.crossing_budget[k], digits);
  }
  return json_text(json);
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

// `r` as printed (as_printed).
std::string crossings_csv(const CampbellWithErrors& r, const PrintedDigits& digits) {
  std::string csv = "engine_order,mode,speed_rad_s,speed_rpm,frequency_hz\n";
  for (std::size_t k = 0; k < r.diagram.crossings.size(); ++k) {
    const EngineOrderCrossing& x = r.diagram.crossings[k];
    csv += fmt::format("{},{},{},{},{}\n", x.engine_order, x.mode, x.speed_rad_s, crossing_rpm(r, k, digits),
                       x.frequency_hz);
  }
  return csv;
}

// A curve's families along the speeds, each change shown: "flap", or "edge>flap" where it veers.
std::string family_path(const CampbellCurve& c) {
  std::string path = to_string(c.family);
  for (std::size_t s = 1; s < c.families.size(); ++s) {
    if (c.families[s] != c.families[s - 1]) path += std::string(">") + to_string(c.families[s]);
  }
  return path;
}

void print_table(const Scene& scene, const CampbellWithErrors& r, const std::vector<std::string>& files) {
  const CampbellDiagram& d = r.diagram;
  const ErrorBudget worst = r.worst();
  fmt::print("scene     {}\nmodel     {}\nspeeds    {} from {:.6g} to {:.6g} rad/s; damping {}; solver {}\n", scene.source,
             describe_model(r.model), d.speeds_rad_s.size(), d.speeds_rad_s.front(), d.speeds_rad_s.back(),
             to_string(scene.damping.model), to_string(d.solver));
  const std::string limits = limits_line(r.static_limits, speed_parameter(), "diagram");
  if (!limits.empty()) fmt::print("limits    {}\n", limits);
  if (d.reduced) {
    fmt::print("reduction {} vectors from the modes at {} speeds, each frequency bounded against the whole model\n",
               d.basis_vectors, d.sample_speeds_rad_s.size());
  }
  const int still = r.points_not_oscillating();
  fmt::print("error     {} relative, largest over the points and crossings (tolerance {:g}; basis against {}-term "
             "models){}\n\n",
             describe_error_budget(worst), r.tolerance, fmt::join(r.reference_terms, "- and "),
             still == 0 ? "" : fmt::format("; {} points where a mode does not oscillate (overdamped, 0 Hz) are not "
                                           "held to it", still));
  fmt::print("{:>4}  {:<9} {:>16} {:>16} {:>9} {:>9}\n", "mode", "family", "f first [Hz]", "f last [Hz]", "min MAC",
             "error");
  for (std::size_t i = 0; i < d.curves.size(); ++i) {
    const CampbellCurve& c = d.curves[i];
    double lowest = 1, error = 0;
    bool oscillates = false;
    for (double m : c.correlation) lowest = std::min(lowest, m);
    for (std::size_t s = 0; s < c.frequency_hz.size(); ++s) {
      if (!(c.frequency_hz[s] > 0)) continue;  // overdamped: no frequency, held to nothing (worst())
      oscillates = true;
      error = std::max(error, r.budget[i][s].total());
    }
    const auto frequency = [error](double f) { return f > 0 ? to_significant_digits(f, error) : std::string("0"); };
    fmt::print("{:>4}  {:<9} {:>16} {:>16} {:>9.3f} {:>9}\n", c.mode, family_path(c), frequency(c.frequency_hz.front()),
               frequency(c.frequency_hz.back()), lowest, oscillates ? estimate_text(error) : std::string("—"));
  }
  fmt::print("\nengine-order crossings ({}):\n", d.crossings.size());
  fmt::print("{:>4} {:>5} {:>16} {:>14} {:>16} {:>9}\n", "EO", "mode", "speed [rad/s]", "speed [rpm]", "frequency [Hz]",
             "error");
  for (std::size_t k = 0; k < d.crossings.size(); ++k) {
    const EngineOrderCrossing& x = d.crossings[k];
    const double error = r.crossing_budget[k].total();
    fmt::print("{:>4} {:>5} {:>16} {:>14} {:>16} {:>9}\n", x.engine_order, x.mode,
               to_significant_digits(x.speed_rad_s, error), to_significant_digits(x.speed_rad_s * rpm_per_rad_s, error),
               to_significant_digits(x.frequency_hz, error), estimate_text(error));
  }
  if (!files.empty()) fmt::print("\nwritten: {}\n", fmt::join(files, ", "));
}

// The whole-model eigensolves a diagram cannot do without, before they start: the scene's model and
// its richer reference, at the three sample speeds of the reduced sweep (undamped, automatic
// solver) or at every speed (the dense sweep); whole_eigensolve_flops each, within the static limits
// (the diagram's speeds are those within them).
void check_campbell_work(const Scene& scene, std::size_t speeds, EigenSolverKind solver) {
  const bool reduced = !scene.damping.damped() && solver == EigenSolverKind::automatic;
  const double solves = reduced ? std::min<double>(3, speeds) : speeds;
  ModelSpec richer = scene.model;
  richer.terms = reference_terms(scene.model.basis, scene.model.terms);
  double flops = 0, bytes = 0;
  for (const ModelSpec& spec : {scene.model, richer}) {
    flops += solves * whole_eigensolve_flops(dof_layout(spec, scene.blade.two_planes()).size(), scene.damping.damped(),
                                             true);
    bytes = std::max(bytes, eigensolve_bytes(dof_layout(spec, scene.blade.two_planes()).size()));
  }
  check_work(fmt::format("--speeds with model.terms = {}", scene.model.terms),
             fmt::format("{:g} whole eigensolves", 2 * solves), flops / dense_flops_per_second, bytes);
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
  auto tolerance = std::make_shared<double>(1e-6);
  add_scene_options(*command, *options);
  command->add_option("--speeds", *speeds, "rotor speeds in rad/s as start:stop:count, e.g. 0:600:61")->required();
  add_integer_list_option(*command, "--engine-orders", *orders, 1, scene_limits::max_engine_order,
                          "engine orders k of the lines f = kΩ/2π (default 1,2,3,4)");
  add_integer_option(*command, "--count", *count, 1, max_int, "modes to track, lowest first (default 8)");
  add_number_option(*command, "--tolerance", *tolerance, AllowedRange::open(0, 1),
                    "wanted relative error of every frequency; the terms are raised until it is met (default 1e-6)");
  auto threads = std::make_shared<int>();
  add_threads_option(*command, *threads);
  add_chart_options(*command, *out, *chart, "directory for campbell.csv, campbell_crossings.csv, campbell.json and the chart");
  return [=] {
    const std::vector<double> speed_list = parse_range("--speeds", *speeds, scene_limits::speed_rad_s);
    check_tolerance(*tolerance);
    check_output_directory("--out", *out);
    const Scene scene = options->load();
    check_campbell_work(scene, speed_list.size(), options->eigen_solver());
    CampbellOptions campbell{speed_list, *orders, *count, options->eigen_solver()};
    campbell.threads = *threads;
    campbell.speeds_text = *speeds;
    campbell.work_flops = work_limits().seconds * dense_flops_per_second;
    const bool for_people = options->output_format() == OutputFormat::table;
    const CampbellWithErrors result =
        campbell_with_error_estimate(scene, campbell, *tolerance, progress_reporter("campbell: speeds", for_people));
    const PrintedDigits digits = options->printed_digits();
    const CampbellWithErrors printed = as_printed(result, digits);
    const std::string json = campbell_json(scene, printed, digits);
    const std::vector<std::string> files = write_outputs(
        *out, "campbell",
        {{"campbell.csv", curves_csv(printed.diagram)}, {"campbell_crossings.csv", crossings_csv(printed, digits)}}, json,
        "campbell", *chart);
    switch (options->output_format()) {
      case OutputFormat::json: print_json_answer(json); break;
      case OutputFormat::csv: fmt::print("{}", curves_csv(printed.diagram)); break;
      case OutputFormat::table: print_table(scene, result, files); break;
    }
  };
}

}  // namespace bladestab::cli
