#include "bladestab/stability/stability_map.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "bladestab/base/input_error.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "stability/map_parts.hpp"

namespace bladestab {
namespace {

// The scene's own point, where the window holds it: its max|ρ| on the shading's model and the
// nearest drawn boundary along F̄ (the margin a designer reads off the map).
std::optional<MapPoint> scene_point(const Scene& scene, const BladeModel& model, const CurveWindow& window,
                                    const MapOptions& o, const StabilityMap& map, const MapCurves& curves,
                                    double scene_theta) {
  const double speed = scene.operation.speed_rad_s;
  const double scene_x = window.theta_plane ? scene_theta : speed;
  const bool scene_in_plane =
      window.theta_plane || std::abs(scene_theta - o.engine_order * speed) <= 1e-9 * scene_theta;
  const double scene_fbar = scene.load.fmax_over_fcr;
  if (!(scene_in_plane && scene_x >= window.x_lo && scene_x <= window.x_hi && scene_fbar >= o.grid_fbar.front() &&
        scene_fbar <= window.y_hi && scene_theta > 0)) {
    return std::nullopt;
  }
  MapPoint p;
  p.x = scene_x;
  p.fbar = scene_fbar;
  const std::optional<FloquetResult> r = decided_multipliers(model, window.point(scene, scene_x, scene_fbar),
                                                             map.shading_fidelity.reduction_vectors, o, p.undecided);
  p.max_abs_multiplier = r ? r->max_abs_multiplier : std::numeric_limits<double>::quiet_NaN();
  const std::vector<Boundary> along = map.curve_fidelity.drawn ? window.along_fbar(scene, curves.model, speed, scene_theta)
                                                               : std::vector<Boundary>{};
  for (const Boundary& b : along) {
    const double f = b.peak_force_n / window.fcr;
    if (b.order > window.max_order || f > window.y_hi) continue;
    if (!p.nearest_boundary || std::abs(f - scene_fbar) < std::abs(p.nearest_boundary->fbar - scene_fbar)) {
      p.nearest_boundary = MapPoint::Nearest{f, b.multiplier, b.mode, b.order};
    }
  }
  return p;
}

}  // namespace

StabilityMap stability_map(const Scene& scene, const MapOptions& o, const std::function<void(int, int)>& progress) {
  refuse_impulse_jump(scene);
  const BladeModel model = assemble_model(scene);
  const bool theta_plane = o.plane == MapPlane::theta_fmax;
  if (!theta_plane && o.grid_x.front() <= 0) {
    throw InputError("the speed plane's grid needs speeds > 0 (θ = kΩ must be a pulse frequency)");
  }
  const LoadSeries scene_load = load_series(scene);
  const int nx = static_cast<int>(o.grid_x.size()), ny = static_cast<int>(o.grid_fbar.size());
  MapProgress counted(progress, nx * ny + static_cast<int>(o.trace.size()));

  StabilityMap map;
  map.plane = o.plane;
  map.grid_x = o.grid_x;
  map.grid_fbar = o.grid_fbar;
  map.max_abs_multiplier = Eigen::MatrixXd::Constant(ny, nx, std::nan(""));
  const CurveWindow window{theta_plane,       scene.operation.speed_rad_s, model.blade.critical_load(),
                           o.engine_order,    o.grid_x.front(),            o.grid_x.back(),
                           o.grid_fbar.back(), o.max_order};
  // Boundary curves, traced within the plotted window on a reduced model. Its fidelity is chosen
  // on a few lines (check_curves), raising what misses the tolerance; then every line is traced.
  const MapCurves curves = map_curves(scene, model, window, o, scene_load.cosine_approximation, counted);
  map.curve_fidelity = curves.fidelity;
  map.curves = curves.drawn;
  map.shading_fidelity = shading_fidelity(model, scene, window, o, scene_load.exact_pulse);
  map.scene_point = scene_point(scene, model, window, o, map, curves, scene_load.angular_frequency);
  shade(map, model, scene, window, o, counted);
  return map;
}

}  // namespace bladestab
