// Stability maps: traced boundaries carry a Floquet multiplier at ±1 (an independent check by
// monodromy), and the shading agrees with the Mathieu tongue it surrounds.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/stability/stability_map.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {
std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
  return v;
}

// A θ-plane map's options: shading grid in θ and F̄, trace lines in F̄.
MapOptions theta_plane(std::vector<double> theta, std::vector<double> fbar, std::vector<double> trace) {
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = std::move(theta);
  o.grid_fbar = std::move(fbar);
  o.trace = std::move(trace);
  return o;
}

// A speed-plane map's options: shading grid in Ω and F̄ refined to `cells_x` × `cells_y`, trace lines in Ω.
MapOptions speed_plane(std::vector<double> speeds, std::vector<double> fbar, std::vector<double> trace, int cells_x,
                       int cells_y) {
  MapOptions o = theta_plane(std::move(speeds), std::move(fbar), std::move(trace));
  o.plane = MapPlane::speed_fmax;
  o.resolution_x = cells_x;
  o.resolution_y = cells_y;
  return o;
}

// The Floquet multipliers at a map point, by the whole model's monodromy (4096 Magnus steps over the
// whole period: at a boundary point the two multipliers at ±1 move like the square root of Φ's
// rounding, which half a period with U⁻¹ would raise by U's condition).
Eigen::VectorXcd multipliers_at(const Scene& base, double speed, double theta, double fbar) {
  Scene s = base;
  s.operation.speed_rad_s = speed;
  s.load.pulse_frequency_hz = theta / (2 * 3.14159265358979323846);
  s.load.fmax_over_fcr = fbar;
  const BladeModel m = assemble_model(s);
  const PeriodicSystem sys = periodic_system(m, speed, damping_matrix(m, s.damping, speed), load_series(s));
  return sorted_eigenvalues(magnus_monodromy(sys, 4096, true));
}

// The multiplier closest to `target` (±1) at a map point.
double distance_to_multiplier(const Scene& base, double speed, double theta, double fbar, double target) {
  const Eigen::VectorXcd rho = multipliers_at(base, speed, theta, fbar);
  return (rho.array() - target).abs().minCoeff();
}
}  // namespace

TEST_CASE("speed-plane map: every traced boundary point has a multiplier at +1 or -1", "[map][slow][parallel]") {
  const Scene scene = paper_scene({"model.terms=3", "model.axial=false"});
  MapOptions o;
  o.plane = MapPlane::speed_fmax;
  o.grid_x = linspace(100, 600, 3);
  o.grid_fbar = linspace(0, 3, 3);  // below the static buckling load (F̄ ≈ 3.9 at 100 rad/s)
  o.trace = linspace(100, 600, 51);
  // 12 harmonics per family: the boundary equations' truncation then moves F̄ by less than 1e-12
  // (at 8 harmonics a point near F̄ = 3 had its multiplier 7e-6 from +1).
  o.approximation = 12;
  o.resolution_x = 2;  // the curves are under test: the shading stays on the 3 × 3 grid
  o.resolution_y = 2;
  const StabilityMap map = stability_map(scene, o);
  REQUIRE(map.curves.size() >= 2);
  int checked = 0;
  for (const BoundaryCurve& c : map.curves) {
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      INFO("curve ρ = " << c.multiplier << ", mode " << c.mode << ", order " << c.order << " at Ω = " << c.x[k]
                        << ", F̄ = " << c.fbar[k]);
      // At a boundary two multipliers meet at ±1 and split like the square root of the distance
      // from it: 1e-6 in ρ is ~1e-12 in F̄ (measured worst: 4e-7).
      CHECK(distance_to_multiplier(scene, c.x[k], c.x[k], c.fbar[k], c.multiplier) < 1e-6);
      ++checked;
    }
  }
  CHECK(checked >= 6);
}

TEST_CASE("theta-plane map of Mathieu's equation: unstable inside the principal tongue, stable outside", "[map][mathieu][parallel]") {
  const Scene scene = paper_scene({"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false",
                                   "model.basis=sine", "operation.speed_rad_s=300"});
  const BladeModel model = assemble_model(scene);
  const double w0 = std::sqrt(model.stiffness(300)(0, 0) / model.M(0, 0));
  const double fcr = model.blade.critical_load();
  // Centre of the principal tongue: twice the frequency under the mean load −F_max/2.
  const auto centre = [&](double fbar) { return 2 * std::sqrt(model.stiffness(300, -fbar / 2 * fcr)(0, 0) / model.M(0, 0)); };
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = {0.6 * centre(0.6), centre(0.6), 1.4 * centre(0.6)};  // left of, inside, right of the tongue at F̄ = 0.6
  o.grid_fbar = {0.6};
  o.trace = linspace(0, 1, 21);
  o.approximation = 8;
  o.tolerance = 1e-8;
  const StabilityMap map = stability_map(scene, o);
  CHECK(map.max_abs_multiplier(0, 0) < 1 + 1e-8);
  CHECK(map.max_abs_multiplier(0, 1) > 1 + 1e-3);  // 1.045: spinning stiffens the single mode
  CHECK(map.max_abs_multiplier(0, 2) < 1 + 1e-8);
  // The two edges of the principal tongue meet at θ = 2ω0 on the F̄ = 0 axis: one curve, closed
  // there, with points left and right of the tongue's centre.
  CHECK(centre(0) == Approx(2 * w0).epsilon(1e-14));
  int closed = 0;
  for (const BoundaryCurve& c : map.curves) {
    if (c.multiplier != -1) continue;
    const auto tip = std::min_element(c.fbar.begin(), c.fbar.end()) - c.fbar.begin();
    bool left = false, right = false;
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      if (c.fbar[k] <= 0) continue;
      left = left || c.x[k] < centre(c.fbar[k]);
      right = right || c.x[k] > centre(c.fbar[k]);
    }
    if (c.fbar[tip] == 0 && std::abs(c.x[tip] / (2 * w0) - 1) < 1e-12 && left && right) ++closed;
  }
  CHECK(closed == 1);
}

TEST_CASE("refined shading: leaves tile the lattice, agree at their corners, and samples match the whole model",
          "[map][refinement][slow][parallel]") {
  const Scene scene = paper_scene({"model.terms=4"});
  MapOptions o = theta_plane(linspace(150, 650, 6), linspace(0, 6, 4), linspace(0, 6, 7));
  o.tolerance = 1e-7;
  o.resolution_x = 40;
  o.resolution_y = 24;
  const StabilityMap map = stability_map(scene, o);
  REQUIRE(map.cells_x == 40);  // 5 grid cells split 8 times
  REQUIRE(map.cells_y == 24);  // 3 grid cells split 8 times

  // The leaves cover the lattice once.
  Eigen::MatrixXi cover = Eigen::MatrixXi::Zero(map.cells_y, map.cells_x);
  for (const MapCell& c : map.cells) cover.block(c.j, c.i, c.height, c.width).array() += 1;
  CHECK(cover.minCoeff() == 1);
  CHECK(cover.maxCoeff() == 1);
  // The refinement went down to single cells somewhere, and skipped a good part of the lattice.
  int unit = 0;
  for (const MapCell& c : map.cells) unit += c.width == 1 && c.height == 1;
  CHECK(unit > 20);
  CHECK(map.samples.size() < static_cast<std::size_t>(3 * (map.cells_x + 1) * (map.cells_y + 1) / 4));

  // Every 14th sample against the whole (unreduced) N = 4 model's monodromy with 1024 Magnus steps:
  // independent of the reduction and of the step ladder (on every 7th sample, 72, 2048 steps are
  // within 8e-13 of 4096, 1024 within 1.4e-10).
  int compared = 0;
  for (std::size_t k = 0; k < map.samples.size(); k += 14) {
    const MapSample& p = map.samples[k];
    Scene at = scene;
    at.load.pulse_frequency_hz = p.x / (2 * 3.14159265358979323846);
    at.load.fmax_over_fcr = p.fbar;
    const BladeModel m = assemble_model(at);
    const PeriodicSystem whole = periodic_system(m, at, load_series(at), {ReductionKind::none, 0, 0});
    const double rho = monodromy_multipliers(whole, 1024).cwiseAbs().maxCoeff();
    INFO("θ = " << p.x << ", F̄ = " << p.fbar << ": map " << p.max_abs_multiplier << ", whole model " << rho);
    // The map's tolerance on the method, plus the 3-vector reduction's error (≲1e-7 here).
    CHECK(std::abs(p.max_abs_multiplier - rho) <= 1e-6 * std::max(1.0, rho));
    ++compared;
  }
  CHECK(compared >= 20);
}

TEST_CASE("map marks the scene's point with its max|rho| and the nearest boundary along F-bar", "[map][scene-point][slow][parallel]") {
  const Scene s = paper_scene({"model.terms=8"});  // θ = Ω = 300 rad/s, F̄ = 5
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = linspace(200, 400, 3);
  o.grid_fbar = linspace(0, 8, 3);
  o.trace = linspace(0, 8, 9);
  o.resolution_x = 2;
  o.resolution_y = 2;
  const StabilityMap map = stability_map(s, o);
  REQUIRE(map.scene_point);
  const MapPoint& p = *map.scene_point;
  CHECK(p.x == Approx(300));
  CHECK(p.fbar == 5);
  // The monodromy of the whole N = 8 model (README: 2.1992274) to the map's tolerance.
  CHECK(p.max_abs_multiplier == Approx(2.1992274).epsilon(o.tolerance));
  // Independently: every boundary F̄ at θ = 300 from the `boundaries --at-theta` analysis (k raised
  // to 1e-6, checked by RKF45); the nearest to F̄ = 5 within the curves' tolerance of the window.
  BoundaryRequest r;
  r.theta_rad_s = 300;
  r.window = std::make_pair(0.0, 8 * assemble_model(s).blade.critical_load());
  const BoundaryAnalysis a = boundaries_with_error_estimate(s, r);
  const double fcr = assemble_model(s).blade.critical_load();
  double nearest = 1e300;
  for (const EstimatedBoundary& e : a.boundaries) {
    if (std::abs(e.boundary.peak_force_n / fcr - 5) < std::abs(nearest - 5)) nearest = e.boundary.peak_force_n / fcr;
  }
  REQUIRE(p.nearest_boundary);
  INFO("map: " << p.nearest_boundary->fbar << ", boundaries: " << nearest);
  CHECK(std::abs(p.nearest_boundary->fbar - nearest) <= o.tolerance * 8);
}

namespace {

// 50 random refined samples of a plane's map against the whole model's monodromy.
void check_random_samples(bool theta_plane) {
  const Scene s = paper_scene({"model.terms=8"});  // the main job's model
  MapOptions o;
  o.plane = theta_plane ? MapPlane::theta_fmax : MapPlane::speed_fmax;
  o.grid_x = theta_plane ? linspace(100, 1000, 14) : linspace(50, 600, 14);
  o.grid_fbar = linspace(0, 10, 14);
  o.trace = theta_plane ? linspace(0, 10, 27) : linspace(50, 600, 27);
  // One split of the 13 × 13 grid cells (26 × 26 effective): 337 refined samples on the θ plane,
  // 277 on the speed plane; the draw needs 200.
  o.resolution_x = 26;
  o.resolution_y = 13;
  const StabilityMap map = stability_map(s, o);
  REQUIRE(map.samples.size() >= 200);
  const BladeModel model = assemble_model(s);
  // A fixed pseudo-random draw (Knuth's multiplicative hash of the index) of 50 evaluated points.
  int checked = 0;
  for (std::size_t k = 0; checked < 50; ++k) {
    const MapSample& p = map.samples[(k * 2654435761u) % map.samples.size()];
    if (std::isnan(p.max_abs_multiplier)) continue;
    Scene at = s;
    if (!theta_plane) at.operation.speed_rad_s = p.x;
    at.load.pulse_frequency_hz = p.x / (2 * 3.14159265358979323846);
    at.load.fmax_over_fcr = p.fbar;
    // Independent: the whole Ritz model (no reduction) by the Magnus monodromy to the map's tolerance,
    // its own estimate added to what the comparison allows.
    const PeriodicSystem whole = periodic_system(model, at, load_series(at), {ReductionKind::none, 0, 0});
    const FloquetResult ref = floquet_multipliers(whole, {FloquetMethod::monodromy, 0, o.tolerance, false});
    INFO((theta_plane ? "θ = " : "Ω = ") << p.x << ", F̄ = " << p.fbar << ": map " << p.max_abs_multiplier
                                         << ", whole model " << ref.max_abs_multiplier << " ± " << ref.error_estimate);
    CHECK(std::abs(p.max_abs_multiplier - ref.max_abs_multiplier) <=
          o.tolerance * std::max(1.0, ref.max_abs_multiplier) + ref.error_estimate);
    ++checked;
  }
}

}  // namespace

// Each plane its own test case, so that ctest runs them side by side.
TEST_CASE("50 random refined samples of the theta-plane map match the whole model's monodromy to the map's tolerance",
          "[map][samples][slow][parallel]") {
  check_random_samples(true);
}

TEST_CASE("50 random refined samples of the speed-plane map match the whole model's monodromy to the map's tolerance",
          "[map][samples][slow][parallel]") {
  check_random_samples(false);
}

namespace {
// Distance in the plot's unit square from point p to the polyline (xs, ys).
double distance_to_polyline(double px, double py, const std::vector<double>& xs, const std::vector<double>& ys) {
  double best = 1e300;
  for (std::size_t j = 0; j < xs.size(); ++j) {
    const std::size_t k = std::min(j + 1, xs.size() - 1);
    const double dx = xs[k] - xs[j], dy = ys[k] - ys[j], length2 = dx * dx + dy * dy;
    const double t = length2 > 0 ? std::clamp(((px - xs[j]) * dx + (py - ys[j]) * dy) / length2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(px - xs[j] - t * dx, py - ys[j] - t * dy));
  }
  return best;
}
}  // namespace

TEST_CASE("theta-plane map of the paper blade: curves followed through their changes of name end on the plot's edge "
          "or at another curve, and their points are boundaries of the whole model",
          "[map][slow][parallel]") {
  // The main job's θ plane. At high loads a boundary's name (its eigenvector's dominant mode and
  // harmonic) changes along it: the −1 pair of mode 2, order 7 near θ = 307 rad/s is "mode 1,
  // order 3" from F̄ = 9, and the 2ω₁ boundary near θ = 500 rad/s, F̄ = 5.5 becomes "mode 2,
  // order 5". Cut where the name left the orders drawn, 5 curve ends hung in mid-air.
  const Scene scene = paper_scene({"model.terms=8"});
  MapOptions o = theta_plane(linspace(100, 1000, 3), linspace(0, 10, 3), linspace(0, 10, 101));
  o.resolution_x = 2;  // the curves are under test: the shading stays on the 3 × 3 grid
  o.resolution_y = 2;
  const StabilityMap map = stability_map(scene, o);
  REQUIRE(map.curve_fidelity.tolerance_met);
  REQUIRE(map.curves.size() >= 10);
  const auto ux = [](double x) { return (x - 100) / 900; };
  const auto uy = [](double fbar) { return fbar / 10; };
  int ends_on_edge = 0, ends_at_curve = 0;
  for (std::size_t c = 0; c < map.curves.size(); ++c) {
    const BoundaryCurve& curve = map.curves[c];
    REQUIRE(curve.x.size() >= 2);
    for (const bool at_start : {true, false}) {
      const std::size_t e = at_start ? 0 : curve.x.size() - 1, before = at_start ? 1 : curve.x.size() - 2;
      const double px = ux(curve.x[e]), py = uy(curve.fbar[e]);
      // On the edge: the last trace line inside the window is at most one step (5 % of the θ
      // span for a steep curve, 0.1 in F̄) from it.
      const bool edge = py <= 0.0 || py >= 1.0 || px <= 0.05 || px >= 0.95;
      // At another curve: it crossed one in its last step, or came within the meeting distance
      // (5e-3 of the unit square), so the end is within that step's length (+ 5e-3) of it.
      const double step = std::hypot(px - ux(curve.x[before]), py - uy(curve.fbar[before]));
      double nearest = 1e300;
      for (std::size_t other = 0; other < map.curves.size(); ++other) {
        if (other == c) continue;
        std::vector<double> xs, ys;
        for (double x : map.curves[other].x) xs.push_back(ux(x));
        for (double f : map.curves[other].fbar) ys.push_back(uy(f));
        nearest = std::min(nearest, distance_to_polyline(px, py, xs, ys));
      }
      INFO("curve ρ = " << curve.multiplier << " (mode " << curve.mode << ", order " << curve.order << ") ends at θ = "
                        << curve.x[e] << ", F̄ = " << curve.fbar[e] << "; nearest other curve " << nearest
                        << ", last step " << step);
      CHECK((edge || nearest <= step + 5e-3));
      ends_on_edge += edge;
      ends_at_curve += !edge;
    }
  }
  CHECK(ends_on_edge >= 10);
  CHECK(ends_at_curve >= 2);
  // The curve through the change of name near θ = 307 rad/s: drawn across F̄ = 9 (both its
  // names), not from F̄ = 9 up only.
  bool across = false;
  for (const BoundaryCurve& c : map.curves) {
    bool below = false, above = false;
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      if (c.multiplier == -1 && std::abs(c.x[k] - 307) < 6) {
        below = below || c.fbar[k] < 8.95;
        above = above || c.fbar[k] > 9.05;
      }
    }
    across = across || (below && above);
  }
  CHECK(across);
  // Every point drawn, of whatever name, is a boundary of the whole Ritz model (no reduction) at
  // 12 harmonics within the error the map states for its curves, on 4 lines of F̄. And each
  // reference boundary is one by monodromy: across it a pair of multipliers leaves the unit
  // circle along the real axis at ±1, so the count of real multipliers of its sign (exactly real
  // in the real Schur form) differs by two between 0.05 rad/s below and above it (or 0.3 of the
  // way to the next boundary of its family, inside a thin tongue), where the monodromy can tell
  // (max|ρ| ≤ 10). The gap to ±1 at the boundary itself is no test here: the two multipliers meet
  // there in a Jordan block, so a boundary 1e-5 rad/s off (converged in the harmonics to 0.01
  // rad/s) already has its multiplier 3e-3 from +1.
  const double allowed = 900 * map.curve_fidelity.budget.total() + 1e-6 * 900;
  int checked = 0, sides_checked = 0;
  for (const double line : {2.0, 4.3, 6.0, 9.0}) {
    Scene at = scene;
    at.load.fmax_over_fcr = line;
    at.load.pulse_frequency_hz = 1;  // θ is the unknown
    const BladeModel model = assemble_model(at);
    const LoadSeries load = load_series(at);
    const PeriodicSystem whole = periodic_system(model, at, load);
    const double peak = -load.minimum();
    const std::vector<Boundary> reference = boundary_frequencies(whole, peak, 12);
    for (const BoundaryCurve& c : map.curves) {
      for (std::size_t k = 0; k < c.x.size(); ++k) {
        if (std::abs(c.fbar[k] - line) > 1e-9) continue;
        const Boundary* nearest = nullptr;
        for (const Boundary& b : reference) {
          if (b.multiplier == c.multiplier &&
              (!nearest || std::abs(b.theta_rad_s - c.x[k]) < std::abs(nearest->theta_rad_s - c.x[k]))) {
            nearest = &b;
          }
        }
        REQUIRE(nearest != nullptr);
        INFO("ρ = " << c.multiplier << " at θ = " << c.x[k] << ", F̄ = " << line << "; whole model's nearest "
                    << nearest->theta_rad_s);
        CHECK(std::abs(nearest->theta_rad_s - c.x[k]) <= allowed);
        ++checked;
        // The step to each side: within the region, whose other edge may be a hair away (thin tongues).
        double h = 0.05;
        for (const Boundary& b : reference) {
          if (&b != nearest && b.multiplier == c.multiplier) h = std::min(h, 0.3 * std::abs(b.theta_rad_s - nearest->theta_rad_s));
        }
        int real[2];
        bool tells = true;
        for (int side = 0; side < 2; ++side) {
          const Eigen::VectorXcd rho =
              multipliers_at(scene, scene.operation.speed_rad_s, nearest->theta_rad_s + (side ? h : -h), line);
          tells = tells && rho.cwiseAbs().maxCoeff() <= 10;
          real[side] = static_cast<int>((rho.array().imag() == 0 && rho.array().real() * c.multiplier > 0).count());
        }
        if (!tells) continue;
        INFO("real multipliers of its sign below and above: " << real[0] << ", " << real[1]);
        CHECK(std::abs(real[0] - real[1]) == 2);
        ++sides_checked;
      }
    }
  }
  CHECK(checked >= 40);
  CHECK(sides_checked >= 20);
}

TEST_CASE("map: a curve model the work limit cannot raise is drawn at its level with its estimate, marked",
          "[map][parallel][long_under_sanitizers]") {
  // --tolerance 1e-9 asks for more harmonics or vectors than the first level's; a budget of one flop
  // allows no further level. The curves stay at --approximation's k, drawn, with an estimate above
  // the tolerance and work_limited set (the table and JSON say why the tolerance is not met).
  const Scene scene = paper_scene({"model.terms=8"});
  MapOptions o = theta_plane(linspace(100, 1000, 3), linspace(0, 10, 3), linspace(0, 10, 11));
  o.resolution_x = 2;
  o.resolution_y = 2;
  o.tolerance = 1e-9;
  o.work_flops = 1;
  const StabilityMap limited = stability_map(scene, o);
  CHECK(limited.curve_fidelity.work_limited);
  CHECK_FALSE(limited.curve_fidelity.tolerance_met);
  CHECK(limited.curve_fidelity.approximation == o.approximation);
  CHECK(limited.curve_fidelity.budget.total() > o.tolerance);
  CHECK(limited.curves.size() >= 4);
}

TEST_CASE("map: a shading point whose ladder outgrows its work is undecided, and the others stand", "[map][mathieu][parallel]") {
  // Mathieu's equation along θ at F̄ = 0.6: the longer the period 2π/θ, the more Magnus steps a point
  // needs. With 1.5e5 flops for the map (1.5e5 / 20 a point; the undamped system steps half its
  // period, monodromy_step_work) the two lowest θ cannot converge; they are listed as undecided
  // (NaN), and the other three keep the values of the unlimited map.
  const Scene scene = paper_scene({"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false",
                                   "model.basis=sine", "operation.speed_rad_s=300"});
  MapOptions o;
  o.plane = MapPlane::theta_fmax;
  o.grid_x = linspace(20, 400, 5);
  o.grid_fbar = {0.6};
  o.trace = linspace(0, 1, 5);
  o.approximation = 8;
  o.tolerance = 1e-8;
  const StabilityMap whole = stability_map(scene, o);
  REQUIRE(whole.undecided.empty());
  o.work_flops = 1.5e5;
  const StabilityMap limited = stability_map(scene, o);
  REQUIRE(limited.undecided.size() == 2);
  CHECK(limited.undecided[0].x == 20);
  CHECK(limited.undecided[1].x == 115);
  CHECK_THAT(limited.undecided_reason, Catch::Contains("all that the work limit affords"));
  for (int i = 0; i < 5; ++i) {
    if (i < 2) {
      CHECK(std::isnan(limited.max_abs_multiplier(0, i)));
    } else {
      CHECK(limited.max_abs_multiplier(0, i) == whole.max_abs_multiplier(0, i));
    }
  }
  CHECK(limited.curves.size() == whole.curves.size());
}

TEST_CASE("speed-plane map: a contact of 0.3 revolution is no contact past the period at the window's edges",
          "[map]") {
  // The curves' reduction asks at the lowest speed (150 rad/s) for the modes up to the highest θ
  // (600 rad/s): 0.3 of a revolution there (12.6 ms) outlasted that θ's period (10.5 ms) and the
  // map was refused, though at every speed 0.3 of a revolution fits in one. The frequencies need no
  // load: the count is that of a short contact.
  const Scene slow = paper_scene({"operation.speed_rad_s=150", "load.contact_time_rev=0.3"});
  const Scene short_contact = paper_scene({"operation.speed_rad_s=150", "load.contact_time_rev=0.01"});
  const BladeModel model = assemble_model(slow);
  CHECK(tongue_vectors(model, slow, 600, 4) == tongue_vectors(model, short_contact, 600, 4));
}

TEST_CASE("a map point too slow for the Magnus ladder does not sink the map: its check is skipped, the rest stand",
          "[map][parallel]") {
  // At Ω = 1 rad/s the pulse period is 6.28 s: the reduction check's richer model (4 vectors per
  // load level) needs more than 131072 Magnus steps there; every other point, from 21 rad/s, runs.
  const Scene scene = paper_scene({});
  const StabilityMap map = stability_map(scene, speed_plane(linspace(1, 101, 6), linspace(0, 2, 5), linspace(1, 101, 11), 6, 5));
  CHECK(map.samples.size() >= 30);
  CHECK(map.shading_fidelity.checked.size() < 12);  // the Ω = 1 check point left out
  CHECK_FALSE(map.shading_fidelity.checked.empty());
  for (const ShadingCheck& c : map.shading_fidelity.checked) CHECK(c.x > 1);
}

TEST_CASE("the shading's basis part covers, on its check points, the distance to a much richer Legendre model",
          "[map][slow][parallel]") {
  // 8 terms under the true train near F̄ = 5, 100–140 rad/s: its narrow tongues sit elsewhere than the
  // converged model's (1.052 at 136 rad/s, where 16 and 24 terms give 1; the method part alone is
  // 3.5e-6). The reference: 16 terms, which agree with 24 at these points.
  const Scene scene = paper_scene({"model.terms=8", "load.approximation=exact"});
  const StabilityMap map =
      stability_map(scene, speed_plane(linspace(100, 140, 21), linspace(4.99, 5.01, 2), linspace(100, 140, 5), 20, 1));
  const ShadingFidelity& f = map.shading_fidelity;
  REQUIRE(f.basis_checked.size() >= 10);
  Scene rich = scene;
  rich.model.terms = 16;
  const BladeModel model = assemble_model(rich);
  double largest = 0;
  for (const ShadingCheck& c : f.basis_checked) {
    Scene at = rich;
    at.operation.speed_rad_s = c.x;
    at.load.fmax_over_fcr = c.fbar;
    const PeriodicSystem whole = periodic_system(model, at, load_series(at), {ReductionKind::none, 0, 0});
    const double reference =
        pulse_train_multipliers(whole, periodic_pulse(pulse_train(at)), {FloquetMethod::monodromy, 0, 1e-8}).max_abs_multiplier;
    const auto sample = std::find_if(map.samples.begin(), map.samples.end(),
                                     [&](const MapSample& s) { return s.x == c.x && s.fbar == c.fbar; });
    REQUIRE(sample != map.samples.end());
    const double difference = std::abs(sample->max_abs_multiplier - reference) / std::max(1.0, reference);
    CAPTURE(c.x, c.fbar, sample->max_abs_multiplier, reference, f.basis_error);
    CHECK(difference <= f.basis_error + map.max_error_estimate);
    largest = std::max(largest, difference);
  }
  CHECK(largest > 1e-3);  // not vacuous: the 8-term model is off at some check point
}
