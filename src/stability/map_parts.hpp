#pragma once
// The parts of a stability map (stability_map.hpp), in the order stability_map() runs them:
//   map_curves.cpp   the boundary curves: their model chosen by the curves' check, every trace
//                    line solved and its points joined into curves (Tracer);
//   map_folds.cpp    the curves closed through their turning points and cut to their drawn parts;
//   map_shading.cpp  the shading: its reduction checked on the grid, max|ρ| on the lattice refined
//                    like a quadtree, and the combination resonances named in it.
#include <algorithm>
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/stability/boundaries.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/stability/stability_map.hpp"

namespace bladestab {

// A boundary curve as traced, with each point's mode and order (the dominant mode and harmonic of
// its eigenvector). At high loads the modes mix and the name changes along one continuous curve
// (measured on the paper blade at Ω = 300 rad/s: the −1 pair of mode 2, order 7 at θ ≈ 307 rad/s,
// F̄ = 8.9 is "mode 1, order 3" from F̄ = 9; the 2ω₁ boundary near θ = 500, F̄ = 5.5 becomes
// "mode 2, order 5"), so a curve is followed through its names, not cut where they change.
struct TracedCurve {
  int multiplier = -1;
  std::vector<double> x, fbar;  // θ or Ω, F̄
  std::vector<int> mode, order;

  void push(double at_x, double at_fbar, int m, int n) {
    x.push_back(at_x), fbar.push_back(at_fbar), mode.push_back(m), order.push_back(n);
  }
  void reverse() {
    std::reverse(x.begin(), x.end()), std::reverse(fbar.begin(), fbar.end());
    std::reverse(mode.begin(), mode.end()), std::reverse(order.begin(), order.end());
  }
  void extend(const TracedCurve& c) {
    x.insert(x.end(), c.x.begin(), c.x.end()), fbar.insert(fbar.end(), c.fbar.begin(), c.fbar.end());
    mode.insert(mode.end(), c.mode.begin(), c.mode.end()), order.insert(order.end(), c.order.begin(), c.order.end());
  }
};

// One model of the boundary equations: a Ritz model, its reduction, K harmonics per multiplier sign.
struct CurveModel {
  const BladeModel* model = nullptr;
  ReductionSpec reduction;
  int approximation = 4;
};

// Where the boundary curves are traced: each trace value is a line of the plane (F̄ = const in the
// θ plane, Ω = const in the speed plane) on which the boundary equations give every boundary at
// once (docs/theory.md §4, (B.15)–(B.23)).
struct CurveWindow {
  bool theta_plane = true;
  double speed = 0, fcr = 0;
  int engine_order = 1;
  double x_lo = 0, x_hi = 0, y_hi = 0;
  int max_order = 4;  // orders n (θ ≈ 2ω/n) drawn

  // The boundaries on line `line` of `m`. In the θ plane the system carries the line's load; in
  // the speed plane it carries the window's top load F̄ = y_hi, so the reduced basis (the modes at
  // F = 0 and at the most compressive load) spans every load the line crosses.
  // `sign`: both multiplier signs (0) or the one of multiplier −1 or +1.
  std::vector<Boundary> on_line(const Scene& scene, const CurveModel& m, double line, int sign = 0) const {
    if (theta_plane) {
      if (line <= 0) return {};
      const Scene at = scene_at(scene, speed, two_pi, line);  // θ is the unknown; any value will do
      return boundary_frequencies(periodic_system(*m.model, at, load_series(at), m.reduction), line * fcr,
                                  m.approximation, sign);
    }
    return along_fbar(scene, m, line, engine_order * line, sign);
  }
  // Every boundary F_max at speed Ω and pulse frequency θ (the speed plane's lines).
  std::vector<Boundary> along_fbar(const Scene& scene, const CurveModel& m, double omega, double theta,
                                   int sign = 0) const {
    if (y_hi <= 0) return {};
    const Scene at = scene_at(scene, omega, theta, y_hi);
    return boundary_loads(periodic_system(*m.model, at, load_series(at), m.reduction), y_hi * fcr, theta,
                          m.approximation, sign);
  }
  // The boundary's coordinate along the line: θ, or F̄.
  double along(const Boundary& b) const { return theta_plane ? b.theta_rad_s : b.peak_force_n / fcr; }
  // In the window, of order ≤ 2·max_order, and of an order the K-th approximation resolves:
  // beyond the first, its highest harmonics (2K − 1 and 2K) are dropped as truncation artefacts
  // (boundaries.hpp), so orders up to 2K − 2. Curves are followed through all of them
  // (TracedCurve), and the checks against K + 2 compare all of them.
  bool traced(const Boundary& b, int approximation) const {
    const double v = along(b);
    const int resolved = approximation == 1 ? 2 : 2 * approximation - 2;
    return b.order <= std::min(resolved, 2 * max_order) && (theta_plane ? v >= x_lo && v <= x_hi : v <= y_hi);
  }
  // Whether a traced curve has a point of order ≤ max_order, where a drawn part starts (drawn_curves).
  bool drawn(const TracedCurve& c) const {
    return std::any_of(c.order.begin(), c.order.end(), [&](int n) { return n <= max_order; });
  }
  // The point in the plot's unit square: θ or Ω over the window, F̄ over its top.
  Eigen::Vector2d unit(double x, double fbar) const {
    return {(x - x_lo) / (x_hi > x_lo ? x_hi - x_lo : 1.0), fbar / (y_hi > 0 ? y_hi : 1.0)};
  }
  // The scene at point (x, F̄) of the plane: θ = x at the window's speed, or Ω = x with θ = kΩ.
  Scene point(const Scene& scene, double x, double fbar) const {
    return theta_plane ? scene_at(scene, speed, x, fbar) : scene_at(scene, x, engine_order * x, fbar);
  }
  // The measure of the curves' error; a window of one line has none, and its value serves.
  double span() const {
    const double s = theta_plane ? x_hi - x_lo : y_hi;
    return s > 0 ? s : std::max(1.0, std::abs(theta_plane ? x_hi : y_hi));
  }
};

// Reduced-basis vectors per load level for the map: enough to hold every tongue drawn
// (tongue_vectors, at the window's lowest speed). Each use checks its choice (check_curves,
// check_shading) and raises it where the check fails.
int window_vectors(const BladeModel& model, const Scene& scene, const CurveWindow& w);

// progress(done, total) over shading points and trace lines; the refinement's points are known one
// level at a time, so the total grows as they are. Called from the worker threads, one at a time.
class MapProgress {
public:
  MapProgress(std::function<void(int, int)> report, int total) : report_(std::move(report)), total_(total) {}
  void tick() {
    const int d = ++done_;
    if (report_) {
      std::lock_guard<std::mutex> hold(lock_);
      report_(d, total_);
    }
  }
  void add(int points) { total_ += points; }

private:
  std::function<void(int, int)> report_;
  std::atomic<int> total_, done_{0};
  std::mutex lock_;
};

// The map's boundary curves (map_curves.cpp): the model they are traced on, raised until the
// curves' check meets the tolerance (or the scene's basis is what misses it), and the drawn curves.
struct MapCurves {
  CurveModel model;
  CurveFidelity fidelity;
  std::vector<BoundaryCurve> drawn;
};
MapCurves map_curves(const Scene& scene, const BladeModel& model, const CurveWindow& window, const MapOptions& o,
                     bool cosine_load, MapProgress& progress);

// The traced curves closed through their turning points (map_folds.cpp): `along(sign, line)` gives
// the values along trace line `line` of the boundaries of multiplier `sign`.
std::vector<TracedCurve> close_folds(std::vector<TracedCurve> curves, const std::vector<double>& trace,
                                     bool theta_plane, double max_jump, int threads,
                                     const std::function<std::vector<double>(int sign, double line)>& along,
                                     const std::function<bool(const TracedCurve&)>& drawn);

// The parts of the traced curves that are drawn (map_folds.cpp).
std::vector<BoundaryCurve> drawn_curves(const std::vector<TracedCurve>& curves, const CurveWindow& w);

// The Floquet multipliers at one map point on the automatic reduction with `vectors` per load level
// (0: the whole Ritz model), to `tolerance`, the ladder within `max_flops` (map_shading.cpp).
FloquetResult point_multipliers(const BladeModel& model, const Scene& scene, int vectors, double tolerance,
                                double max_flops);

// The work each point's Floquet ladder may take: a quarter of the map's work spread over the
// shading grid's points (the refinement adds about as many again near the boundaries).
inline double point_work_flops(const MapOptions& o) {
  return o.work_flops / (4.0 * static_cast<double>(o.grid_x.size() * o.grid_fbar.size()));
}

// A shading point's (or the scene point's) multipliers, to the map's tolerance within its work
// (point_work_flops); none where its ladder did not converge within it, `undecided` then saying
// why (map_shading.cpp).
std::optional<FloquetResult> decided_multipliers(const BladeModel& model, const Scene& scene, int vectors,
                                                 const MapOptions& o, std::string& undecided);

// The shading's reduction: the window's vectors, doubled while the check on the grid fails
// (map_shading.cpp).
ShadingFidelity shading_fidelity(const BladeModel& model, const Scene& scene, const CurveWindow& window,
                                 const MapOptions& o, bool exact_pulse);

// The shading on the fine lattice with the combination regions (map_shading.cpp): fills the map's
// samples, cells, grid values, lattice size, error estimate and combinations.
void shade(StabilityMap& map, const BladeModel& model, const Scene& scene, const CurveWindow& window,
           const MapOptions& o, MapProgress& progress);

}  // namespace bladestab
