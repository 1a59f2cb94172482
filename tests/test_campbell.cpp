// Campbell diagram: mode tracking by shape through crossings, engine-order crossing points.
#include <catch2/catch.hpp>

#include <cmath>

#include "bladestab/campbell.hpp"
#include "bladestab/damping.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {
constexpr double two_pi = 6.28318530717958647692;

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
  return v;
}
}  // namespace

TEST_CASE("without Coriolis coupling, bending modes cross the first axial mode and tracking follows shapes",
          "[campbell]") {
  const Scene s = paper_scene({"model.coriolis=false"});
  const BladeModel model = assemble_model(s.blade, s.model);
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 1500, 31), {}, 6});
  const CampbellCurve& axial = d.curves[4];
  REQUIRE(axial.family == ModeFamily::axial);
  // The axial frequency only softens slightly with speed (−ρAΩ² ∫u²): Ω = 0 value (2n−1)π/2 · c/L.
  const double f_axial = std::sqrt(117e9 / 4466.0) / 4;
  CHECK(axial.frequency_hz.front() == Approx(f_axial).epsilon(1e-9));
  for (std::size_t i = 0; i < d.speeds_rad_s.size(); ++i) {
    // Decoupled axial bar spinning: ω² = ω0² − Ω² exactly for every axial mode.
    const double W = d.speeds_rad_s[i];
    CHECK(axial.frequency_hz[i] == Approx(std::sqrt(std::pow(two_pi * f_axial, 2) - W * W) / two_pi).epsilon(1e-8));
    CHECK(axial.correlation[i] == Approx(1).epsilon(1e-12));
  }
  // Bending modes 3 and 4 start below and end above it; sort order would have swapped labels.
  for (int k : {2, 3}) {
    CHECK(d.curves[k].frequency_hz.front() < axial.frequency_hz.front());
    CHECK(d.curves[k].frequency_hz.back() > axial.frequency_hz.back());
    for (std::size_t i = 1; i < d.speeds_rad_s.size(); ++i) {
      CHECK(d.curves[k].frequency_hz[i] > d.curves[k].frequency_hz[i - 1]);
    }
  }
}

TEST_CASE("with Coriolis coupling, modes veer and stay tracked", "[campbell]") {
  const Scene s = paper_scene();
  const BladeModel model = assemble_model(s.blade, s.model);
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 1500, 61), {}, 6});
  for (const CampbellCurve& c : d.curves) {
    for (std::size_t i = 1; i < c.frequency_hz.size(); ++i) {
      CHECK(c.correlation[i] > 0.5);
      CHECK(std::abs(c.frequency_hz[i] / c.frequency_hz[i - 1] - 1) < 0.1);
    }
  }
}

TEST_CASE("engine-order crossings are refined to where the mode meets the line", "[campbell]") {
  const Scene s = paper_scene();
  const BladeModel model = assemble_model(s.blade, s.model);
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 600, 13), {2, 3, 4, 8}, 4});
  REQUIRE(d.crossings.size() >= 5);
  for (const EngineOrderCrossing& x : d.crossings) {
    INFO("EO " << x.engine_order << ", mode " << x.mode);
    CHECK(x.frequency_hz == Approx(x.engine_order * x.speed_rad_s / two_pi).epsilon(1e-14));
    // Independently: at that speed the mode's frequency is on the line.
    const SecondOrderSystem sys = system_at(model, x.speed_rad_s, damping_matrix(model, s.damping, x.speed_rad_s));
    const ModalSolution sol = solve_modes(model, sys, x.speed_rad_s, 6, EigenSolverKind::dense);
    double closest = 1e300;
    for (const Mode& m : sol.modes) closest = std::min(closest, std::abs(m.frequency_hz / x.frequency_hz - 1));
    CHECK(closest < 1e-9);
  }
  for (std::size_t i = 1; i < d.crossings.size(); ++i) {
    CHECK(d.crossings[i].speed_rad_s >= d.crossings[i - 1].speed_rad_s);
  }
}
