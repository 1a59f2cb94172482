// Answers that stand with what they could not reach said: boundaries that do not converge
// are listed beside those that do, with the exit status a blade engineer expects (0 while some
// converged, 1 when none did), and a tolerance the sine basis cannot reach is said at once in one
// line and in the JSON instead of being run into the time limit.
#include <sys/wait.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "bladestab/blade/model.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "reference/mathieu.hpp"
#include "support/json.hpp"
#include "support/run_cli.hpp"
#include "support/scenes.hpp"

namespace {

using namespace bladestab;
using reference::MathieuKind;
using testing_support::describe;
using testing_support::Json;
using testing_support::Outcome;

const std::string paper = BLADESTAB_SOURCE_DIR "/stability_maps/sinha2005/blade.toml";

// `bladestab boundaries` on the Mathieu blade at F̄ = 1, where the stiffness touches zero once a
// period (Mathieu's line a = 2q) and the tongues of high order at low θ pinch.
Outcome mathieu_boundaries(const std::vector<std::string>& extra) {
  std::vector<std::string> args{"boundaries", paper};
  for (const std::string& o : testing_support::mathieu_overrides(1.0)) args.insert(args.end(), {"--set", o});
  args.insert(args.end(), extra.begin(), extra.end());
  return testing_support::run_bladestab(args, {300});
}

int exit_status(const Outcome& o) { return WIFEXITED(o.wait_status) ? WEXITSTATUS(o.wait_status) : -1; }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t start = 0, end; start < text.size(); start = end + 1) {
    end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    out.push_back(text.substr(start, end - start));
  }
  return out;
}

bool starts_with(const std::string& text, const std::string& start) { return text.rfind(start, 0) == 0; }

// The JSON answer of a run that ends with `status` and one stderr line starting `start`.
Json answer_with_one_line(const Outcome& o, int status, const std::string& start) {
  INFO(o.command << "\n" << describe(o) << "\n" << o.err);
  REQUIRE(exit_status(o) == status);
  REQUIRE(lines(o.err).size() == 1);
  CHECK(starts_with(o.err, start));
  return testing_support::parse_json(o.out);
}

}  // namespace

TEST_CASE("boundaries --range 10:300 at F̄ = 1: the order-1 and order-2 edges at Mathieu's values from the default k "
          "and from k = 20",
          "[boundaries][mathieu][slow][parallel]") {
  const BladeModel m = assemble_model(testing_support::mathieu_scene(1.0));
  const double w0 = std::sqrt(m.K_S(0, 0) / m.M(0, 0));
  // In [10, 300]: a₁ (order 1, θ ≈ 199 rad/s; b₁ lies at 327), a₂ and b₂ (order 2, θ ≈ 108 and 138).
  std::vector<double> edges;
  for (auto [kind, rank, x0, x1] : {std::tuple{MathieuKind::a_odd, 0, 0.01, 60.0},
                                    std::tuple{MathieuKind::a_even, 1, 2.0, 80.0},
                                    std::tuple{MathieuKind::b_even, 0, 2.0, 80.0}}) {
    edges.push_back(reference::mathieu_blade_boundary(kind, rank, 1.0, w0, x0, x1));
  }
  for (const std::string k : {"2", "20"}) {
    const Outcome o = mathieu_boundaries({"--range", "10:300", "--approximation", k, "--format", "json", "--digits", "full"});
    INFO(o.command << "\n" << describe(o) << "\n" << o.err);
    REQUIRE(exit_status(o) == 0);
    for (const std::string& line : lines(o.err)) CHECK(starts_with(line, "bladestab: note: boundaries: "));
    const Json j = testing_support::parse_json(o.out);
    REQUIRE(j["boundaries"].size() > 0);
    for (double theta : edges) {
      double closest = 1;
      for (const Json& b : j["boundaries"].items) closest = std::min(closest, std::abs(b["theta_rad_s"].number / theta - 1));
      INFO("Mathieu's θ = " << theta);
      CHECK(closest <= 1e-8);
    }
    CHECK(j["converged"].boolean == (j["unconverged"].size() == 0));
  }
}

TEST_CASE("boundaries: some converged, the others listed with how far they got (exit 0, one note), or none converged "
          "(exit 1, one failure line)",
          "[boundaries][slow][parallel]") {
  SECTION("some converged") {
    const Outcome o = mathieu_boundaries({"--range", "5.9:6.5", "--approximation", "16", "--format", "json"});
    const Json j = answer_with_one_line(o, 0, "bladestab: note: boundaries: ");
    CHECK(o.err.find("did not converge to --tolerance 1e-06 with up to 40 harmonics per family") != std::string::npos);
    CHECK_FALSE(j["converged"].boolean);
    CHECK_FALSE(j["tolerance_met"].boolean);
    REQUIRE(j["boundaries"].size() >= 1);
    REQUIRE(j["unconverged"].size() >= 1);
    for (const Json& u : j["unconverged"].items) {
      const double theta = u["theta_rad_s"].number;
      CHECK(theta >= 5.9);
      CHECK(theta <= 6.5);
      CHECK(u["approximation"].number + 4 <= 40);  // compared with k + 2 and k + 4 at most
      // How far it got: its change from k to k + 2 (twice it above the tolerance), or its check failed.
      const bool far = u["last_change"].type == Json::Type::number && 2 * u["last_change"].number > 1e-6;
      CHECK((far || u["check_failed"].boolean));
    }
  }
  SECTION("none converged") {
    const Outcome o = mathieu_boundaries({"--range", "3.2:3.7", "--approximation", "16", "--format", "json"});
    // The answer, complete, lists them.
    const Json j = answer_with_one_line(o, 1, "bladestab: failed: boundaries: none of the ");
    CHECK(j["boundaries"].size() == 0);
    CHECK(j["unconverged"].size() >= 2);
  }
}

TEST_CASE("a tolerance the sine basis cannot reach: stability answers at once with what it reaches, and says so",
          "[stability]") {
  // The paper's model (10 sine terms per field) toward the default 1e-6 ran for ten minutes into the
  // time limit, raising the terms. Its basis part is ~1e-3: even a convergence like N^-2 would need
  // more than 200 terms, so the terms stay at 10.
  const StabilityAnswer a =
      analyse_stability(testing_support::paper_scene({"model.basis=sine", "model.terms=10"}), {FloquetMethod::automatic, 0, 1e-6});
  const double relative_basis = a.budget.basis / std::max(1.0, a.floquet.max_abs_multiplier);
  INFO("basis part " << a.budget.basis << ", max|ρ| " << a.floquet.max_abs_multiplier << ", terms " << a.model.terms);
  CHECK(relative_basis * std::pow(10.0 / 200, 2) > 1e-6);
  CHECK(a.model.terms == 10);
  CHECK_FALSE(a.tolerance_met);
  CHECK(starts_with(a.tolerance_unmet, "tolerance 1e-06: not met with 10 terms per field"));

  const Outcome o = testing_support::run_bladestab(
      {"stability", paper, "--set", "model.basis=sine", "--set", "model.terms=10", "--format", "json"}, {120});
  const Json j = answer_with_one_line(o, 0, "bladestab: note: stability: --tolerance 1e-06: not met with 10 terms per field");
  CHECK(o.err.find("model.basis = \"legendre\"") != std::string::npos);
  CHECK_FALSE(j["tolerance_met"].boolean);
  CHECK(starts_with(j["tolerance_unmet"].text, "--tolerance 1e-06: not met"));
  CHECK(j["terms"].number == 10);
}
