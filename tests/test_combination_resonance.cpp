// Combination resonances named by their modes: on two modes coupled only through a parametric load,
// where the resonance is known (θ = ω₁ + ω₂ for a symmetric coupling, θ = ω₂ − ω₁ for an
// antisymmetric one), and on the paper blade's θ-plane map against the whole Ritz model's
// multipliers and an independent eigen-solve of its frequencies under the mean load.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "bladestab/stability/combination_resonance.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/stability/stability_map.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

// q̈ + diag(ω₁², ω₂²) q + F(t) G q = 0 with F(t) = 2a cos θt and G the coupling alone.
FloquetResult two_mode_multipliers(double w1, double w2, const Eigen::Matrix2d& G, double a, double theta) {
  ReducedSystem r;
  r.basis = Eigen::MatrixXd::Identity(2, 2);
  r.K = Eigen::Vector2d(w1 * w1, w2 * w2).asDiagonal();
  r.C = Eigen::MatrixXd::Zero(2, 2);
  r.G = G;
  r.full_size = 2;
  r.undamped = true;
  LoadSeries load;
  load.angular_frequency = theta;
  load.coefficients = {0.0, a};
  return floquet_multipliers(periodic_system(r, load), {FloquetMethod::monodromy, 0, 1e-10, false});
}

}  // namespace

TEST_CASE("two modes coupled by the load: the unstable multiplier is named by the sum or the difference it sits at",
          "[combination]") {
  const double w1 = 60, w2 = 170;
  const Eigen::VectorXd omega = Eigen::Vector2d(w1, w2);
  struct Case {
    Eigen::Matrix2d G;
    double theta;
    bool sum;
  };
  Eigen::Matrix2d symmetric, antisymmetric;
  symmetric << 0, 1, 1, 0;
  antisymmetric << 0, 1, -1, 0;
  // A symmetric coupling destabilizes the sum, an antisymmetric (circulatory) one the difference.
  for (const Case& c : {Case{symmetric, w1 + w2, true}, Case{antisymmetric, w2 - w1, false},
                        Case{symmetric, 1.01 * (w1 + w2), true}}) {
    const FloquetResult r = two_mode_multipliers(w1, w2, c.G, 400, c.theta);
    const std::complex<double> rho = r.multipliers(0);
    INFO("θ = " << c.theta << ": ρ = " << rho);
    REQUIRE(r.max_abs_multiplier > 1.01);
    REQUIRE(std::abs(rho.imag()) > 0.05 * std::abs(rho));  // a complex pair, not ±1
    const std::optional<Combination> named = nearest_combination(omega, c.theta, rho, 4);
    REQUIRE(named.has_value());
    CHECK(named->mode_i == 1);
    CHECK(named->mode_j == 2);
    CHECK(named->sum == c.sum);
    CHECK(named->order == 1);
    CHECK(named->detuning == Approx((c.sum ? w1 + w2 : w2 - w1) / c.theta - 1).margin(1e-12));
  }
  // Away from every combination the same multiplier phase names nothing.
  const FloquetResult r = two_mode_multipliers(w1, w2, symmetric, 400, w1 + w2);
  CHECK_FALSE(nearest_combination(omega, 1.5 * (w1 + w2), r.multipliers(0), 1).has_value());
}

TEST_CASE("the paper blade's theta plane: the islands near 720-850 rad/s are (w1 + w2)/2, confirmed at their point",
          "[combination][map][parallel][long_under_sanitizers]") {
  const Scene scene = paper_scene({"model.terms=8"});
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  for (int i = 0; i <= 10; ++i) o.grid_x.push_back(650 + 25.0 * i);
  for (int j = 0; j <= 7; ++j) o.grid_fbar.push_back(2 + 1.0 * j);
  o.trace = {4.0, 6.0};
  o.resolution_x = 80, o.resolution_y = 40;
  const StabilityMap map = stability_map(scene, o);
  const CombinationRegion* island = nullptr;
  for (const CombinationRegion& r : map.combinations) {
    if (r.x >= 700 && r.x <= 860 && r.fbar >= 4 && r.fbar <= 8 && (!island || r.samples > island->samples)) island = &r;
  }
  REQUIRE(island != nullptr);
  INFO("island at θ = " << island->x << ", F̄ = " << island->fbar << ", " << island->samples << " samples");
  CHECK(island->combination.mode_i == 1);
  CHECK(island->combination.mode_j == 2);
  CHECK(island->combination.sum);
  CHECK(island->combination.order == 2);
  CHECK(island->samples >= 10);
  // Independently: the whole Ritz model's multipliers there are a complex unstable pair, and its
  // frequencies under the mean load (the cosine load's F₀ = −F_max/2 as a static tip compression)
  // put ω₁ + ω₂ within a tenth of 2θ.
  Scene at = scene;
  at.load.pulse_frequency_hz = island->x / (2 * M_PI);
  at.load.fmax_over_fcr = island->fbar;
  const BladeModel model = assemble_model(at);
  const FloquetResult whole = floquet_multipliers(periodic_system(model, at, load_series(at), {ReductionKind::none, 0, 0}),
                                                  {FloquetMethod::monodromy, 0, 1e-8, false});
  CHECK(whole.max_abs_multiplier == Approx(island->max_abs_multiplier).epsilon(1e-3));
  CHECK(std::abs(whole.multipliers(0).imag()) > 0.05 * whole.max_abs_multiplier);
  const BladeModel compressed = assemble_model(paper_scene({"model.terms=8", "operation.tip_compression_over_fcr=" +
                                                                                 std::to_string(island->fbar / 2)}));
  const Eigen::VectorXd w = undamped_modes(compressed, 300, 0, 2, false).omega2.cwiseSqrt();
  CHECK(std::abs(w(0) + w(1) - 2 * island->x) <= 0.1 * island->x);
}
