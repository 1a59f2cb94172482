// Damping in the boundary equations and the map, and maps of the true pulse train: with damping a principal region no longer reaches
// F̄ = 0 (a parametric resonance must overcome the dissipation), its boundaries move up, and the
// boundary equations, which carry the damping in their Ĉ term, agree with an independent Floquet
// analysis of the damped system.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/stability/stability_map.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

constexpr double two_pi = 6.28318530717958647692;

// The principal region of mode 1 at Ω = 300 rad/s lies near θ = 2ω₁ = 853 rad/s (the cosine load's
// mean compression bends it to lower θ); θ = 836 rad/s is inside it for F̄ ≳ 0.4 undamped.
constexpr double theta = 836;

Scene scene_with(const std::string& damping) {
  std::vector<std::string> overrides{"model.terms=6"};
  if (!damping.empty()) {
    overrides.push_back("damping.model=" + damping.substr(0, damping.find(':')));
    overrides.push_back("damping.ratio=" + damping.substr(damping.find(':') + 1));
  }
  overrides.push_back("load.pulse_frequency_hz=" + std::to_string(theta / two_pi));
  return paper_scene(overrides);
}

// max|ρ| of the whole Ritz model at F̄ by its monodromy matrix (2048 Magnus steps: 1e-10 here).
double floquet_max_rho(Scene s, double fbar) {
  s.load.fmax_over_fcr = fbar;
  const double speed = s.operation.speed_rad_s;
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, speed, damping_matrix(m, s.damping, speed), load_series(s),
                                             {ReductionKind::none, 0, 0});
  return monodromy_multipliers(sys, 2048).cwiseAbs().maxCoeff();
}

// The lowest boundary F̄ at θ from the boundary equations of the whole Ritz model.
double lowest_boundary(const Scene& s) {
  BoundaryRequest r;
  r.theta_rad_s = theta;
  r.cutoff_hz = 0;
  r.window = std::make_pair(0.0, 3 * assemble_model(s).blade.critical_load());
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  REQUIRE(!a.boundaries.empty());
  const double fcr = assemble_model(s).blade.critical_load();
  return a.boundaries.front().boundary.peak_force_n / fcr;
}

}  // namespace

TEST_CASE("damped boundaries move up and agree with the damped Floquet multipliers", "[boundaries][damping][slow]") {
  const double undamped = lowest_boundary(scene_with(""));
  for (const std::string damping : {"modal:0.01", "paper:0.02"}) {
    const Scene s = scene_with(damping);
    const double fbar = lowest_boundary(s);
    INFO(damping << ": lowest boundary F̄ = " << fbar << " (undamped " << undamped << ")");
    CHECK(fbar > undamped * 1.01);
    // Independently: the damped multipliers leave the unit circle there (|ρ| < 1 below, > 1 above;
    // a damped pair meets −1 on the real axis, so max|ρ| − 1 changes sign linearly).
    CHECK(floquet_max_rho(s, fbar * (1 - 1e-4)) < 1);
    CHECK(floquet_max_rho(s, fbar * (1 + 1e-4)) > 1);
  }
}

TEST_CASE("a damped map's principal region is lifted off the F-bar = 0 axis", "[map][damping][parallel]") {
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = {780, 800, 820, 840, 860, 880};
  o.grid_fbar = {0, 0.1, 0.2, 0.3};
  o.trace = {0.1, 0.2, 0.3};
  o.resolution_x = 6;
  o.resolution_y = 4;
  const auto largest_low = [&](const std::string& damping) {
    const StabilityMap map = stability_map(scene_with(damping), o);
    double largest = 0;
    for (const MapSample& p : map.samples) {
      if (p.fbar > 0) largest = std::max(largest, p.max_abs_multiplier);
    }
    return largest;
  };
  // Undamped, the region reaches down to F̄ → 0 at θ = 2ω₁: some low-load point is unstable.
  CHECK(largest_low("") > 1 + o.tolerance);
  // With 1 % modal damping every point up to F̄ = 0.3 is stable (the region starts near F̄ = 0.5).
  CHECK(largest_low("modal:0.01") < 1);
}

TEST_CASE("a damped region's traced boundary is closed through its tip, and the tip is where Floquet says",
          "[map][damping][fold][parallel][long_under_sanitizers]") {
  const Scene s = scene_with("modal:0.01");
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = {700, 800, 900};
  o.grid_fbar = {0, 1.5, 3};
  o.trace = {0.3, 0.5, 0.7, 0.9, 1.1, 1.3, 1.5};  // the tip (F̄ ≈ 0.53) between the second and third
  o.resolution_x = 3;
  o.resolution_y = 3;
  const StabilityMap map = stability_map(s, o);
  std::vector<const BoundaryCurve*> principal;
  for (const BoundaryCurve& c : map.curves) {
    if (c.multiplier == -1 && c.mode == 1 && c.order == 1) principal.push_back(&c);
  }
  // Both edges of the region in one curve, its lowest point between two trace lines.
  REQUIRE(principal.size() == 1);
  const BoundaryCurve& c = *principal.front();
  const auto tip = std::min_element(c.fbar.begin(), c.fbar.end()) - c.fbar.begin();
  const double tip_theta = c.x[tip], tip_fbar = c.fbar[tip];
  INFO("tip at θ = " << tip_theta << ", F̄ = " << tip_fbar);
  CHECK(tip_fbar > 0.5);
  CHECK(tip_fbar < 0.7);
  CHECK(tip > 0);
  CHECK(tip + 1 < static_cast<long>(c.fbar.size()));
  // Floquet at the tip's θ: stable 1 % below it, unstable 1 % above (inside the narrow tip).
  Scene at = s;
  at.load.pulse_frequency_hz = tip_theta / two_pi;
  CHECK(floquet_max_rho(at, tip_fbar * 0.99) < 1);
  CHECK(floquet_max_rho(at, tip_fbar * 1.01) > 1);
}

namespace {

// max|ρ| of the true half-sine train on the whole Ritz model: Φ(T) = e^{A_free (T − t_c)} Φ_contact
// (docs/theory.md §3–§4), Φ_contact by Boost.Odeint's Dormand–Prince (rtol 1e-10) through the contact, the
// free flight's exponential from the eigenvectors of A_free, V e^{Λ(T − t_c)} V⁻¹. Shares no code
// with the map's piecewise monodromy (Magnus through the contact, Padé scaling and squaring for the
// free flight). Dormand–Prince through the free flight too gave the same max|ρ| to 2e-10 on the
// nine grid points of the map below (100× the cost: its step is held by the whole model's stiffest
// mode for the whole period).
double odeint_true_pulse_max_rho(const Scene& s) {
  const BladeModel m = assemble_model(s);
  const double speed = s.operation.speed_rad_s;
  const PeriodicSystem sys = periodic_system(m, speed, damping_matrix(m, s.damping, speed), load_series(s),
                                             {ReductionKind::none, 0, 0});
  const PulseTrain train = pulse_train(s);
  const Eigen::MatrixXd A_free = sys.A0 - sys.coefficients.at(0).real() * sys.B;  // the mean's share back out
  const int n = sys.state_size();
  using State = std::vector<double>;
  Eigen::MatrixXd contact(n, n);
  for (int column = 0; column < n; ++column) {
    State x(n, 0.0);
    x[column] = 1;
    const auto rhs = [&](const State& y, State& dy, double t) {
      const Eigen::Map<const Eigen::VectorXd> Y(y.data(), n);
      Eigen::Map<Eigen::VectorXd> D(dy.data(), n);
      D = A_free * Y + train.force(t) * (sys.B * Y);
    };
    auto stepper = boost::numeric::odeint::make_controlled<boost::numeric::odeint::runge_kutta_dopri5<State>>(1e-12, 1e-10);
    boost::numeric::odeint::integrate_adaptive(stepper, rhs, x, 0.0, train.contact_time_s, train.contact_time_s / 50);
    contact.col(column) = Eigen::Map<Eigen::VectorXd>(x.data(), n);
  }
  const Eigen::EigenSolver<Eigen::MatrixXd> free_modes(A_free);
  const Eigen::VectorXcd growth = (free_modes.eigenvalues() * (train.period_s - train.contact_time_s)).array().exp();
  const Eigen::MatrixXd flight =
      (free_modes.eigenvectors() * growth.asDiagonal() * free_modes.eigenvectors().inverse()).real();
  return (flight * contact).eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("a map of the true pulse train matches an independent integration of the train", "[map][exact][parallel][long_under_sanitizers]") {
  // The speed plane of the paper blade's true half-sine train (t̄c = 0.01), N = 4 for a cheap
  // reference; six refined samples against Boost.Odeint on the whole Ritz model.
  const Scene s = paper_scene({"model.terms=4", "load.approximation=exact"});
  MapOptions o;
  o.plane = MapPlane::speed_fmax;
  o.grid_x = {100, 300, 500};
  o.grid_fbar = {0, 4, 8};
  o.trace = {100, 500};
  o.resolution_x = 6;
  o.resolution_y = 6;
  const StabilityMap map = stability_map(s, o);
  CHECK(map.curves.empty());  // no boundary equations for the true train: shaded only
  REQUIRE(map.samples.size() >= 9);
  // Every unstable sample (up to four: the thin tongues are where the two could differ) and two
  // stable ones.
  std::vector<MapSample> chosen;
  for (const MapSample& p : map.samples) {
    if (p.max_abs_multiplier > 1 + o.tolerance && chosen.size() < 4) chosen.push_back(p);
  }
  const std::size_t unstable = chosen.size();
  for (const MapSample& p : map.samples) {
    if (p.max_abs_multiplier <= 1 && chosen.size() < unstable + 2) chosen.push_back(p);
  }
  CHECK(unstable >= 1);
  int checked = 0;
  for (const MapSample& p : chosen) {
    Scene at = s;
    at.operation.speed_rad_s = p.x;
    at.load.pulse_frequency_hz = p.x / two_pi;
    at.load.fmax_over_fcr = p.fbar;
    const double reference = odeint_true_pulse_max_rho(at);
    INFO("Ω = " << p.x << ", F̄ = " << p.fbar << ": map " << p.max_abs_multiplier << ", odeint " << reference);
    CHECK(std::abs(p.max_abs_multiplier - reference) <= o.tolerance * std::max(1.0, reference));
    ++checked;
  }
  CHECK(checked >= 3);
}
