// Issue "every answer right or refused", acceptance: over scenes across the space a user will try,
// the total error estimate of `stability` is not below its true error against a reference
// computed here, and each failure mode of the first release is gone. The ratios estimate/true are
// printed (the README shows their distribution).
//
// The reference for a scene is its continuum model, approached independently of the answer's
// fidelity choices: the Legendre basis at max(24, N + 8) terms (converged to ~1e-12 at 12 terms
// for this blade, docs/theory.md §2), the true pulse train where the scene asks for a Fourier series, and
// the Magnus monodromy at a tolerance of 1e-10 (1e-9 on the true train's contact; at 1e-11 no reference of the survey moved by more
// than 7e-12 of max(1, max|ρ|), at half again the cost); the true train on the whole Ritz model
// (it is integrated only through the contacts). The series' reduction: three modes per load level plus
// gyroscopic corrections, checked against the whole Ritz model (N = 8) and the independent
// value in the first test (to 5e-9); twelve where max|ρ| > 10, since far past buckling three miss
// 1e-4 (F̄ = 50: 7.5158e26 against 7.5206e26 with six and twelve). Differences below 1e-8 of
// max(1, max|ρ|) are below the reference's own accuracy.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bladestab/modal/campbell.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double two_pi = 6.28318530717958647692;

// max|ρ| of a much richer model: 24 terms or 8 more, the Fourier series as the true train; on the
// whole Ritz model where the answer's is (`whole`) and for the true train, else on the automatic
// reduction of `vectors` (12 where max|ρ| > 10: a growth that large leaves 3 vectors' error at 1e-6
// of it, as large as the answer's).
double reference_max_rho(Scene scene, bool whole, int vectors = 3) {
  scene.model.basis = BasisKind::legendre;
  scene.model.terms = std::max(24, scene.model.terms + 8);
  if (scene.load.approximation == LoadApproximation::fourier) scene.load.approximation = LoadApproximation::exact;
  const BladeModel model = assemble_model(scene);
  // The true train is integrated only through its contacts: the whole Ritz model.
  const bool exact = scene.load.approximation == LoadApproximation::exact;
  const PeriodicSystem sys = periodic_system(model, scene, load_series(scene),
                                             {exact || whole ? ReductionKind::none : ReductionKind::automatic, vectors, 0});
  // The true train's contact ladder at 1e-9: its last level is within 1e-9 of the one before,
  // so (sixth-order Magnus) ~2e-11 from the limit, below the 1e-8 floor.
  const FloquetOptions o{FloquetMethod::monodromy, 0, exact ? 1e-9 : 1e-10, false};
  const double rho =
      (exact ? pulse_train_multipliers(sys, periodic_pulse(pulse_train(scene)), o) : floquet_multipliers(sys, o)).max_abs_multiplier;
  return rho > 10 && vectors < 12 && !whole && !exact ? reference_max_rho(scene, false, 12) : rho;
}

// The regions of the space a user tries; each is its own test case, so that ctest runs them side by side.
enum class Region { models_and_methods, loads_and_frequencies, true_pulse, damping };

struct Case {
  Region region;
  std::string name;
  std::vector<std::string> overrides;
  StabilityRequest request;
  // Where the load excites modes that a reduced reference misses: the whole Ritz model of the
  // scene's own basis, with this many Magnus steps (and twice as many, which must agree).
  int whole_model_steps = 0;
};

double whole_model_max_rho(const Scene& scene, int steps) {
  const PeriodicSystem whole = periodic_system(assemble_model(scene), scene, load_series(scene),
                                               {ReductionKind::none, 0, 0});
  const double rho = monodromy_multipliers(whole, steps).cwiseAbs().maxCoeff();
  CHECK(std::abs(monodromy_multipliers(whole, 2 * steps).cwiseAbs().maxCoeff() - rho) < 1e-10);
  return rho;
}

}  // namespace

TEST_CASE("the reduced reference agrees with the whole Ritz model (N = 8, 16384 Magnus steps)", "[budget][slow]") {
  // The whole 24-dof model integrates its 64 kHz modes: the independent check of the reduction.
  const Scene scene = paper_scene({"model.terms=8"});
  const BladeModel model = assemble_model(scene);
  const LoadSeries load = load_series(scene);
  const PeriodicSystem whole = periodic_system(model, scene, load, {ReductionKind::none, 0, 0});
  const PeriodicSystem reduced = periodic_system(model, scene, load, {ReductionKind::automatic, 3, 0});
  const double full = monodromy_multipliers(whole, 16384).cwiseAbs().maxCoeff();
  const double coarse = monodromy_multipliers(whole, 8192).cwiseAbs().maxCoeff();
  CHECK(std::abs(full - coarse) < 1e-8);  // the whole model's own convergence
  const double red = floquet_multipliers(reduced, {FloquetMethod::monodromy, 0, 1e-11, false}).max_abs_multiplier;
  CHECK(std::abs(red - full) < 1e-8);
  // Two independent integrations of this model in the issue (N = 12 and 14) give 2.1992296566 at
  // convergence; N = 8 is 2.3e-6 below it.
  CHECK(std::abs(reference_max_rho(paper_scene(), false) - 2.1992296566) < 1e-8);
}

namespace {

// The survey: 29 scenes across the space a user tries, by region.
std::vector<Case> survey() {
  const double w1 = two_pi * 68.0354;  // first bending mode at 300 rad/s (docs/theory.md §7)
  const auto theta = [w1](double ratio) { return "load.pulse_frequency_hz=" + std::to_string(ratio * w1 / two_pi); };
  const StabilityRequest plain{}, loose{FloquetMethod::automatic, 0, 1e-5};
  using R = Region;
  return {
      {R::models_and_methods, "scene as it ships (N = 16)", {}, plain},
      {R::models_and_methods, "N = 40", {"model.terms=40"}, plain},
      {R::loads_and_frequencies, "theta = 150 rad/s", {"load.pulse_frequency_hz=23.8732"}, plain},
      {R::loads_and_frequencies, "F = 20, monodromy", {"load.fmax_over_fcr=20"}, {FloquetMethod::monodromy, 0, 1e-4}},
      {R::loads_and_frequencies, "F = 50", {"load.fmax_over_fcr=50"}, {FloquetMethod::automatic, 0, 1e-4}},
      {R::models_and_methods, "classical Hill", {"model.terms=8"}, {FloquetMethod::hill, 0, 1e-5}},
      {R::models_and_methods, "Koopman-Hill, N = 8, F = 3, tol 1e-3", {"model.terms=8", "load.fmax_over_fcr=3"},
       {FloquetMethod::koopman_hill, 0, 1e-3}},
      {R::models_and_methods, "Koopman-Hill q = 16", {"model.terms=8"}, {FloquetMethod::koopman_hill, 16, 1e-6}},
      {R::loads_and_frequencies, "t_c = 1e-4 rev, Fourier", {"load.contact_time_rev=1e-4", "load.approximation=fourier"},
       plain},
      {R::loads_and_frequencies, "half-sine Fourier series", {"model.terms=8", "load.approximation=fourier"}, plain},
      {R::models_and_methods, "cut-off 2 kHz", {"model.reduction=modal", "model.cutoff_hz=2000"}, plain},
      {R::models_and_methods, "cut-off 5 kHz", {"model.reduction=modal", "model.cutoff_hz=5000"}, plain},
      {R::models_and_methods, "slenderness 1e-4", {"blade.slenderness=1e-4"}, plain},
      {R::loads_and_frequencies, "slenderness 0.3, F = 1", {"blade.slenderness=0.3", "load.fmax_over_fcr=1"}, plain},
      {R::loads_and_frequencies, "at rest, 50 Hz pulses",
       {"operation.speed_rad_s=0", "load.pulse_frequency_hz=50", "load.fmax_over_fcr=0.5"}, plain},
      {R::loads_and_frequencies, "theta = 0.3 w1", {theta(0.3)}, plain},
      {R::loads_and_frequencies, "theta = w1", {theta(1.0)}, plain},
      {R::loads_and_frequencies, "theta = 2 w1", {theta(2.0)}, plain},
      // The 3-vector reference is 6.5e-7 off here (1.061162988 against the whole model's
      // 1.0611623433, converged to 1e-13 between 1024 and 2048 steps and to 3e-13 between 2048
      // and 4096).
      {R::loads_and_frequencies, "theta = 3 w1", {theta(3.0)}, plain, 1024},
      {R::models_and_methods, "N = 4", {"model.terms=4"}, plain},
      {R::models_and_methods, "N = 60", {"model.terms=60"}, plain},
      {R::models_and_methods, "sine basis N = 10", {"model.basis=sine", "model.terms=10"},
       {FloquetMethod::automatic, 0, 1e-3}},
      // The true train at the default tolerance at the scene's speed; in its narrow tongues at 1e-5
      // (at 1e-6 the tongue at 106 rad/s raises N to 24, with a 36-term basis check: 27 s).
      {R::true_pulse, "exact pulse, 300 rad/s", {"load.approximation=exact"}, plain},
      {R::true_pulse, "exact pulse, tongue at 118 rad/s", {"load.approximation=exact", "operation.speed_rad_s=118"},
       loose},
      {R::true_pulse, "exact pulse, 2 per rev, 240 rad/s",
       {"load.approximation=exact", "operation.speed_rad_s=240", "load.pulses_per_rev=2"}, loose},
      // At 10 rad/s the reduction converges irregularly in its vectors: 6 and 12 agree to 3.7e-7, both
      // 4.2e-5 off the whole model; its 3 → 6 change, 7e-5, holds the part.
      {R::true_pulse, "exact pulse, 10 rad/s", {"load.approximation=exact", "operation.speed_rad_s=10"}, plain},
      // The sine basis meets a spurious tongue here (max|ρ| = 1.0348; 1.0330 at 60 terms, its richer
      // model's 2·difference 3.5e-3); the continuum blade is stable.
      {R::true_pulse, "sine basis N = 30, exact pulse", {"model.basis=sine", "model.terms=30", "load.approximation=exact"},
       plain},
      {R::damping, "paper damping 1 %", {"damping.model=paper", "damping.ratio=0.01"}, plain},
      {R::damping, "modal damping 2 %, F = 10", {"damping.model=modal", "damping.ratio=0.02", "load.fmax_over_fcr=10"},
       plain},
      {R::damping, "Rayleigh damping 1 %",
       {"damping.model=rayleigh", "damping.ratio=0.01", "damping.frequencies_hz=[50.0, 500.0]"}, plain},
      {R::true_pulse, "modal damping 1 %, exact pulse at 118 rad/s",
       {"damping.model=modal", "damping.ratio=0.01", "load.approximation=exact", "operation.speed_rad_s=118"}, loose},
  };
}

// Each scene of the region: the total estimate is not below the true error against the reference,
// and the verdict holds where the estimate separates max|ρ| from 1. Prints every ratio
// estimate/true and their spread over the region.
void check_region(Region region, std::size_t least_scenes) {
  std::vector<double> ratios;
  for (const Case& c : survey()) {
    if (c.region != region) continue;
    const Scene scene = paper_scene(c.overrides);
    const StabilityAnswer a = analyse_stability(scene, c.request);
    const double reference = c.whole_model_steps ? whole_model_max_rho(scene, c.whole_model_steps)
                                                 : reference_max_rho(scene, a.reduction.kind == ReductionKind::none);
    const double error = std::abs(a.floquet.max_abs_multiplier - reference);
    const double estimate = a.budget.total();
    const double floor = 1e-8 * std::max(1.0, reference);
    const double ratio = estimate / std::max(error, floor);
    ratios.push_back(ratio);
    std::printf("budget | %-38s | N %2d, vectors %2d | max|rho| %.10g | reference %.10g | true %.2e | estimate %.2e | "
                "ratio %.3g\n",
                c.name.c_str(), a.model.terms, a.reduction.vectors, a.floquet.max_abs_multiplier, reference, error,
                estimate, ratio);
    INFO(c.name << ": max|ρ| " << a.floquet.max_abs_multiplier << ", reference " << reference << ", estimate "
                << estimate);
    CHECK(estimate + floor >= error);
    // The verdict holds whenever the estimate separates max|ρ| from 1.
    if (std::abs(reference - 1) > estimate + floor) CHECK(a.stable == (reference <= 1 + floor));
  }
  REQUIRE(ratios.size() >= least_scenes);
  std::sort(ratios.begin(), ratios.end());
  std::printf("budget | ratio estimate/true: min %.3g, median %.3g, max %.3g over %zu scenes\n", ratios.front(),
              ratios[ratios.size() / 2], ratios.back(), ratios.size());
}

}  // namespace

TEST_CASE("total error estimate covers the true error over the space a user tries: models, bases and methods",
          "[budget][slow][parallel]") {
  CHECK(survey().size() >= 25);
  check_region(Region::models_and_methods, 11);
}

TEST_CASE("total error estimate covers the true error over the space a user tries: loads and pulse frequencies",
          "[budget][slow][parallel]") {
  check_region(Region::loads_and_frequencies, 11);
}

TEST_CASE("total error estimate covers the true error over the space a user tries: the true pulse train",
          "[budget][slow][parallel]") {
  check_region(Region::true_pulse, 4);
}

TEST_CASE("total error estimate covers the true error over the space a user tries: damping", "[budget][slow][parallel]") {
  check_region(Region::damping, 3);
}

TEST_CASE("a blade that diverges beyond the double range within a period is refused, not printed", "[budget][slow][parallel]") {
  // d̄ = 0.3 with the scene's F̄ = 5: the mean load is 2.5 F_cr, far past static buckling.
  CHECK_THROWS_AS(analyse_stability(paper_scene({"blade.slenderness=0.3"}), {}), NumericalError);
}

TEST_CASE("an estimate as large as max|rho| itself is refused, never a verdict", "[budget][parallel]") {
  // F̄ = 500 on a 4-term blade without its axial field: max|ρ| ≈ 6.5e260 with an estimate of 4.5e273
  // (the budget's models overflow differently), which printed "stable".
  const Scene scene = paper_scene({"model.terms=4", "model.axial=false", "load.fmax_over_fcr=500",
                                   "load.contact_time_rev=0.01", "load.profile=\"rectangular\""});
  CHECK_THROWS_WITH(analyse_stability(scene, {}), Catch::Contains("is as large as max|ρ| itself"));
}

TEST_CASE("a growth past 1e218 a period is an answer whose checks say what they cannot tell, never inf",
          "[budget][parallel]") {
  // A thick Euler–Bernoulli blade (d̄ = 0.99) without its axial field: max|ρ| ≈ 4.7e218. The
  // partners 1/ρ of its multipliers lie far below Φ's rounding, and ρ times a partner overflowed:
  // the reciprocal-pairs check printed "inf" (seed 2031). It is not informative there: NaN ("n/a").
  const Scene scene = paper_scene({"model.axial=false", "model.terms=7", "model.theory=\"euler-bernoulli\"",
                                   "blade.slenderness=0.99"});
  const StabilityAnswer a = analyse_stability(scene, {});
  CHECK(a.floquet.max_abs_multiplier > 1e200);
  CHECK_FALSE(a.stable);
  CHECK(std::isnan(a.floquet.checks.reciprocal_error));
  CHECK(std::isfinite(a.budget.total()));
  CHECK(a.floquet.multipliers.allFinite());
}

TEST_CASE("a monodromy matrix of 1e271 is checked on its own scale: a refusal, never a crash", "[budget][parallel]") {
  // A thick (d̄ = 0.3), 4-term blade under a cosine load twice a revolution at 250 rad/s: one budget
  // variant's Φ reaches 4e271, whose eigenvectors came out non-finite and crashed the LU of the
  // independent check (seed 2033, `boundaries`); another's passes the double range.
  const Scene scene = paper_scene({"load.pulses_per_rev=2", "load.approximation=\"cosine\"", "blade.slenderness=0.3",
                                   "model.coriolis=true", "load.profile=\"cosine\"", "load.contact_time_rev=0.05",
                                   "model.terms=4", "operation.speed_rad_s=250"});
  CHECK_THROWS_WITH(analyse_stability(scene, {}), Catch::Contains("overflows the double range"));
}

// The 9-pulse triangular train on 8 sine terms (seed 2036, `boundaries`), at θ = 2409.6 rad/s: inside
// the order-1 tongue of mode 2, where 1e-4 raises the basis to 200 terms.
namespace {
Scene nine_pulse_scene() {
  return paper_scene({"load.pulses_per_rev=9", "model.basis=\"sine\"", "load.profile=\"triangular\"",
                      "load.approximation=\"cosine\"", "model.terms=8", "load.pulse_frequency_hz=383.5"});
}
}  // namespace

TEST_CASE("a verdict stops raising the fidelity where its estimate decides it, and agrees with the tolerance's answer",
          "[budget][parallel]") {
  const Scene scene = nine_pulse_scene();
  const StabilityAnswer full = analyse_stability(scene, {FloquetMethod::automatic, 0, 1e-4});
  StabilityRequest request{FloquetMethod::automatic, 0, 1e-4};
  request.verdict_only = true;
  const StabilityAnswer verdict = analyse_stability(scene, request);
  REQUIRE(full.tolerance_met);
  CHECK_FALSE(full.stable);
  CHECK_FALSE(verdict.stable);
  CHECK(verdict.floquet.max_abs_multiplier - 1 > verdict.budget.total());
  CHECK(verdict.model.terms < full.model.terms);
  // The verdict's estimate covers its distance from the answer at 1e-4 (that one's error included).
  CHECK(std::abs(verdict.floquet.max_abs_multiplier - full.floquet.max_abs_multiplier) <=
        verdict.budget.total() + full.budget.total());
}

namespace {

// An answer left standing at `terms` because the work limit stopped the next round: `raising` and
// `why` in the reason the tolerance is not met.
void check_left_standing(const StabilityAnswer& a, int terms, const std::string& raising, const std::string& why) {
  CHECK(a.model.terms == terms);
  CHECK(a.work_limited);
  CHECK_FALSE(a.tolerance_met);
  CHECK_THAT(a.tolerance_unmet, Catch::Contains(raising) && Catch::Contains(why));
}

}  // namespace

TEST_CASE("the systems of the fidelity rounds count against the work: a round past it is not started",
          "[budget][parallel]") {
  // 8 sine terms and the variants' 8 and 16 (24, 24 and 48 dofs) take 8 (2·24³ + 48³) = 1.1e6 flops
  // (periodic_system_flops); 16 terms add 8.8e6, 32 terms 7.1e7.
  const Scene scene = nine_pulse_scene();
  StabilityRequest request{FloquetMethod::automatic, 0, 1e-4};
  request.work_flops = 4 * 2e7;
  check_left_standing(analyse_stability(scene, request), 16, "raising it to 32 terms per field",
                      "would pass the work limit");
  request.work_flops = 4 * 1e6;
  CHECK_THROWS_AS(analyse_stability(scene, request), WorkLimitError);
}

TEST_CASE("a raised round the work limit cannot finish leaves the last finished round's answer standing",
          "[budget][parallel][long_under_sanitizers]") {
  // Rectangular pulses, true train, 12 terms: the budget against 18 terms (0.015) raises to 18, then
  // to 27, whose monodromy ladder the work of 1e10 flops cannot take two levels of. Before, the
  // whole analysis failed there and printed nothing (the fan blade at F̄ = 6: after 100 s).
  const Scene scene =
      paper_scene({"model.terms=12", "load.profile=\"rectangular\"", "load.approximation=\"exact\""});
  StabilityRequest request;
  request.work_flops = 1e10;
  const StabilityAnswer a = analyse_stability(scene, request);
  check_left_standing(a, 18, "raising it to 27 terms per field did not finish", "work limit");
  // Its estimate covers the converged true train: 1.014855 at 27 terms and 1e-6, 1.014854 ± 3.1e-7
  // at 36 (`stability` at its default work).
  CHECK(a.budget.total() < 1e-4);
  CHECK(std::abs(a.floquet.max_abs_multiplier - 1.014855) <= a.budget.total() + 1e-6);
}

TEST_CASE("the first release's wrong answers are right now (issue table)", "[budget][parallel][long_under_sanitizers]") {
  // Each against the value the issue measured with independent integrations.
  CHECK(analyse_stability(paper_scene({"model.terms=40"}), {}).floquet.max_abs_multiplier ==
        Approx(2.1992297).epsilon(2e-7));
  const StabilityAnswer slow = analyse_stability(paper_scene({"load.pulse_frequency_hz=23.8732"}), {});
  CHECK(slow.floquet.max_abs_multiplier == Approx(2.0290551).epsilon(2e-7));
  CHECK_FALSE(slow.stable);
  const StabilityAnswer buckled =
      analyse_stability(paper_scene({"load.fmax_over_fcr=20"}), {FloquetMethod::monodromy, 0, 1e-4});
  CHECK(buckled.floquet.multipliers(0).real() == Approx(-4.56e8).epsilon(2e-3));
  CHECK(analyse_stability(paper_scene({"model.terms=8", "load.fmax_over_fcr=3"}), {FloquetMethod::koopman_hill, 0, 1e-3})
            .stable);
}

TEST_CASE("answers do not depend on --threads: stability's budget and campbell's estimate, 1 against 2", "[budget][threads][parallel]") {
  SECTION("stability: the variants in turn or beside the answer") {
    const Scene scene = paper_scene();
    StabilityAnswer a[2];
    for (int t = 1; t <= 2; ++t) a[t - 1] = analyse_stability(scene, {FloquetMethod::automatic, 0, 1e-6, t});
    CHECK(a[0].floquet.max_abs_multiplier == a[1].floquet.max_abs_multiplier);
    CHECK(a[0].budget.basis == a[1].budget.basis);
    CHECK(a[0].budget.reduction == a[1].budget.reduction);
    CHECK(a[0].budget.method == a[1].budget.method);
    CHECK(a[0].model.terms == a[1].model.terms);
  }
  SECTION("stability: the failure reported where two variants fail, in turn or side by side") {
    // A thick blade (d̄ = 0.99) at 3000 rad/s with little work: the reduction variant's ladder and the
    // basis variant's both stop at the work limit, at different levels (fuzz seed 2038).
    const Scene scene = paper_scene({"load.contact_time_rev=0.08", "operation.speed_rad_s=3000", "model.terms=5",
                                     "blade.slenderness=0.99", "load.pulse_frequency_hz=430.02"});
    std::string failure[2];
    for (int t = 1; t <= 2; ++t) {
      StabilityRequest request{FloquetMethod::automatic, 0, 1e-4, t};
      request.work_flops = 8e8;
      try {
        analyse_stability(scene, request);
      } catch (const WorkLimitError& e) {
        failure[t - 1] = e.what();
      }
    }
    CHECK_THAT(failure[0], Catch::Contains("Magnus steps per period, all that the work limit affords"));
    CHECK(failure[0] == failure[1]);
  }
  SECTION("campbell: the richer models in turn or on a second thread") {
    CampbellOptions o;
    for (int k = 0; k < 21; ++k) o.speeds_rad_s.push_back(30.0 * k);
    o.engine_orders = {1, 2, 3};
    o.mode_count = 4;
    const auto with_threads = [&o](int t) {
      o.threads = t;
      return campbell_with_error_estimate(paper_scene(), o, 1e-6);
    };
    const CampbellWithErrors c[2] = {with_threads(1), with_threads(2)};
    REQUIRE(c[0].diagram.curves.size() == c[1].diagram.curves.size());
    for (std::size_t m = 0; m < c[0].diagram.curves.size(); ++m) {
      CHECK(c[0].diagram.curves[m].frequency_hz == c[1].diagram.curves[m].frequency_hz);
      for (std::size_t s = 0; s < c[0].budget[m].size(); ++s) CHECK(c[0].budget[m][s].total() == c[1].budget[m][s].total());
    }
    CHECK(c[0].diagram.crossings.size() == c[1].diagram.crossings.size());
  }
}

TEST_CASE("stability's progress counts the answer's levels and its variants, and leaves the answer alone", "[budget][parallel][long_under_sanitizers]") {
  // The cosine approximation by the automatic method and by Koopman–Hill, and the true pulse train
  // (its contact's step ladder).
  for (const auto& [approximation, method] : {std::pair{"cosine", FloquetMethod::automatic},
                                              std::pair{"cosine", FloquetMethod::koopman_hill},
                                              std::pair{"exact", FloquetMethod::automatic}}) {
    const Scene scene = paper_scene({"model.terms=8", std::string("load.approximation=") + approximation});
    INFO("load.approximation = " << approximation);
    std::vector<std::pair<int, int>> calls;
    StabilityRequest counted{method, 0, 1e-5, 2};
    counted.progress = [&calls](int done, int total) { calls.emplace_back(done, total); };
    const StabilityAnswer quiet = analyse_stability(scene, {method, 0, 1e-5, 2}), loud = analyse_stability(scene, counted);
    CHECK(quiet.floquet.max_abs_multiplier == loud.floquet.max_abs_multiplier);
    CHECK(quiet.budget.total() == loud.budget.total());
    // Each level of the answer's refinement (Koopman–Hill: its q, then the monodromy it is checked
    // against) and each variant (basis, reduction) counts one; done never passes the total.
    const int variants = 2;
    const int levels = method == FloquetMethod::automatic ? 2 : 2 + 2;  // at least two levels per ladder
    REQUIRE(calls.size() >= static_cast<std::size_t>(levels + variants));
    CHECK(calls.front().first == 1);
    for (std::size_t i = 1; i < calls.size(); ++i) {
      CHECK(calls[i].first - calls[i - 1].first <= 1);
      CHECK(calls[i].first >= calls[i - 1].first);
      CHECK(calls[i].first <= calls[i].second);
    }
    CHECK(calls.back().first == calls.back().second);
    CHECK(calls.back().first >= levels + variants);
  }
}

TEST_CASE("a tolerance the reduction keeps out of reach names the reduction part and quotes the whole estimate",
          "[budget]") {
  // 8 terms at 129 rad/s under the Fourier series: the 3 vectors are 0.097 off twice as many, the
  // basis 1.8e-3; 3 vectors are the richest level below the 24-dof model.
  const Scene scene = paper_scene({"model.terms=8", "load.approximation=fourier", "operation.speed_rad_s=129"});
  const StabilityAnswer a = analyse_stability(scene, {FloquetMethod::automatic, 0, 1e-4});
  REQUIRE_FALSE(a.tolerance_met);
  REQUIRE(a.budget.reduction > 10 * a.budget.basis);
  CHECK_THAT(a.tolerance_unmet, Catch::Contains("its reduction part") && Catch::Contains("model.reduction = \"none\""));
  const double relative = a.budget.total() / std::max(1.0, a.floquet.max_abs_multiplier);
  CHECK_THAT(a.tolerance_unmet, Catch::Contains(fmt::format("estimated error {:.2g}", relative)));
}
