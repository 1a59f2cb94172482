// Every command of the program end to end on a small scene (the paper blade as an Euler–Bernoulli
// beam, four terms per field): --format json and --format csv (check: json and junit) parsed, their
// structure asserted, one number or more per command against a value computed here, and the charts
// the commands draw (matplotlib, Debian's /usr/bin/python3) checked as files: PNG of
// figsize × 150 dpi from scripts/charts/ (FIGSIZE 8 × 5.5 in; transient 10 × 7; sweep 11 × 5),
// SVG non-empty.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/transient/transient.hpp"
#include "reference/first_order_modes.hpp"
#include "reference/odeint_monodromy.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::Json;

namespace {

namespace fs = std::filesystem;
constexpr double pi = 3.14159265358979323846;

const std::vector<std::string> small{"model.theory=euler-bernoulli", "model.terms=4"};

// A fresh output directory for one command.
fs::path output_dir(const std::string& name) {
  const fs::path dir = testing_support::scratch() / ("end_to_end_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// bladestab COMMAND SCENE --set <small> MORE...; exit 0 and nothing on stderr required, or with
// `note`, one line that starts with it.
std::string run(const std::string& command, const std::vector<std::string>& more, const std::string& note = "",
                const std::string& scene = testing_support::paper_scene_path()) {
  std::vector<std::string> args{command, scene};
  for (const std::string& key : small) args.insert(args.end(), {"--set", key});
  args.insert(args.end(), more.begin(), more.end());
  const testing_support::Outcome o = testing_support::run_bladestab(args, {120});
  INFO(o.command << ": " << testing_support::describe(o) << "\n" << o.err);
  REQUIRE(WIFEXITED(o.wait_status));
  REQUIRE(WEXITSTATUS(o.wait_status) == 0);
  if (note.empty()) {
    REQUIRE(o.err.empty());
  } else {
    REQUIRE(o.err.rfind(note, 0) == 0);
    REQUIRE(o.err.find('\n') + 1 == o.err.size());
  }
  return o.out;
}

Json run_json(const std::string& command, std::vector<std::string> more, const std::string& note = "") {
  more.insert(more.end(), {"--format", "json"});
  return testing_support::parse_json(run(command, more, note));
}

// A CSV table: its header and its rows of fields (the program quotes nothing it writes).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    REQUIRE(it != header.end());
    return static_cast<std::size_t>(it - header.begin());
  }
  double number(std::size_t row, const std::string& name) const { return std::stod(rows.at(row).at(column(name))); }
};

Csv parse_csv(const std::string& text) {
  Csv csv;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    if (csv.header.empty()) {
      csv.header = fields;
    } else {
      INFO("CSV row: " << line);
      CHECK(fields.size() == csv.header.size());
      csv.rows.push_back(fields);
    }
  }
  return csv;
}

Csv run_csv(const std::string& command, std::vector<std::string> more, const std::string& note = "") {
  more.insert(more.end(), {"--format", "csv"});
  return parse_csv(run(command, more, note));
}

Csv read_csv(const fs::path& path) { return parse_csv(testing_support::read_text(path)); }

// Width and height from a PNG's IHDR chunk (bytes 16–23, big-endian), after checking the signature.
std::pair<int, int> png_size(const fs::path& path) {
  const std::string bytes = testing_support::read_text(path);
  REQUIRE(bytes.size() > 24);
  REQUIRE(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  REQUIRE(bytes.compare(12, 4, "IHDR") == 0);
  const auto be32 = [&](std::size_t at) {
    int v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = v * 256 + static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

void check_png(const fs::path& path, int width, int height) {
  INFO(path);
  REQUIRE(fs::exists(path));
  CHECK(fs::file_size(path) > 10000);
  CHECK(png_size(path) == std::pair{width, height});
}

// Λ₁ of the Euler–Bernoulli cantilever: x² for the first root x of 1 + cosh x cos x = 0.
double euler_bernoulli_lambda1() {
  double lo = 1.5, hi = 2.5;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((1 + std::cosh(mid) * std::cos(mid) > 0) ? lo : hi) = mid;
  }
  return lo * lo;
}

// The small scene's model with `terms`, the paper's speed Ω = 300 rad/s unless given.
Scene small_scene(int terms, std::vector<std::string> more = {}) {
  more.insert(more.begin(), {"model.theory=euler-bernoulli", "model.terms=" + std::to_string(terms)});
  return testing_support::paper_scene(more);
}

// max|ρ| of the cosine load (42) on the scene's periodic system (its reduction), by Fehlberg 7(8).
double odeint_max_rho(const Scene& s, const ReductionSpec& reduction) {
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s), reduction);
  const double peak = s.load.fmax_over_fcr * m.blade.critical_load(), theta = sys.angular_frequency;
  const double F0 = sys.coefficients[0].real();
  const Eigen::MatrixXd phi = reference::odeint_propagator(
      sys.A0, sys.B, [&](double t) { return -peak / 2 + peak / 2 * std::cos(theta * t) - F0; }, {}, sys.period(), 1e-12);
  return phi.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("end to end: modes, json and csv, mode 1 at rest is the Euler-Bernoulli cantilever's", "[end_to_end][modes]") {
  const std::vector<std::string> at_rest{"--set", "operation.speed_rad_s=0", "--count", "3"};
  const Json j = run_json("modes", at_rest);
  const Csv c = run_csv("modes", at_rest);
  REQUIRE(j["modes"].size() == 3);
  CHECK(j["model"]["theory"].text == "euler-bernoulli");
  CHECK(j["model"]["terms"].number == 4);
  CHECK(c.header == std::vector<std::string>{"index", "family", "frequency_hz", "lambda", "damping_ratio", "relative_error"});
  REQUIRE(c.rows.size() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(j["modes"][k]["index"].number == k + 1);
    CHECK(c.number(k, "frequency_hz") == Approx(j["modes"][k]["frequency_hz"].number).epsilon(1e-15));
  }
  // Four Legendre terms: Λ₁ within 1e-5 of the closed form (measured 1.5e-6), and its printed estimate covers that.
  const double exact = euler_bernoulli_lambda1(), lambda1 = j["modes"][0]["lambda"].number;
  CHECK(std::abs(lambda1 / exact - 1) < 1e-5);
  CHECK(std::abs(lambda1 / exact - 1) <= j["modes"][0]["error_estimate"].number);
}

TEST_CASE("end to end: campbell, json, csv, crossings and PNG, mode 1 at rest is the cantilever's", "[end_to_end][campbell][parallel]") {
  const fs::path dir = output_dir("campbell");
  const std::vector<std::string> more{"--speeds", "0:600:4", "--count", "3", "--out", dir.string()};
  const Json j = run_json("campbell", {more.begin(), more.end()});
  std::vector<std::string> csv_args = more;
  csv_args.insert(csv_args.end(), {"--chart", "none"});
  const Csv c = run_csv("campbell", csv_args);
  REQUIRE(j["curves"].size() == 3);
  CHECK(j["speeds_rad_s"].numbers() == std::vector<double>{0, 200, 400, 600});
  REQUIRE(c.rows.size() == 4);
  CHECK(c.header.at(0) == "speed_rad_s");
  CHECK(c.header.size() == 2 + 3);
  for (std::size_t k = 0; k < 3; ++k) CHECK(j["curves"][k]["frequency_hz"].size() == 4);
  CHECK(read_csv(dir / "campbell.csv").rows.size() == 4);
  const Csv crossings = read_csv(dir / "campbell_crossings.csv");
  CHECK(crossings.header == std::vector<std::string>{"engine_order", "mode", "speed_rad_s", "speed_rpm", "frequency_hz"});
  CHECK(crossings.rows.size() == j["crossings"].size());
  // A crossing lies on its engine-order line, f = kΩ/2π, within what its printed digits resolve:
  // f and Ω are each rounded to the crossing's relative estimate (docs/outputs.md).
  for (std::size_t k = 0; k < crossings.rows.size(); ++k) {
    CHECK(crossings.number(k, "frequency_hz") ==
          Approx(crossings.number(k, "engine_order") * crossings.number(k, "speed_rad_s") / (2 * pi))
              .epsilon(j["crossings"][k]["error_estimate"].number));
  }
  // Mode 1 at rest against the closed form through the blade's Λ = ω L² sqrt(ρA/(EI)).
  const BladeModel m = assemble_model(small_scene(4));
  const double f1 = euler_bernoulli_lambda1() / (m.blade.L * m.blade.L) * std::sqrt(m.blade.E * m.blade.I / (m.blade.rho * m.blade.A)) / (2 * pi);
  CHECK(c.number(0, c.header[2]) == Approx(f1).epsilon(1e-6));
  check_png(dir / "campbell.png", 1200, 825);
}

TEST_CASE("end to end: stability, json and csv, max|rho| against Runge-Kutta 7(8) on the same system", "[end_to_end][stability][parallel][long_under_sanitizers]") {
  const Json j = run_json("stability", {});
  const Csv c = run_csv("stability", {});
  const std::size_t count = j["multipliers"].size();
  CHECK(count == 2 * j["reduced_dofs"].number);
  CHECK(j["log_decrements"].size() == count);
  CHECK(c.header == std::vector<std::string>{"index", "re", "im", "abs", "log_decrement"});
  REQUIRE(c.rows.size() == count);
  CHECK(c.number(0, "abs") == Approx(j["max_abs_multiplier"].number).epsilon(1e-15));
  // The system the answer reports (its terms and reduction), integrated independently.
  const Scene s = small_scene(static_cast<int>(j["terms"].number));
  const double reference = odeint_max_rho(
      s, {ReductionKind::automatic, static_cast<int>(j["reduction_vectors"].number), 0});
  INFO("max|ρ| " << j["max_abs_multiplier"].number << ", Fehlberg 7(8) " << reference << ", method estimate "
                 << j["error_budget"]["method"].number);
  // The printed max|ρ| is rounded to the decade of the total estimate (docs/outputs.md): half that unit more.
  CHECK(std::abs(j["max_abs_multiplier"].number - reference) <=
        j["error_budget"]["method"].number + 1e-9 + testing_support::half_printed_unit(j["error_estimate"].number));
  CHECK_FALSE(j["stable"].boolean);
}

TEST_CASE("end to end: boundaries, json and csv, a multiplier of the reference monodromy at -1 there",
          "[end_to_end][boundaries][parallel][long_under_sanitizers]") {
  const std::vector<std::string> more{"--max-order", "1", "--set", "model.axial=false"};
  // The four-term basis is ~1e-3 from the continuum, above the harmonics' --tolerance: said in one line.
  const std::string note = "bladestab: note: boundaries: the whole estimate ";
  const Json j = run_json("boundaries", more, note);
  const Csv c = run_csv("boundaries", more, note);
  CHECK_FALSE(j["tolerance_met"].boolean);
  CHECK(j["error_estimate"].number > j["tolerance"].number);
  REQUIRE(j["boundaries"].size() >= 2);
  REQUIRE(c.rows.size() == j["boundaries"].size());
  CHECK(c.header == std::vector<std::string>{"theta_rad_s", "fmax_over_fcr", "multiplier", "mode", "order",
                                             "approximation", "error_estimate", "basis", "reduction", "load", "method",
                                             "converged", "last_change", "check_failed"});
  const Json& first = j["boundaries"][0];
  CHECK(c.number(0, "theta_rad_s") == Approx(first["theta_rad_s"].number).epsilon(1e-15));
  // At the boundary's θ the whole 4-term bending model's monodromy (Fehlberg 7(8)) has a multiplier at
  // its family's ±1: a double one, moved by √ of the boundary's error (≤ 1e-3 relative here).
  const double theta = first["theta_rad_s"].number;
  const Scene s = small_scene(4, {"model.axial=false", "load.pulse_frequency_hz=" + std::to_string(theta / (2 * pi))});
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s), {ReductionKind::none, 0, 0});
  const double peak = s.load.fmax_over_fcr * m.blade.critical_load(), F0 = sys.coefficients[0].real();
  const Eigen::MatrixXd phi = reference::odeint_propagator(
      sys.A0, sys.B, [&](double t) { return -peak / 2 + peak / 2 * std::cos(sys.angular_frequency * t) - F0; }, {},
      sys.period(), 1e-12);
  const Eigen::VectorXcd rho = phi.eigenvalues();
  double gap = 1e300;
  for (Eigen::Index k = 0; k < rho.size(); ++k) gap = std::min(gap, std::abs(rho(k) - first["multiplier"].number));
  INFO("boundary θ = " << theta << " rad/s (estimate " << first["error_estimate"].number << "): gap " << gap);
  CHECK(gap < 0.1);
  CHECK(gap < 3 * std::sqrt(first["error_estimate"].number));
}

TEST_CASE("end to end: map, json, csv, grid and curve files, PNG and SVG, the scene point's max|rho|",
          "[end_to_end][map][parallel][long_under_sanitizers]") {
  const fs::path dir = output_dir("map");
  const std::vector<std::string> grid{"--plane", "theta-fmax", "--theta", "100:900:5", "--fmax", "0:10:3", "--trace",
                                      "11", "--resolution", "10x6", "--max-order", "1", "--out", dir.string(),
                                      "--set", "model.axial=false"};
  const Json j = run_json("map", grid);
  std::vector<std::string> svg = grid;
  svg.insert(svg.end(), {"--chart", "svg"});
  const Csv c = run_csv("map", svg);
  CHECK(j["plane"].text == "theta-fmax");
  CHECK(j["grid"]["x"].numbers() == std::vector<double>{100, 300, 500, 700, 900});
  CHECK(j["grid"]["y"].numbers() == std::vector<double>{0, 5, 10});
  REQUIRE(j["grid"]["max_abs_multiplier"].size() == 3);
  CHECK(c.header == std::vector<std::string>{"curve", "multiplier", "mode", "order", "x_rad_s", "fmax_over_fcr"});
  CHECK(!c.rows.empty());
  const Csv grid_file = read_csv(dir / "map_theta_fmax_grid.csv");
  CHECK(grid_file.header == std::vector<std::string>{"x_rad_s", "fmax_over_fcr", "max_abs_multiplier"});
  CHECK(grid_file.rows.size() == 15);
  CHECK(read_csv(dir / "map_theta_fmax_curves.csv").rows.size() == c.rows.size());
  // The scene point (θ = 300 rad/s, F̄ = 5) against the whole 4-term bending model by Fehlberg 7(8),
  // within the shading's printed relative error.
  const double reference = odeint_max_rho(small_scene(4, {"model.axial=false"}), {ReductionKind::none, 0, 0});
  const double point = j["scene_point"]["max_abs_multiplier"].number;
  INFO("scene point " << point << ", reference " << reference << ", shading error " << j["shading_max_relative_error"].number);
  // The printed max|ρ| is rounded to the decade of the shading's accuracy — the default --tolerance
  // 1e-3 or the estimate, method, reduction and basis, if larger (docs/outputs.md): half that unit more.
  const double shading = std::max(1e-3, j["shading_max_relative_error"].number + j["shading_reduction_error"].number +
                                            j["shading_basis_error"].number);
  CHECK(std::abs(point / reference - 1) <=
        j["shading_max_relative_error"].number + testing_support::half_printed_unit(shading * point) / point);
  CHECK(j["grid"]["max_abs_multiplier"][1][1].number == Approx(point).epsilon(j["shading_max_relative_error"].number));
  check_png(dir / "map_theta_fmax.png", 1200, 825);
  REQUIRE(fs::exists(dir / "map_theta_fmax.svg"));
  CHECK(testing_support::read_text(dir / "map_theta_fmax.svg").find("<svg") != std::string::npos);
}

TEST_CASE("end to end: transient, json, csv and PNG, the static stretch and the tip load's range",
          "[end_to_end][transient]") {
  const fs::path dir = output_dir("transient");
  // Every digit: the static stretch and the load's bound are checked to 1e-12, far below the
  // integration tolerance the default output prints to (docs/outputs.md).
  const std::vector<std::string> run_args{"--revolutions", "1", "--samples-per-rev", "100", "--out", dir.string(),
                                          "--digits", "full"};
  const Json j = run_json("transient", run_args);
  std::vector<std::string> csv_args = run_args;
  csv_args.insert(csv_args.end(), {"--chart", "none"});
  const Csv c = run_csv("transient", csv_args);
  REQUIRE(c.rows.size() == 101);
  for (const char* column : {"time_s", "tip_lateral_m", "tip_axial_m", "axial_force_n", "friction_force_n",
                             "total_energy_j", "work_j", "energy_balance_error_j"}) {
    c.column(column);
  }
  CHECK(read_csv(dir / "transient.csv").rows.size() == 101);
  // The static stretch against the test's own solve of K(Ω) f = Ω² P_cf1 (docs/theory.md §1's ≈ 2 mm).
  const BladeModel m = assemble_model(small_scene(4));
  const double stretch = m.tip_axial.dot(m.stiffness(300).ldlt().solve(Eigen::VectorXd(300.0 * 300.0 * m.P_cf1)));
  CHECK(j["static_tip_axial_m"].number == Approx(stretch).epsilon(1e-12));
  CHECK(c.number(0, "tip_axial_m") == Approx(stretch).epsilon(1e-12));
  CHECK(stretch == Approx(2.0e-3).epsilon(0.02));
  // The tip load is compressive and at most F_max = F̄ F_cr = 5 π²EI/(4L²).
  const double peak = 5 * pi * pi * m.blade.E * m.blade.I / (4 * m.blade.L * m.blade.L);
  for (std::size_t k = 0; k < c.rows.size(); ++k) {
    CHECK(c.number(k, "axial_force_n") <= 0);
    CHECK(c.number(k, "axial_force_n") >= -peak * (1 + 1e-12));
  }
  CHECK(j["energy_balance"]["max_error_j"].number < 1e-6 * j["energy_balance"]["vibration_energy_j"].number);
  check_png(dir / "transient.png", 1500, 1050);
}

TEST_CASE("end to end: transient, the same run on one and two threads prints the same bytes", "[end_to_end][transient]") {
  // The self-check's wall time ("seconds") had made every two runs differ in JSON and table.
  const std::vector<std::string> args{"--revolutions", "1", "--chart", "none", "--out", output_dir("transient_threads").string()};
  for (const char* format : {"json", "table"}) {
    std::vector<std::string> one = args, two = args;
    one.insert(one.end(), {"--format", format, "--threads", "1"});
    two.insert(two.end(), {"--format", format, "--threads", "2"});
    INFO(format);
    CHECK(run("transient", one) == run("transient", two));
  }
}

TEST_CASE("end to end: crosscheck, json and csv, the cosine approximation's Floquet max|rho| against Runge-Kutta 7(8)",
          "[end_to_end][crosscheck]") {
  const std::vector<std::string> more{"--points", "5", "--revolutions", "6", "--set", "model.axial=false"};
  const Json j = run_json("crosscheck", more);
  const Csv c = run_csv("crosscheck", more);
  REQUIRE(j["points"].size() == 1);
  REQUIRE(c.rows.size() == 1);
  CHECK(c.header.at(0) == "fmax_over_fcr");
  const Json& cosine = j["points"][0]["cosine_approximation"];
  CHECK(c.number(0, "cosine_floquet") == Approx(cosine["floquet_max_abs_multiplier"].number).epsilon(1e-15));
  const double reference = odeint_max_rho(small_scene(4, {"model.axial=false"}), {ReductionKind::none, 0, 0});
  INFO("Floquet " << cosine["floquet_max_abs_multiplier"].number << ", reference " << reference);
  CHECK(cosine["floquet_max_abs_multiplier"].number == Approx(reference).epsilon(1e-6));
  CHECK(cosine["rkf45_monodromy_max_abs_multiplier"].number == Approx(reference).epsilon(1e-6));
  // The transient's growth per revolution is the Floquet max|ρ| (docs/theory.md §5), over 6 revolutions to 1 %.
  CHECK(cosine["transient_growth_per_revolution"].number == Approx(reference).epsilon(0.01));
}

TEST_CASE("end to end: sweep, json, csv and PNG, mode 1 at rest is the cantilever's", "[end_to_end][sweep][parallel]") {
  const fs::path dir = output_dir("sweep");
  const std::vector<std::string> more{"--key", "operation.speed_rad_s", "--values", "0:600:4", "--count", "3", "--out",
                                      dir.string()};
  const Json j = run_json("sweep", more);
  std::vector<std::string> csv_args = more;
  csv_args.insert(csv_args.end(), {"--chart", "none"});
  const Csv c = run_csv("sweep", csv_args);
  REQUIRE(j["modes"].size() == 3);
  REQUIRE(c.rows.size() == 4);
  CHECK(c.header.at(0) == "operation.speed_rad_s");
  CHECK(c.header.size() == 1 + 2 * 3);  // frequency and Λ of each mode
  CHECK(c.number(0, "mode_1_bending_lambda") == Approx(euler_bernoulli_lambda1()).epsilon(1e-5));
  CHECK(j["modes"][0]["lambda"][0].number == Approx(c.number(0, "mode_1_bending_lambda")).epsilon(1e-15));
  check_png(dir / "sweep.png", 1650, 750);
}

TEST_CASE("end to end: check, json and junit, the worst Campbell margin from the test's own eigen-solve",
          "[end_to_end][check][parallel][long_under_sanitizers]") {
  const std::string scene = std::string(BLADESTAB_SOURCE_DIR) + "/stability_maps/ci/passes.toml";
  const auto check_run = [&](const char* format) {
    // Every digit: the worst point is compared with the test's own solve of the same model to 1e-8,
    // below the frequencies' tolerance 1e-6 that the default output prints to (docs/outputs.md).
    const testing_support::Outcome o =
        testing_support::run_bladestab({"check", scene, "--format", format, "--digits", "full"}, {120});
    INFO(testing_support::describe(o) << "\n" << o.err);
    REQUIRE(WIFEXITED(o.wait_status));
    REQUIRE(WEXITSTATUS(o.wait_status) == 0);
    return o.out;
  };
  const Json j = testing_support::parse_json(check_run("json"));
  const std::string junit = check_run("junit");
  CHECK(j["passed"].boolean);
  REQUIRE(j["checks"].size() == 2);
  CHECK(junit.find("<testsuite name=\"bladestab check\"") != std::string::npos);
  CHECK(junit.find("tests=\"2\" failures=\"0\"") != std::string::npos);
  // The worst point: mode 1 against engine order 1 at the speed given, recomputed from the gyroscopic
  // eigenvalues of the scene's model at the terms used (reference/first_order_modes.hpp).
  const Json& worst = j["checks"][0]["worst"];
  const double speed = worst["speed_rad_s"].number;
  const Scene s = load_scene(scene, {"model.terms=" + std::to_string(static_cast<int>(j["checks"][0]["terms"].number))});
  const BladeModel m = assemble_model(s);
  double f1 = 1e300;
  for (const std::complex<double>& l : reference::FirstOrderModes(m.M, m.gyroscopic(speed), m.stiffness(speed)).eigenvalues()) {
    if (l.imag() > 0) f1 = std::min(f1, l.imag() / (2 * pi));
  }
  const double k = worst["engine_order"].number;
  INFO("worst: mode " << worst["mode"].number << ", order " << k << " at " << speed << " rad/s, " << worst["frequency_hz"].number
                      << " Hz (reference " << f1 << " Hz), margin " << worst["margin"].number);
  CHECK(worst["mode"].number == 1);
  CHECK(worst["frequency_hz"].number == Approx(f1).epsilon(1e-8));
  CHECK(worst["margin"].number == Approx(std::abs(f1 - k * speed / (2 * pi)) / f1).epsilon(1e-8));
}
