// The blade's static limits (include/bladestab/blade/static_limits.hpp): where they lie against a
// closed form and the test's own Cholesky of the stiffness either side, and every command keeping
// to them — a point past a limit refused in one line (exit 2, no file), a range computed up to the
// limit and saying where it lies, the same bytes on one thread and on two.
#include <sys/wait.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/static_limits.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::describe;
using testing_support::expect_rejected;
using testing_support::paper_scene;
using testing_support::read_text;
using testing_support::run_bladestab;
using testing_support::scratch;

namespace {

namespace fs = std::filesystem;

constexpr double pi = 3.14159265358979323846;

const std::string scene_path = testing_support::paper_scene_path();

// The test's own verdict on a stiffness: a Cholesky factorization exists.
bool positive_definite(const Eigen::MatrixXd& K) { return Eigen::LLT<Eigen::MatrixXd>(K).info() == Eigen::Success; }

// A fresh, empty output directory in the scratch dir.
fs::path empty_dir(const std::string& name) {
  const fs::path dir = scratch() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int exit_code(const testing_support::Outcome& o) { return WIFEXITED(o.wait_status) ? WEXITSTATUS(o.wait_status) : -1; }

// Every file of a directory, by name, with its bytes.
std::vector<std::pair<std::string, std::string>> files_of(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    files.emplace_back(entry.path().filename().string(), read_text(entry.path()));
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("static limits: the spin divergence speed is the axial rod's (π/2)·sqrt(E/ρ)/L", "[static_limits]") {
  // EA u'' + ρAΩ² u = 0, u(0) = 0, u'(L) = 0 first has a root at kL = π/2, k = Ω sqrt(ρ/E); the
  // axial field couples with no other in K (and G does not act on it), so the Ritz model's limit
  // converges to it (16 Legendre terms: to rounding).
  const Scene scene = paper_scene();
  const BladeModel model = assemble_model(scene);
  const double closed = pi / 2 * std::sqrt(scene.blade.youngs_modulus / scene.blade.density) / scene.blade.length;
  const std::optional<StaticLimit> limit = static_limit_at(model, 9000);
  REQUIRE(limit);
  CHECK(limit->kind == StaticLimitKind::spin_divergence);
  CHECK(limit->field == "axial");
  INFO("divergence at " << limit->where << " rad/s, closed form " << closed);
  CHECK(limit->where == Approx(closed).epsilon(1e-12));  // measured 2e-16
  CHECK(positive_definite(model.stiffness(limit->where * (1 - 1e-9))));
  CHECK_FALSE(positive_definite(model.stiffness(limit->where * (1 + 1e-9))));
  CHECK_FALSE(static_limit_at(model, limit->where * (1 - 1e-9)));
  CHECK(static_margin(model, 0) == Approx(1).epsilon(1e-12));  // K(0) = K_E
}

TEST_CASE("static limits: the speed below which a compressed blade buckles, found by root search", "[static_limits]") {
  // Under 2 F_cr the paper blade buckles at rest (F_b = 0.99923 F_cr) and carries it at 300 rad/s
  // (4.954 F_cr): the speeds' path meets buckling between. Its root against two independent
  // statements: the buckling load there, 1/μ_max of G x = μ (K_E + Ω²K_C1) x, is 2 F_cr; and the
  // test's own Cholesky of the stiffness fails just below it and succeeds just above.
  const Scene scene = paper_scene({"operation.tip_compression_over_fcr=2"});
  const BladeModel model = assemble_model(scene);
  const std::vector<double> speeds{0, 100, 200, 300, 400, 500, 600};
  const PathWithinLimits path = speeds_within_limits(model, speeds);
  REQUIRE(path.before);
  CHECK_FALSE(path.after);
  CHECK(path.end == speeds.size());
  CHECK(path.before->kind == StaticLimitKind::buckling);
  CHECK(path.before->field == "lateral");
  const double speed = path.before->where;
  INFO("buckles below " << speed << " rad/s");
  CHECK(speeds[path.first - 1] < speed);
  CHECK(speed < speeds[path.first]);
  const std::optional<double> load = static_buckling_load(model, speed);
  REQUIRE(load);
  CHECK(*load / model.blade.critical_load() == Approx(2).epsilon(1e-12));  // measured 2e-14
  CHECK_FALSE(positive_definite(model.stiffness(speed * (1 - 1e-9))));
  CHECK(positive_definite(model.stiffness(speed * (1 + 1e-9))));
  // At a speed below it the point is past buckling, and says under what load it buckles there.
  const std::optional<StaticLimit> at_rest = static_limit_at(model, 0);
  REQUIRE(at_rest);
  CHECK(at_rest->kind == StaticLimitKind::buckling);
  const double kGA = model.blade.kappa * model.blade.shear_modulus * model.blade.A;
  const double engesser = 1 / (1 + model.blade.critical_load() / kGA);  // F_cr/(1 + F_cr/κGA), in F_cr
  CHECK(at_rest->where / model.blade.critical_load() == Approx(engesser).epsilon(1e-6));
}

TEST_CASE("static limits: a point past them is refused alike by every command (bad_input)",
          "[static_limits][bad_input]") {
  // The unloaded blade at 9000 rad/s: past its axial divergence speed (8039.95 rad/s).
  const std::vector<std::string> past{"--set", "model.terms=4", "--set", "operation.speed_rad_s=9000"};
  for (const std::string command : {"modes", "transient", "stability", "boundaries", "map", "crosscheck"}) {
    DYNAMIC_SECTION(command) {
      const fs::path out = empty_dir("point_" + command);
      std::vector<std::string> args{command, scene_path};
      args.insert(args.end(), past.begin(), past.end());
      if (command == "transient" || command == "map") args.insert(args.end(), {"--out", out.string(), "--chart", "none"});
      if (command == "map") args.insert(args.end(), {"--plane", "theta-fmax"});
      expect_rejected(args, {"operation.speed_rad_s = 9000", "statically unstable", "diverges above 8039.9", "axial field"});
      CHECK(fs::is_empty(out));
    }
  }
  SECTION("a compression the blade cannot carry at its speed names the key and the load it buckles under") {
    expect_rejected({"modes", scene_path, "--set", "model.terms=4", "--set", "operation.speed_rad_s=0", "--set",
                     "operation.tip_compression_over_fcr=2"},
                    {"operation.tip_compression_over_fcr = 2", "statically unstable", "buckles at 0.99"});
  }
}

TEST_CASE("static limits: a range past them is refused naming the range (bad_input)",
          "[static_limits][bad_input]") {
  SECTION("campbell") {
    const fs::path out = empty_dir("campbell_past");
    expect_rejected({"campbell", scene_path, "--speeds", "9000:12000:5", "--set", "model.terms=8", "--threads", "2",
                     "--chart", "none", "--out", out.string()},
                    {"--speeds 9000:12000:5", "every speed is past the blade's static limits", "diverges above 8039.9"});
    CHECK(fs::is_empty(out));
  }
  SECTION("campbell under a compression it cannot carry at any of the speeds") {
    expect_rejected({"campbell", scene_path, "--speeds", "0:300:3", "--set", "operation.tip_compression_over_fcr=50",
                     "--chart", "none", "--out", empty_dir("campbell_buckled").string()},
                    {"--speeds 0:300:3", "operation.tip_compression_over_fcr = 50", "statically unstable"});
  }
  SECTION("check") {
    const std::string text = read_text(scene_path) +
                             "\n[requirements]\nspeed_range_rad_s = [99999.0, 100000.0]\nfrequency_margin = 0.1\n";
    const fs::path scene = scratch() / "diverged_range.toml";
    std::ofstream(scene) << text;
    expect_rejected({"check", scene.string()}, {"requirements.speed_range_rad_s = [99999, 100000]",
                                                "static limits", "diverges above 8039.9"});
  }
  SECTION("map on the speed plane, whose points all need the blade within its limits") {
    for (const std::string threads : {"1", "2"}) {
      expect_rejected({"map", scene_path, "--plane", "speed-fmax", "--speeds", "7000:9000:3", "--fmax", "0.5:1:2",
                       "--set", "model.terms=4", "--threads", threads, "--out", empty_dir("map_past").string(),
                       "--chart", "none"},
                      {"--speeds 7000:9000:3", "diverges (the spin softening of its axial field) above 8039.9",
                       "within the blade's static limits"});
    }
  }
  SECTION("sweep") {
    expect_rejected({"sweep", scene_path, "--key", "operation.speed_rad_s", "--values", "9000:9500:3", "--set",
                     "model.terms=4", "--out", empty_dir("sweep_past").string(), "--chart", "none"},
                    {"--values 9000:9500:3", "every value is past", "diverges above 8039.9"});
  }
}

TEST_CASE("static limits: campbell up to the limit, saying where, the same on one thread and two",
          "[static_limits][campbell][slow]") {
  // Buckled below a speed (2 F_cr at rest), and diverging above one (8039.95 rad/s).
  struct Case {
    std::string name, speeds;
    std::vector<std::string> overrides;
    const char* side;
  };
  for (const Case& c : {Case{"buckled", "0:600:7", {"model.terms=4", "operation.tip_compression_over_fcr=2"}, "below"},
                        Case{"diverging", "7000:9000:5", {"model.terms=8"}, "above"}}) {
    DYNAMIC_SECTION(c.name) {
      std::vector<std::vector<std::pair<std::string, std::string>>> outputs;
      std::vector<std::string> stdouts;
      for (const std::string threads : {"1", "2"}) {
        const fs::path out = empty_dir("campbell_" + c.name + "_" + threads);
        std::vector<std::string> args{"campbell", scene_path, "--speeds", c.speeds, "--threads", threads,
                                      "--chart", "none", "--out", out.string(), "--format", "json"};
        for (const std::string& o : c.overrides) args.insert(args.end(), {"--set", o});
        const auto o = run_bladestab(args, {600});
        INFO(o.command << "\n" << describe(o) << "\n" << o.err);
        REQUIRE(exit_code(o) == 0);
        CHECK(o.err.empty());
        outputs.push_back(files_of(out));
        stdouts.push_back(o.out);
      }
      CHECK(stdouts[0] == stdouts[1]);
      CHECK(outputs[0] == outputs[1]);
      const testing_support::Json j = testing_support::parse_json(stdouts[0]);
      const testing_support::Json& limit = j["static_limits"][c.side];
      REQUIRE(limit.type == testing_support::Json::Type::object);
      const double where = limit["speed_rad_s"].number;
      const std::vector<double> speeds = j["speeds_rad_s"].numbers();
      CHECK(j["static_limits"]["text"].text.find(c.side == std::string("below") ? "starts there" : "stops there") !=
            std::string::npos);
      // Every speed of the diagram within the limit, the limit where the stiffness stops being
      // positive definite (the test's Cholesky either side), the kind and field named.
      // The limit is the one of the model the curves belong to (its terms raised to the tolerance).
      std::vector<std::string> overrides = c.overrides;
      overrides.push_back("model.terms=" + std::to_string(static_cast<int>(j["terms"].number)));
      const BladeModel model = assemble_model_at_any_speed(paper_scene(overrides), paper_scene(overrides).model);
      const bool below = c.side == std::string("below");
      for (double s : speeds) CHECK((below ? s > where : s < where));
      CHECK(positive_definite(model.stiffness(where * (below ? 1 + 1e-6 : 1 - 1e-6))));
      CHECK_FALSE(positive_definite(model.stiffness(where * (below ? 1 - 1e-6 : 1 + 1e-6))));
      CHECK(limit["kind"].text == (below ? "buckling" : "spin divergence"));
      CHECK(limit["field"].text == (below ? "lateral" : "axial"));
      if (below) {
        // Mode 1 of the diagram is `modes`' mode 1 at its first speed: nothing relabelled.
        std::vector<std::string> args{"modes", scene_path, "--format", "json", "--count", "2", "--set",
                                      "operation.speed_rad_s=" + std::to_string(speeds.front())};
        for (const std::string& o : overrides) args.insert(args.end(), {"--set", o});
        const auto m = run_bladestab(args);
        REQUIRE(exit_code(m) == 0);
        const double f_modes = testing_support::parse_json(m.out)["modes"][0]["frequency_hz"].number;
        const double f_campbell = j["curves"][0]["frequency_hz"].numbers().front();
        INFO("mode 1 at " << speeds.front() << " rad/s: campbell " << f_campbell << " Hz, modes " << f_modes << " Hz");
        CHECK(f_campbell == Approx(f_modes).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("static limits: a sweep into buckling stops at the buckling load, found by root search on the key",
          "[static_limits][sweep]") {
  const fs::path out = empty_dir("sweep_buckling");
  const auto o = run_bladestab({"sweep", scene_path, "--set", "operation.speed_rad_s=0", "--key",
                                "operation.tip_compression_over_fcr", "--values", "0:1.2:4", "--count", "2", "--out",
                                out.string(), "--chart", "none", "--format", "json", "--digits", "full"});
  INFO(o.err);
  REQUIRE(exit_code(o) == 0);
  const testing_support::Json j = testing_support::parse_json(o.out);
  const std::vector<double> values = j["values"].numbers();
  REQUIRE(values.size() == 3);
  CHECK(values[2] == Approx(0.8));
  const testing_support::Json& limit = j["static_limits"]["above"];
  REQUIRE(limit.type == testing_support::Json::Type::object);
  CHECK(limit["kind"].text == "buckling");
  CHECK(j["static_limits"]["below"].type == testing_support::Json::Type::null);
  // The root on the key against the generalized eigenvalue 1/μ_max at rest, and Engesser's column.
  const BladeModel rest = assemble_model(paper_scene({"operation.speed_rad_s=0"}));
  const double fcr = rest.blade.critical_load();
  CHECK(limit["value"].number == Approx(*static_buckling_load(rest, 0) / fcr).epsilon(1e-10));
  const double kGA = rest.blade.kappa * rest.blade.shear_modulus * rest.blade.A;
  CHECK(limit["value"].number == Approx(1 / (1 + fcr / kGA)).epsilon(1e-6));
  // The table says it in one line.
  const auto table = run_bladestab({"sweep", scene_path, "--set", "operation.speed_rad_s=0", "--key",
                                    "operation.tip_compression_over_fcr", "--values", "0:1.2:4", "--count", "2",
                                    "--out", out.string(), "--chart", "none"});
  REQUIRE(exit_code(table) == 0);
  CHECK(table.out.find("limits    the blade buckles under its static tip compression above "
                       "operation.tip_compression_over_fcr = 0.99923") != std::string::npos);
}
