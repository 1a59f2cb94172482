// `bladestab check`: the requirements of a blade design over its operating range
// (requirements_check.hpp), against references computed here: the frequencies by dense whole-model
// eigensolves with a bisection and a golden search of this file's own, the stability onset by
// Floquet multipliers either side of it, and the example scenes end to end.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <catch2/catch.hpp>

#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/modal/campbell.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/stability/requirements_check.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"

namespace {

using namespace bladestab;
using namespace testing_support;

constexpr double two_pi = 6.28318530717958647692;

std::string example(const std::string& name) {
  return std::string(BLADESTAB_SOURCE_DIR) + "/stability_maps/ci/" + name + ".toml";
}

// f_mode(Ω) [Hz] of the whole Ritz model of `terms` terms by a dense solve (modes sorted by size;
// the low modes of the paper blade do not cross inside the ranges used here).
double dense_frequency(const Scene& scene, int terms, int mode, double speed) {
  ModelSpec spec = scene.model;
  spec.terms = terms;
  const BladeModel model = assemble_model(scene, spec);
  const Eigen::MatrixXd damping = damping_matrix(model, scene.damping, speed);
  const ModalSolution s = solve_modes(model, system_at(model, speed, damping), speed, 0, EigenSolverKind::dense);
  return s.modes.at(mode - 1).frequency_hz;
}

// The margin's worst point against the reference: golden search of |f − kΩ/2π|/f on dense solves,
// for every mode checked and every engine order, each from the least of 21 speeds.
void check_least_distance(const Scene& scene, const FrequencyMarginResult& m) {
  const RequirementsSpec& req = *scene.requirements;
  double least = 1e300, where = 0;
  for (int mode = 1; mode <= m.modes_checked; ++mode) {
    for (int k : req.engine_orders) {
      const auto distance = [&](double speed) {
        const double f = dense_frequency(scene, m.terms, mode, speed);
        return std::abs(f - k * speed / two_pi) / f;
      };
      double best = req.speed_lo_rad_s, best_value = distance(best);
      const double step = (req.speed_hi_rad_s - req.speed_lo_rad_s) / 20;
      for (int s = 1; s <= 20; ++s) {
        const double v = distance(req.speed_lo_rad_s + s * step);
        if (v < best_value) best = req.speed_lo_rad_s + s * step, best_value = v;
      }
      double a = std::max(req.speed_lo_rad_s, best - step), b = std::min(req.speed_hi_rad_s, best + step);
      const double r = 0.5 * (std::sqrt(5.0) - 1);
      while (b - a > 1e-7 * b) {
        const double c = b - r * (b - a), d = a + r * (b - a);
        if (distance(c) <= distance(d)) {
          b = d;
        } else {
          a = c;
        }
      }
      for (double x : {a, b}) {
        if (distance(x) < least) least = distance(x), where = x;
      }
    }
  }
  CHECK(m.worst.distance == Approx(least).margin(1e-6));
  CHECK(m.worst.speed_rad_s == Approx(where).epsilon(1e-5));
  CHECK(m.error_estimate < 1e-5);
}

int exit_code(const Outcome& o) { return WIFEXITED(o.wait_status) ? WEXITSTATUS(o.wait_status) : -1; }

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("check: the Campbell margin's worst point against dense solves", "[check][parallel][long_under_sanitizers]") {
  SECTION("a crossing inside the range: margin 0 at the root of f = kΩ/2π") {
    const Scene scene = load_scene(example("fails"));
    const FrequencyMarginResult m = check_frequency_margin(scene, 1e-6);
    REQUIRE_FALSE(m.passed);
    REQUIRE(m.worst.distance == 0);
    // The reference: bisection of f(Ω) − kΩ/2π on dense solves over the range.
    const double line = m.worst.engine_order / two_pi;
    const auto g = [&](double speed) { return dense_frequency(scene, m.terms, m.worst.mode, speed) - line * speed; };
    double a = scene.requirements->speed_lo_rad_s, b = scene.requirements->speed_hi_rad_s;
    REQUIRE(g(a) * g(b) < 0);
    while (b - a > 1e-9 * b) {
      const double c = 0.5 * (a + b);
      (g(a) * g(c) <= 0 ? b : a) = c;
    }
    CHECK(m.worst.speed_rad_s == Approx(0.5 * (a + b)).epsilon(1e-8));
    CHECK(m.worst.frequency_hz == Approx(line * 0.5 * (a + b)).epsilon(1e-8));
  }
  SECTION("no crossing: the least relative distance over the range") {
    const Scene scene = load_scene(example("passes"));
    const FrequencyMarginResult m = check_frequency_margin(scene, 1e-6);
    REQUIRE(m.passed);
    check_least_distance(scene, m);
  }
  SECTION("the paper's damping (37), which overdamps the stiff modes (0 Hz): they meet no line") {
    // ζ = 0.02: every mode above Ω/(2πζ) ≈ 2 kHz is overdamped. The worst approach is the undamped
    // one's, mode 1 to engine order 1, and the damped dense solves are the reference.
    const Scene scene = load_scene(example("passes"), {"damping.model=paper", "damping.ratio=0.02"});
    const FrequencyMarginResult m = check_frequency_margin(scene, 1e-6);
    REQUIRE(m.passed);
    CHECK(m.modes_checked == 1);
    check_least_distance(scene, m);
  }
}

TEST_CASE("check: the Campbell margin reaches the modes of the raised model, past the scene's own dofs",
          "[check][long_under_sanitizers]") {
  // The scene's 4 terms have 12 modes, all far below engine order 270 over 245–280 rad/s (39–45 kHz·k/1000).
  // The axial rod's fifth mode, (2n − 1)c/4L = 9/4·√(E/ρ)/L = 11516.4 Hz, crosses it at 268.0 rad/s:
  // the requirement fails, whatever the bending modes do.
  const Scene scene = load_scene(example("passes"), {"model.terms=4", "requirements.engine_orders=[270]"});
  const double axial = 9.0 / 4 * std::sqrt(scene.blade.youngs_modulus / scene.blade.density) / scene.blade.length;
  REQUIRE(two_pi * axial / 270 == Approx(268.0).epsilon(1e-3));
  const FrequencyMarginResult m = check_frequency_margin(scene, 1e-3);
  CHECK_FALSE(m.passed);
  CHECK(m.worst.distance == 0);
  CHECK(m.modes_checked > 12);
  // The crossing it names against a dense solve of its model at that speed.
  CHECK(dense_frequency(scene, m.terms, m.worst.mode, m.worst.speed_rad_s) ==
        Approx(270 * m.worst.speed_rad_s / two_pi).epsilon(1e-3));
}

TEST_CASE("check: the stability onset at the worst speed against Floquet either side", "[check][parallel][long_under_sanitizers]") {
  // Damped, so the regions lift off F̄ = 0 and the onset is a boundary: max|ρ| ≤ 1 just below it,
  // > 1 just above.
  Scene scene = load_scene(example("passes"),
                           {"requirements.max_fmax_over_fcr=2.0", "damping.model=modal", "damping.ratio=0.01"});
  const RubStabilityResult r = check_rub_stability(scene);
  REQUIRE(r.onset_fmax_over_fcr);
  REQUIRE_FALSE(r.tip);
  const double onset = *r.onset_fmax_over_fcr;
  INFO("onset F̄ = " << onset << " at " << r.speed_rad_s << " rad/s");
  const auto max_rho = [&](double fbar) {
    Scene at = scene;
    at.operation.speed_rad_s = r.speed_rad_s;
    at.load.pulse_frequency_hz = scene.load.pulses_per_rev * r.speed_rad_s / two_pi;
    at.load.fmax_over_fcr = fbar;
    return analyse_stability(at, {FloquetMethod::monodromy, 0, 1e-8}).floquet.max_abs_multiplier;
  };
  CHECK(max_rho(onset * (1 - 1e-3)) <= 1 + 1e-7);
  CHECK(max_rho(onset * (1 + 1e-3)) > 1 + 1e-7);
  CHECK(r.passed == (onset > 2.0));
}

TEST_CASE("check: a thin region of higher order inside the range fails the requirement, by Floquet across it",
          "[check][parallel][long_under_sanitizers]") {
  // passes.toml over 129–131 rad/s under the Fourier series: no region of order <= 4 opens below
  // F̄ = 10, but mode 3's order-49 region holds 130 rad/s at F̄ = 5 (the whole model under the true
  // train gives 1.0847 there from 12 terms on, a real −1 multiplier); the worst speed's own Floquet
  // point, 129 rad/s, is stable.
  const Scene scene = load_scene(example("passes"), {"requirements.speed_range_rad_s=[129.0, 131.0]",
                                                     "requirements.max_fmax_over_fcr=5.0",
                                                     "load.approximation=fourier"});
  const RubStabilityResult r = check_rub_stability(scene);
  CHECK_FALSE(r.passed);
  CHECK_FALSE(r.check_stable);
  CHECK(r.check_speed_rad_s == Approx(130));
  CHECK(r.floquet_speeds >= 2);
  Scene at = scene_at(scene, 130, 130, 5);  // as the check moves the scene (the duty held)
  at.load.approximation = LoadApproximation::exact;  // the true train the series stands for
  at.model.terms = 16;                               // converged: 12 terms give 1.08473 too
  const PeriodicSystem sys = periodic_system(assemble_model(at), at, load_series(at), {ReductionKind::none, 0, 0});
  const double whole =
      pulse_train_multipliers(sys, periodic_pulse(pulse_train(at)), {FloquetMethod::monodromy, 0, 1e-8}).max_abs_multiplier;
  CHECK(whole > 1.05);
  CHECK(r.max_abs_multiplier == Approx(whole).epsilon(0.01));
}

// The example scenes end to end, one run of the program each, as separate test cases so that ctest
// runs them side by side.
TEST_CASE("check: the example scenes end to end: passes.toml, exit 0, JSON", "[check][parallel]") {
  const Outcome o = run_bladestab({"check", example("passes"), "--format", "json"}, {120});
  INFO(describe(o) << "\n" << o.err);
  REQUIRE(exit_code(o) == 0);
  const Json j = parse_json(o.out);
  CHECK(j["passed"].boolean);
  REQUIRE(j["checks"].size() == 2);
  for (std::size_t c = 0; c < 2; ++c) CHECK(j["checks"][c]["passed"].boolean);
  CHECK(j["checks"][0]["name"].text == "campbell_margin");
  CHECK(j["checks"][0]["worst"]["margin"].number >= 0.1);
  CHECK(j["checks"][1]["name"].text == "rub_stability");
}

TEST_CASE("check: the example scenes end to end: fails.toml, exit 1, JSON", "[check][slow][parallel]") {
  const Outcome o = run_bladestab({"check", example("fails"), "--format", "json"}, {120});
  INFO(describe(o) << "\n" << o.err);
  REQUIRE(exit_code(o) == 1);
  CHECK(o.err.empty());
  const Json j = parse_json(o.out);
  CHECK_FALSE(j["passed"].boolean);
  REQUIRE(j["checks"].size() == 2);
  CHECK_FALSE(j["checks"][0]["passed"].boolean);
  CHECK(j["checks"][0]["worst"]["margin"].number == 0);
  CHECK_FALSE(j["checks"][1]["passed"].boolean);
  CHECK(j["checks"][1]["worst"]["onset_fmax_over_fcr"].number == 0);
}

// The JUnit form of two failed checks: the passing scene asked for more than it holds (a 50 %
// frequency margin, stability up to 8 F_cr), 2.5× cheaper than fails.toml's run at a tongue's tip.
TEST_CASE("check: the example scenes end to end: two failures as JUnit", "[check][parallel][long_under_sanitizers]") {
  const Outcome x = run_bladestab({"check", example("passes"), "--set", "requirements.frequency_margin=0.5", "--set",
                                   "requirements.max_fmax_over_fcr=8", "--format", "junit"},
                                  {120});
  REQUIRE(exit_code(x) == 1);
  CHECK(x.out.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"bladestab check\"", 0) == 0);
  CHECK(count_of(x.out, "<testsuite ") == 1);
  CHECK(count_of(x.out, "</testsuite>") == 1);
  CHECK(count_of(x.out, "<testcase ") == 2);
  CHECK(count_of(x.out, "</testcase>") == 2);
  CHECK(count_of(x.out, "<failure message=") == 2);
  CHECK(count_of(x.out, "</failure>") == 2);
  CHECK(x.out.find("tests=\"2\" failures=\"2\"") != std::string::npos);
  // Every '&' starts an entity, and no '<' is loose inside text.
  for (std::size_t at = x.out.find('&'); at != std::string::npos; at = x.out.find('&', at + 1)) {
    const std::string entity = x.out.substr(at, 6);
    CHECK((entity.rfind("&amp;", 0) == 0 || entity.rfind("&lt;", 0) == 0 || entity.rfind("&gt;", 0) == 0 ||
           entity.rfind("&quot;", 0) == 0 || entity.rfind("&apos;", 0) == 0));
  }
}

TEST_CASE("check: a requirement whose computation fails has no verdict, and the others keep theirs",
          "[check][parallel]") {
  // 1 to 10 rad/s: the rub check's Floquet period at 1 rad/s would need more than 131072 Magnus
  // steps. It ended the whole run in one line, and `--format junit` wrote nothing for CI to read.
  const Outcome x = run_bladestab({"check", example("passes"), "--set", "requirements.speed_range_rad_s=[1, 10]",
                                   "--format", "junit"},
                                  {120});
  INFO(describe(x) << "\n" << x.err);
  REQUIRE(exit_code(x) == 1);
  CHECK(x.out.find("tests=\"2\" failures=\"0\" errors=\"1\"") != std::string::npos);
  CHECK(count_of(x.out, "<error message=\"no verdict: the check failed\">no verdict: the monodromy needs more than") == 1);
  CHECK(count_of(x.out, "<failure") == 0);
  // The Campbell margin still answers: at 10 rad/s mode 1 (28.69 Hz) is 83 % from engine order 3.
  CHECK(x.out.find("name=\"campbell_margin\"") != std::string::npos);
  CHECK(x.out.find("|f - kΩ/2π|/f = 0.8335") != std::string::npos);
  const Outcome j = run_bladestab({"check", example("passes"), "--set", "requirements.speed_range_rad_s=[1, 10]",
                                   "--format", "json"},
                                  {120});
  REQUIRE(exit_code(j) == 1);
  const Json answer = parse_json(j.out);
  CHECK_FALSE(answer["passed"].boolean);
  CHECK(answer["checks"][0]["passed"].boolean);
  CHECK_FALSE(answer["checks"][1]["passed"].boolean);
  CHECK(answer["checks"][1]["worst"].type == Json::Type::null);
  CHECK_THAT(answer["checks"][1]["error"].text, Catch::StartsWith("the monodromy needs more than"));
}

TEST_CASE("check: bad input is one line naming the key", "[check]") {
  const std::string scene = read_text(example("passes"));
  const auto with = [&](const std::string& name, const std::string& requirements) {
    const std::string base = scene.substr(0, scene.find("[requirements]"));
    const auto path = scratch() / (name + ".toml");
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs((base + requirements).c_str(), f);
    std::fclose(f);
    return path.string();
  };
  const std::string range = "[requirements]\nspeed_range_rad_s = [220.0, 270.0]\n";
  expect_rejected({"check", with("none", "")}, {"[requirements]", "missing"});
  expect_rejected({"check", with("unknown", range + "frequency_margin = 0.1\nmargin = 2\n")},
                  {"requirements.margin", "unknown key"});
  expect_rejected({"check", with("reversed", "[requirements]\nspeed_range_rad_s = [270.0, 220.0]\nfrequency_margin = 0.1\n")},
                  {"requirements.speed_range_rad_s", "lo < hi"});
  expect_rejected({"check", with("equal", "[requirements]\nspeed_range_rad_s = [220.0, 220.0]\nfrequency_margin = 0.1\n")},
                  {"requirements.speed_range_rad_s", "lo < hi"});
  expect_rejected({"check", with("empty_orders", range + "engine_orders = []\nfrequency_margin = 0.1\n")},
                  {"requirements.engine_orders", "non-empty"});
  expect_rejected({"check", with("duplicate_orders", range + "engine_orders = [1, 2, 2]\nfrequency_margin = 0.1\n")},
                  {"requirements.engine_orders", "distinct"});
  expect_rejected({"check", with("nan", range + "frequency_margin = nan\n")}, {"requirements.frequency_margin", "nan"});
  expect_rejected({"check", with("margin_one", range + "frequency_margin = 1.0\n")},
                  {"requirements.frequency_margin", "(0, 1)"});
  expect_rejected({"check", with("no_requirement", range)}, {"requirements.frequency_margin", "max_fmax_over_fcr"});
  expect_rejected({"check", with("load", range + "max_fmax_over_fcr = -1\n")},
                  {"requirements.max_fmax_over_fcr", "[0, 1000]"});
  expect_rejected({"check", example("passes"), "--format", "csv"}, {"--format"});
  // Other commands accept a scene with [requirements] and ignore it.
  const Outcome o = run_bladestab({"modes", example("passes"), "--count", "2"});
  CHECK(exit_code(o) == 0);
}

// A slender blade (d̄ = 1e-4) over 0–600 rad/s against engine order 12 needs 40 modes below 1273 Hz
// and 76 terms per field at the tolerance 1e-2: ~47 s of eigensolves. With 4e9 flops (what half of
// --max-seconds 2 allows) the terms are raised only while the next round's whole-model solves,
// and then its diagram's solves at every speed, fit; the check ends in one line saying so.
// Counted, not timed: the same under a sanitizer.
TEST_CASE("check: a Campbell margin whose terms outgrow the work limit ends in one line naming the tolerance",
          "[check][parallel]") {
  Scene scene = load_scene(BLADESTAB_SOURCE_DIR "/stability_maps/sinha2005/blade.toml", {"blade.slenderness=1e-4"});
  scene.requirements = RequirementsSpec{};
  scene.requirements->speed_lo_rad_s = 0;
  scene.requirements->speed_hi_rad_s = 600;
  scene.requirements->engine_orders = {12};
  scene.requirements->frequency_margin = 0.1;
  try {
    check_frequency_margin(scene, 1e-2, {}, 4e9);
    FAIL("the margin was checked within 4e9 flops");
  } catch (const WorkLimitError& e) {
    const std::string message = e.what();
    CHECK_THAT(message, Catch::StartsWith("the Campbell frequencies cannot be brought within the tolerance 0.01: "));
    CHECK_THAT(message, Catch::Contains("the diagram at model.terms = "));
    CHECK_THAT(message, Catch::EndsWith("would pass all that the work limit affords"));
  }
}

TEST_CASE("check: the Campbell estimate starts no round its work limit cannot afford", "[check]") {
  const Scene scene = load_scene(example("fails"));
  CampbellOptions options;
  options.speeds_rad_s = {230, 290, 350};
  options.engine_orders = {1};
  options.mode_count = 2;
  // The first round's least work: the screen's three whole solves of the 8-term model (24 dofs) and
  // of its 12-term reference (36 dofs), Hermitian within the static limits: (12 n + 4000) n² flops each.
  const auto hermitian = [](double n) { return (12 * n + 4000) * n * n; };
  const double first_round = 3 * (hermitian(24) + hermitian(36));
  options.work_flops = 0.99 * first_round;
  CHECK_THROWS_WITH(campbell_with_error_estimate(scene, options, 1e-6),
                    Catch::Contains("the diagram at model.terms = 8 would pass all that the work limit affords"));
  options.work_flops = 1e300;
  const CampbellWithErrors whole = campbell_with_error_estimate(scene, options, 1e-6);
  CHECK(whole.work_flops >= first_round);
}
