// Boundaries with error estimates: k raised to the tolerance converges to the large-k value, the
// estimated whole error covers the true error against a richer model, Mathieu's tongues with the
// automatic k, and the multiplier check.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/stability/instability_regions.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "reference/mathieu.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using reference::MathieuKind;
using testing_support::mathieu_scene;
using testing_support::paper_scene;

namespace {

// The reference boundaries: the paper blade with a richer model, straight from the eigenproblem.
std::vector<Boundary> reference_loads(const Scene& s, double theta, int k) {
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s), {ReductionKind::none, 0, 0});
  return boundary_loads(sys, s.load.fmax_over_fcr * m.blade.critical_load(), theta, k);
}

// The reference boundary nearest to b of the same family, mode and order.
const Boundary* counterpart(const Boundary& b, const std::vector<Boundary>& all) {
  const Boundary* best = nullptr;
  for (const Boundary& r : all) {
    if (r.multiplier != b.multiplier || r.mode != b.mode || r.order != b.order) continue;
    if (!best || std::abs(r.peak_force_n - b.peak_force_n) < std::abs(best->peak_force_n - b.peak_force_n)) best = &r;
  }
  return best;
}

// The regions of `s` along θ in [lo, hi] (boundaries of order ≤ max_order), as `boundaries` lists them.
std::vector<InstabilityRegion> regions_between(const Scene& s, double lo, double hi, int max_order = 4) {
  BoundaryRequest r;
  r.window = std::make_pair(lo, hi);
  r.max_order = max_order;
  return instability_regions(s, r, boundaries_with_error_estimate(s, r));
}

}  // namespace

TEST_CASE("boundaries at theta = 300: k is raised until converged, to the large-k value within the estimate",
          "[boundaries][slow]") {
  // The whole model (no reduction), as the reference's: the harmonics' part alone is compared.
  const Scene s = paper_scene({"model.terms=8", "model.reduction=\"none\""});
  BoundaryRequest r;
  r.theta_rad_s = 300;
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  const double fcr = assemble_model(s).blade.critical_load();
  // k = 4 gives the mode-1, order-2 boundary at F̄ = 6.1594; k >= 8 gives 6.0926.
  CHECK(a.approximation >= 6);
  const std::vector<Boundary> k12 = reference_loads(s, 300, 12);
  int compared = 0;
  for (const EstimatedBoundary& e : a.boundaries) {
    const Boundary* ref = counterpart(e.boundary, k12);
    REQUIRE(ref != nullptr);
    const double truth = std::abs(e.boundary.peak_force_n / ref->peak_force_n - 1);
    INFO("F̄ = " << e.boundary.peak_force_n / fcr << " (k = 12: " << ref->peak_force_n / fcr << "), mode "
                 << e.boundary.mode << ", order " << e.boundary.order << ": harmonics' estimate " << e.budget.method
                 << ", true " << truth << ", ratio " << e.budget.method / truth);
    CHECK(truth <= e.budget.method);
    CHECK(e.budget.method <= r.tolerance);
    ++compared;
  }
  CHECK(compared >= 5);
  const auto principal = std::find_if(a.boundaries.begin(), a.boundaries.end(), [&](const EstimatedBoundary& e) {
    return e.boundary.multiplier == 1 && std::abs(e.boundary.peak_force_n / fcr - 6.0926) < 1e-3;
  });
  REQUIRE(principal != a.boundaries.end());
  // The check: a Floquet multiplier at −1 or +1 by RKF45 monodromy.
  REQUIRE(!a.checks.empty());
  for (const BoundaryCheck& c : a.checks) CHECK(c.gap <= c.allowed);
}

TEST_CASE("boundaries: the whole error estimate covers the true error against a richer model", "[boundaries][slow]") {
  // N = 8 with the estimate against N = 12; the truth from N = 14 (Legendre: exponential
  // convergence) with 4 harmonics more than the analysis chose.
  const Scene s = paper_scene({"model.terms=8"});
  const Scene rich = paper_scene({"model.terms=14"});
  const double fcr = assemble_model(s).blade.critical_load();
  int compared = 0;
  // θ = 300 has its own test (k raised until converged) above.
  for (double theta : {250.0, 400.0}) {
    BoundaryRequest r;
    r.theta_rad_s = theta;
    const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
    const std::vector<Boundary> truth_set = reference_loads(rich, theta, a.approximation + 4);
    for (const EstimatedBoundary& e : a.boundaries) {
      const Boundary* ref = counterpart(e.boundary, truth_set);
      REQUIRE(ref != nullptr);
      const double truth = std::abs(e.boundary.peak_force_n / ref->peak_force_n - 1);
      INFO("θ = " << theta << ", F̄ = " << e.boundary.peak_force_n / fcr << " (N = 14: " << ref->peak_force_n / fcr
                  << "), mode " << e.boundary.mode << ", order " << e.boundary.order << ": estimate "
                  << e.budget.total() << " (basis " << e.budget.basis << "), true " << truth << ", ratio "
                  << e.budget.total() / truth);
      CHECK(truth <= e.budget.total());
      ++compared;
    }
  }
  CHECK(compared >= 8);
}

TEST_CASE("boundaries: with a modal cut-off the reduction part covers the true error", "[boundaries][slow]") {
  const Scene s = paper_scene({"model.terms=8"});
  const double fcr = assemble_model(s).blade.critical_load();
  BoundaryRequest r;
  r.theta_rad_s = 300;
  r.cutoff_hz = 3000;  // drops the rotation modes and all but the first axial mode
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  const std::vector<Boundary> truth_set = reference_loads(paper_scene({"model.terms=14"}), 300, a.approximation + 4);
  REQUIRE(a.boundaries.size() >= 4);
  for (const EstimatedBoundary& e : a.boundaries) {
    const Boundary* ref = counterpart(e.boundary, truth_set);
    REQUIRE(ref != nullptr);
    const double truth = std::abs(e.boundary.peak_force_n / ref->peak_force_n - 1);
    INFO("F̄ = " << e.boundary.peak_force_n / fcr << " (N = 14, all modes: " << ref->peak_force_n / fcr
                 << "): estimate " << e.budget.total() << " (reduction " << e.budget.reduction << "), true " << truth
                 << ", ratio " << e.budget.total() / truth);
    CHECK(e.budget.reduction > 0);
    CHECK(truth <= e.budget.total());
  }
}

TEST_CASE("boundaries: the automatic reduction's part covers the change to the whole model at the same k",
          "[boundaries][slow]") {
  // The θ window at F̄ = 5: the truth is the whole Ritz model's boundary at the harmonics the answer
  // comes from, so their difference is the reduction's error alone. (Where the reduction is raised
  // to the step before the whole model, the part is that change itself.)
  const Scene s = paper_scene({"model.terms=10"});
  const BladeModel m = assemble_model(s);
  const double peak = s.load.fmax_over_fcr * m.blade.critical_load();
  const PeriodicSystem whole = periodic_system(m, s, load_series(s), {ReductionKind::none, 0, 0});
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, BoundaryRequest{});
  REQUIRE(a.reduction.kind == ReductionKind::automatic);
  CHECK(3 * a.reduction.vectors * 2 < a.full_size);  // the part is estimated, not the change to the whole model
  REQUIRE(a.boundaries.size() >= 5);
  std::map<int, std::vector<Boundary>> truth_at;  // k → the whole model's boundaries
  for (const EstimatedBoundary& e : a.boundaries) {
    if (!truth_at.count(e.approximation)) truth_at[e.approximation] = boundary_frequencies(whole, peak, e.approximation);
    const Boundary* ref = nullptr;
    for (const Boundary& b : truth_at[e.approximation]) {
      const double distance = std::abs(b.theta_rad_s - e.boundary.theta_rad_s);
      if (b.multiplier == e.boundary.multiplier && b.mode == e.boundary.mode &&
          (!ref || distance < std::abs(ref->theta_rad_s - e.boundary.theta_rad_s))) {
        ref = &b;
      }
    }
    REQUIRE(ref != nullptr);
    const double truth = std::abs(e.boundary.theta_rad_s / ref->theta_rad_s - 1);
    INFO("θ = " << e.boundary.theta_rad_s << ", order " << e.boundary.order << ": reduction part "
                << e.budget.reduction << ", true " << truth);
    CHECK(truth <= e.budget.reduction);
    CHECK(e.budget.reduction <= BoundaryRequest{}.tolerance / 2);
  }
}

TEST_CASE("boundaries: Mathieu's first two tongues with the automatic k", "[boundaries][mathieu][long_under_sanitizers]") {
  for (double fbar : {0.2, 0.6, 1.2}) {
    const Scene s = mathieu_scene(fbar);
    const BladeModel m = assemble_model(s);
    const double w0 = std::sqrt(m.K_S(0, 0) / m.M(0, 0));
    BoundaryRequest r;
    r.tolerance = 1e-9;
    r.window = std::make_pair(0.25 * w0, 4 * w0);  // the tongues θ ≈ 2ω and θ ≈ ω (ω ≥ 0.63 ω0 under the mean load)
    const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
    // τ = θt/2: y'' + (a − 2q cos 2τ) y = 0 with x = 4ω0²/θ², a = x(1 − F̄/2), q = −x F̄/4 (as in
    // test_stability.cpp); the edges are where a equals a characteristic value.
    for (auto [kind, rank, x0, x1] : {std::tuple{MathieuKind::a_odd, 0, 0.01, 60.0}, std::tuple{MathieuKind::b_odd, 0, 0.01, 60.0},
                                      std::tuple{MathieuKind::a_even, 1, 2.0, 80.0}, std::tuple{MathieuKind::b_even, 0, 2.0, 80.0}}) {
      const double theta = reference::mathieu_blade_boundary(kind, rank, fbar, w0, x0, x1);
      const EstimatedBoundary* best = nullptr;
      for (const EstimatedBoundary& e : a.boundaries) {
        if (!best || std::abs(e.boundary.theta_rad_s - theta) < std::abs(best->boundary.theta_rad_s - theta)) best = &e;
      }
      REQUIRE(best != nullptr);
      const double truth = std::abs(best->boundary.theta_rad_s / theta - 1);
      INFO("F̄ = " << fbar << ", kind " << static_cast<int>(kind) << ": θ = " << theta << ", found "
                  << best->boundary.theta_rad_s << " with k = " << a.approximation << ", estimate "
                  << best->budget.total() << ", true " << truth);
      // The one-dof model is Mathieu's equation exactly, so its error is the method part (the
      // basis part is the beam's, against two terms); 5e-12 is the reference's own rounding.
      CHECK(truth <= best->budget.method + 5e-12);
      CHECK(best->budget.method <= r.tolerance);
    }
    for (const BoundaryCheck& c : a.checks) CHECK(c.gap <= c.allowed);
  }
}

TEST_CASE("boundaries: where the stiffness touches zero (F̄ = 1) the pinched tongues do not sink the first two, "
          "at every starting k from 2 to 20", "[boundaries][mathieu][long_under_sanitizers]") {
  // F̄ = 1: a = 2q, Mathieu's line where the stiffness vanishes once a period. The tongues of high
  // order at low θ pinch and converge slowly or not at all in k; the order-1 and order-2 edges
  // converge at small k and must be reported whatever k the run starts from.
  const Scene s = mathieu_scene(1.0);
  const BladeModel m = assemble_model(s);
  const double w0 = std::sqrt(m.K_S(0, 0) / m.M(0, 0));
  // The edges a₁ and b₁ (order 1, θ ≈ 199 and 327 rad/s), a₂ and b₂ (order 2, θ ≈ 108 and 138).
  std::vector<double> edges;
  for (auto [kind, rank, x0, x1] : {std::tuple{MathieuKind::a_odd, 0, 0.01, 60.0}, std::tuple{MathieuKind::b_odd, 0, 0.01, 60.0},
                                    std::tuple{MathieuKind::a_even, 1, 2.0, 80.0}, std::tuple{MathieuKind::b_even, 0, 2.0, 80.0}}) {
    edges.push_back(reference::mathieu_blade_boundary(kind, rank, 1.0, w0, x0, x1));
  }
  for (int k = 2; k <= 20; ++k) {
    BoundaryRequest r;
    r.first_approximation = k;
    r.window = std::make_pair(10.0, 400.0);
    const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
    INFO("starting k = " << k << ": chosen k = " << a.approximation << ", " << a.boundaries.size() << " converged, "
                          << a.unconverged.size() << " not");
    for (double theta : edges) {
      const EstimatedBoundary* best = nullptr;
      for (const EstimatedBoundary& e : a.boundaries) {
        if (!best || std::abs(e.boundary.theta_rad_s - theta) < std::abs(best->boundary.theta_rad_s - theta)) best = &e;
      }
      REQUIRE(best != nullptr);
      const double truth = std::abs(best->boundary.theta_rad_s / theta - 1);
      INFO("Mathieu θ = " << theta << ", found " << best->boundary.theta_rad_s << " (order " << best->boundary.order
                          << "), estimate " << best->budget.method << ", true " << truth);
      CHECK(truth <= 1e-8);
      CHECK(truth <= best->budget.method + 5e-12);
    }
    // What did not converge is listed with how far it got, never mixed with the answer.
    for (const UnconvergedBoundary& u : a.unconverged) {
      CHECK(u.approximation + 4 <= r.max_approximation);
      if (u.change && !u.check_failed) CHECK(2 * *u.change + eigensolver_rounding > r.tolerance);
      CHECK(u.boundary.theta_rad_s >= 10.0);
      CHECK(u.boundary.theta_rad_s <= 400.0);
    }
    for (const BoundaryCheck& c : a.checks) CHECK(c.gap <= c.allowed);
  }
}

TEST_CASE("boundaries: a work limit stops the raising of k, and the edges that converged are still the answer",
          "[boundaries][mathieu]") {
  // Mathieu at F̄ = 1 as above, where the pinched tongues would raise k to its largest: a budget of
  // the work up to k = 10 stops there, and the order-1 and order-2 edges (converged by then) are
  // Mathieu's; whatever k reached is the same with one thread or two.
  const Scene s = mathieu_scene(1.0);
  const BladeModel m = assemble_model(s);
  const double w0 = std::sqrt(m.K_S(0, 0) / m.M(0, 0));
  const double a1 = reference::mathieu_blade_boundary(MathieuKind::a_odd, 0, 1.0, w0, 0.01, 60.0);
  const double b2 = reference::mathieu_blade_boundary(MathieuKind::b_even, 0, 1.0, w0, 2.0, 80.0);
  double budget = 0;
  for (int k = 2; k <= 14; k += 2) budget += boundary_level_flops(k, 1, true);
  std::vector<BoundaryAnalysis> runs;
  for (int threads : {1, 2}) {
    BoundaryRequest r;
    r.window = std::make_pair(10.0, 400.0);
    r.work_flops = budget;
    r.threads = threads;
    runs.push_back(boundaries_with_error_estimate(s, r));
  }
  const BoundaryAnalysis& a = runs[0];
  CHECK(a.work_limited);
  CHECK(a.approximation <= 10);
  CHECK(!a.unconverged.empty());
  CHECK(runs[1].approximation == a.approximation);
  CHECK(runs[1].boundaries.size() == a.boundaries.size());
  for (double theta : {a1, b2}) {
    const EstimatedBoundary* best = nullptr;
    for (const EstimatedBoundary& e : a.boundaries) {
      if (!best || std::abs(e.boundary.theta_rad_s - theta) < std::abs(best->boundary.theta_rad_s - theta)) best = &e;
    }
    REQUIRE(best != nullptr);
    INFO("Mathieu θ = " << theta << ", found " << best->boundary.theta_rad_s << " at k = " << a.approximation);
    CHECK(std::abs(best->boundary.theta_rad_s / theta - 1) <= 1e-8);
  }
}

TEST_CASE("boundaries: the families side by side give the answer of one thread, and progress counts to its end",
          "[boundaries][slow][parallel]") {
  const Scene s = paper_scene({"model.terms=3"});
  std::vector<BoundaryAnalysis> runs;
  std::vector<std::pair<int, int>> calls;
  for (int threads : {1, 2}) {
    BoundaryRequest r;
    r.threads = threads;
    if (threads == 2) r.progress = [&calls](int done, int total) { calls.emplace_back(done, total); };
    runs.push_back(boundaries_with_error_estimate(s, r));
  }
  REQUIRE(runs[0].boundaries.size() == runs[1].boundaries.size());
  REQUIRE_FALSE(runs[0].boundaries.empty());
  CHECK(runs[0].approximation == runs[1].approximation);
  for (std::size_t i = 0; i < runs[0].boundaries.size(); ++i) {
    const EstimatedBoundary &a = runs[0].boundaries[i], &b = runs[1].boundaries[i];
    CHECK(a.boundary.theta_rad_s == b.boundary.theta_rad_s);  // the same eigenproblems: equal to the last bit
    CHECK(a.boundary.multiplier == b.boundary.multiplier);
    CHECK(a.boundary.order == b.boundary.order);
    CHECK(a.budget.total() == b.budget.total());
  }
  // One call per harmonic level of each model: the ladder's k, k + 2 (and k + 4) up to the chosen k,
  // and the richer basis; done counts up by one, never past the total, which ends equal to it.
  REQUIRE(calls.size() >= 4);
  for (std::size_t i = 0; i + 1 < calls.size(); ++i) {
    CHECK(calls[i].first == static_cast<int>(i) + 1);
    CHECK(calls[i].first < calls[i].second);
  }
  CHECK(calls.back().first == calls.back().second);
  CHECK(calls.back().first == static_cast<int>(calls.size()) - 1);
  CHECK(calls.back().first >= (runs[1].approximation - 2) / 2 + 3);
}

TEST_CASE("boundaries: the multiplier check tells a boundary from a point inside the region", "[boundaries][mathieu]") {
  // Mathieu scene, F̄ = 0.6: the principal (−1) tongue between the edges a₁ and b₁.
  const Scene s = paper_scene({"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false", "model.basis=sine",
                               "operation.speed_rad_s=0", "load.approximation=cosine", "load.fmax_over_fcr=0.6"});
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, s, load_series(s));
  const double peak = 0.6 * m.blade.critical_load();
  std::vector<Boundary> edges;
  for (const Boundary& b : boundary_frequencies(sys, peak, 8)) {
    if (b.multiplier == -1 && b.order == 1) edges.push_back(b);
  }
  REQUIRE(edges.size() == 2);
  for (const Boundary& b : edges) CHECK(multiplier_gap(sys, peak, b, 1e-10).gap.value() < 1e-3);
  // Halfway between the edges the multiplier is real, below −1: far from −1.
  Boundary inside = edges[0];
  inside.theta_rad_s = 0.5 * (edges[0].theta_rad_s + edges[1].theta_rad_s);
  CHECK(multiplier_gap(sys, peak, inside, 1e-10).gap.value() > 0.1);
}

TEST_CASE("boundaries at F̄ = 0 are the tongues' tips 2ω₁/n, in pairs, and no region", "[boundaries][regions]") {
  // Without load the scaled check system was 0/0 (a non-finite exponential, exit 1, nothing printed).
  const Scene s = paper_scene({"load.fmax_over_fcr=0"});  // θ = Ω = 300 rad/s, window [150, 600]
  const BoundaryRequest r;
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  // The closed form: the lowest mode of the whole Ritz model at Ω with its Coriolis coupling (which
  // moves it by 6.6e-4 from the non-gyroscopic one; `modes` prints 68.0354375847 Hz).
  const BladeModel model = assemble_model(s);
  const Eigen::MatrixXd no_damping = Eigen::MatrixXd::Zero(model.M.rows(), model.M.cols());
  const double omega1 = dense_eigenpairs(system_at(model, 300, no_damping)).values.imag().minCoeff();
  std::map<int, int> per_order;
  for (const EstimatedBoundary& e : a.boundaries) {
    CHECK(e.boundary.mode == 1);
    CHECK(e.boundary.multiplier == (e.boundary.order % 2 == 0 ? 1 : -1));
    CHECK(std::abs(e.boundary.theta_rad_s / (2 * omega1 / e.boundary.order) - 1) <= e.budget.total() + 1e-9);
    ++per_order[e.boundary.order];
  }
  CHECK(per_order == std::map<int, int>{{2, 2}, {3, 2}, {4, 2}});  // 2ω₁ = 855 rad/s is outside the window
  CHECK(instability_regions(s, r, a).empty());
}

TEST_CASE("boundaries: a thin tongue's region is checked until its estimate decides, not dropped as stable",
          "[boundaries][regions][parallel]") {
  // F̄ = 0.5: the +1 pair of order 4 at 209.72696 and 209.72706 rad/s encloses max|ρ| = 1.0000031,
  // which the middle's check at 1e-4 left within its estimate (6.7e-6) of 1: the region was dropped.
  const Scene s = paper_scene({"load.fmax_over_fcr=0.5"});
  const std::vector<InstabilityRegion> regions = regions_between(s, 205, 215);
  REQUIRE(regions.size() == 1);
  const InstabilityRegion& thin = regions[0];
  CHECK(thin.multiplier == 1);
  CHECK(thin.upper - thin.lower < 2e-4);
  // The reference: `stability` at the middle at 1e-9, whatever the region code asked.
  Scene middle = s;
  middle.load.pulse_frequency_hz = 0.5 * (thin.lower + thin.upper) / (2 * M_PI);
  StabilityRequest tight;
  tight.tolerance = 1e-9;
  const StabilityAnswer reference = analyse_stability(middle, tight);
  REQUIRE(reference.floquet.max_abs_multiplier - 1 > 10 * reference.budget.total());
  CHECK(thin.middle_max_abs_multiplier - 1 > thin.middle_error_estimate);
  CHECK(std::abs(thin.middle_max_abs_multiplier - reference.floquet.max_abs_multiplier) <=
        thin.middle_error_estimate + reference.budget.total());
}

TEST_CASE("boundaries along θ with a pulse series: the regions' middles hold the series' duty, as the boundaries do",
          "[boundaries][regions][series][parallel]") {
  // t̄c = 0.3 under the Fourier series: the boundary equations keep the coefficients of the scene's
  // duty t_c/T_p along θ. The middle was checked with t_c held instead (1.0426 at the middle of the
  // order-2 region, where the duty held gives 1.0545), so regions and boundaries answered two loads.
  const Scene s = paper_scene({"model.terms=8", "load.approximation=fourier", "load.contact_time_rev=0.3",
                               "load.fmax_over_fcr=0.8"});
  const std::vector<InstabilityRegion> regions = regions_between(s, 400, 450, 2);
  REQUIRE(regions.size() == 1);
  const double middle_theta = 0.5 * (regions[0].lower + regions[0].upper);
  const auto at_middle = [&](double contact_time_rev) {
    Scene at = s;
    at.load.pulse_frequency_hz = middle_theta / (2 * M_PI);
    at.load.contact_time_rev = contact_time_rev;
    StabilityRequest tight;
    tight.tolerance = 1e-8;
    return analyse_stability(at, tight);
  };
  const StabilityAnswer duty_held = at_middle(0.3 * 300 / middle_theta), contact_held = at_middle(0.3);
  CHECK(std::abs(regions[0].middle_max_abs_multiplier - duty_held.floquet.max_abs_multiplier) <=
        regions[0].middle_error_estimate + duty_held.budget.total());
  CHECK(std::abs(contact_held.floquet.max_abs_multiplier - duty_held.floquet.max_abs_multiplier) > 1e-3);
}

TEST_CASE("boundaries: neighbouring unstable intervals of one sign are one region, the boundary between inside it",
          "[boundaries][regions][parallel]") {
  // F̄ = 5: past the principal −1 region's lower edge at 473.77 rad/s a −1 boundary at 514.29 (the
  // upper edge of a mode-2 tongue of order 5) had split it into two regions, each checked unstable.
  const Scene s = paper_scene({"model.terms=8"});
  const std::vector<InstabilityRegion> regions = regions_between(s, 460, 600);
  REQUIRE(regions.size() == 1);
  CHECK(regions[0].multiplier == -1);
  CHECK(regions[0].lower == Approx(473.7713).epsilon(1e-6));
  CHECK(regions[0].upper_open);
  REQUIRE(regions[0].inner.size() == 1);
  const double inner = regions[0].inner[0];
  CHECK(inner == Approx(514.28953).epsilon(1e-6));
  // Unstable, of the −1 family, on both sides of it: `stability` 0.5 % either side.
  for (const double side : {0.995, 1.005}) {
    Scene at = s;
    at.load.pulse_frequency_hz = side * inner / (2 * M_PI);
    const StabilityAnswer x = analyse_stability(at, {FloquetMethod::automatic, 0, 1e-6});
    CHECK(x.floquet.max_abs_multiplier > 1.5);
    CHECK(x.floquet.multipliers(0).real() < 0);
  }
}

TEST_CASE("boundaries: regions at the scene's load hold the paper point, and the Floquet verdict flips at their ends",
          "[boundaries][regions][slow][parallel]") {
  const Scene s = paper_scene({"model.terms=8"});  // θ = Ω = 300 rad/s, F̄ = 5
  const BoundaryRequest r;
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  const std::vector<InstabilityRegion> regions = instability_regions(s, r, a);
  REQUIRE(!regions.empty());
  // The scene's own point: the +1 region of mode 1, order 2, between 258.9 and 329.4 rad/s (README).
  const auto holds = std::find_if(regions.begin(), regions.end(), [](const InstabilityRegion& g) {
    return g.lower < 300 && g.upper > 300 && g.multiplier == 1 && g.mode == 1 && g.order == 2;
  });
  REQUIRE(holds != regions.end());
  CHECK(holds->lower == Approx(258.9).epsilon(1e-3));
  CHECK(holds->upper == Approx(329.4).epsilon(1e-3));
  // Independently of the middle check: Floquet multipliers (the whole budget at 1e-6) just inside
  // each closed end are unstable, with the family's real multiplier, and inside every region.
  const auto dominant_at = [&](double theta) {
    Scene at = s;
    at.load.pulse_frequency_hz = theta / 6.28318530717958647692;
    const StabilityAnswer answer = analyse_stability(at, {FloquetMethod::automatic, 0, 1e-6});
    return std::make_pair(answer.stable, answer.floquet.multipliers(0));
  };
  for (const InstabilityRegion& g : regions) {
    INFO("region " << g.lower << " … " << g.upper << ", multiplier " << g.multiplier << ", mode " << g.mode
                   << ", order " << g.order);
    for (double f : {0.001, 0.5, 0.999}) {
      if ((f < 0.01 && g.lower_open) || (f > 0.99 && g.upper_open)) continue;
      const auto [stable, rho] = dominant_at(g.lower + f * (g.upper - g.lower));
      CHECK(!stable);
      CHECK(rho.real() * g.multiplier > 1);
    }
  }
  // Verdicts that cannot be reached within the work they may take leave their intervals undecided,
  // listed with why, not dropped: every region found above begins and ends with one of them (a
  // region joined from two unstable intervals spans two undecided ones, which are not joined).
  BoundaryRequest starved = r;
  starved.work_flops = 1;
  const std::vector<InstabilityRegion> undecided = instability_regions(s, starved, a);
  for (const InstabilityRegion& g : undecided) CHECK_THAT(g.undecided, Catch::Contains("work limit"));
  for (const InstabilityRegion& g : regions) {
    const auto has = [&](auto end_matches) {
      return std::any_of(undecided.begin(), undecided.end(), [&](const InstabilityRegion& u) {
        return u.multiplier == g.multiplier && end_matches(u);
      });
    };
    CHECK(has([&](const InstabilityRegion& u) { return u.lower == g.lower; }));
    CHECK(has([&](const InstabilityRegion& u) { return u.upper == g.upper; }));
  }
  // Just outside the scene's region, on both sides, the +1 instability is gone.
  for (double theta : {holds->lower * (1 - 1e-3), holds->upper * (1 + 1e-3)}) {
    const auto [stable, rho] = dominant_at(theta);
    INFO("θ = " << theta << ": dominant ρ = " << rho);
    CHECK((stable || rho.real() < 0 || std::abs(rho.imag()) > 1e-6 * std::abs(rho)));
  }
}

TEST_CASE("boundaries --at-theta with a pulse series: the pulses come at the theta asked for", "[boundaries][series][slow][parallel]") {
  // A long pulse (t_c = 0.3 rev) as its own Fourier series: the duty t_c/T, so every F_m, depends on θ.
  const Scene s = paper_scene({"model.terms=8", "load.approximation=\"fourier\"", "load.contact_time_rev=0.3"});
  BoundaryRequest r;
  r.theta_rad_s = 400;  // the scene's own θ is 300
  const double fcr = assemble_model(s).blade.critical_load();
  r.window = std::make_pair(0.0, 3 * fcr);
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  REQUIRE(!a.boundaries.empty());
  const double first = a.boundaries.front().boundary.peak_force_n / fcr;
  // Independently: the Floquet verdict of the scene with its pulses at 400 rad/s flips there.
  const auto stable_at = [&](double fbar) {
    Scene at = s;
    at.load.pulse_frequency_hz = 400 / 6.28318530717958647692;
    at.load.fmax_over_fcr = fbar;
    return analyse_stability(at, {FloquetMethod::automatic, 0, 1e-6}).stable;
  };
  INFO("first boundary F̄ = " << first);
  CHECK(first == Approx(1.927735).epsilon(1e-5));
  CHECK(stable_at(first * (1 - 1e-3)));
  CHECK_FALSE(stable_at(first * (1 + 1e-3)));
}
