#include "bladestab/stability_map.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>

#include "bladestab/blas_threads.hpp"
#include "bladestab/boundaries.hpp"
#include "bladestab/input_error.hpp"

namespace bladestab {
namespace {

constexpr double two_pi = 6.28318530717958647692;

// The scene at one map point: speed Ω, pulse frequency θ, load F̄.
Scene scene_at(Scene scene, double speed, double theta, double fbar) {
  scene.operation.speed_rad_s = speed;
  scene.load.pulse_frequency_hz = theta / two_pi;
  scene.load.fmax_over_fcr = fbar;
  return scene;
}

// The boundary equations are eigenproblems, not time integrations: the whole Ritz model, in a
// basis that does not depend on the load they solve for. The shading integrates the reduced one.
PeriodicSystem system_for(const BladeModel& model, const Scene& scene, ReductionKind reduction) {
  return periodic_system(model, scene, load_series(scene), {reduction, 0, 0});
}

// Joins boundary points into curves by continuity: at each new parameter value, every curve
// still open takes the nearest point of its family (±1) within `max_jump`; points left over
// start new curves and curves left over end. The curve's mode and order are its first point's.
class Tracer {
public:
  explicit Tracer(double max_jump) : max_jump_(max_jump) {}

  // `value` is the coordinate that varies between curves (θ in the θ plane, F̄ in the speed plane).
  void add(int index, const std::vector<Boundary>& found, const std::vector<double>& value, double x_fixed,
           bool x_is_value) {
    std::vector<bool> used(found.size(), false);
    for (Open& open : open_) {
      if (open.index != index - 1) continue;
      int best = -1;
      for (std::size_t k = 0; k < found.size(); ++k) {
        if (used[k] || found[k].multiplier != curves_[open.curve].multiplier) continue;
        const double jump = std::abs(value[k] - open.value);
        if (jump <= max_jump_ && (best < 0 || jump < std::abs(value[best] - open.value))) best = static_cast<int>(k);
      }
      if (best < 0) continue;
      used[best] = true;
      append(open.curve, value[best], x_fixed, x_is_value);
      open = {open.curve, index, value[best]};
    }
    for (std::size_t k = 0; k < found.size(); ++k) {
      if (used[k]) continue;
      curves_.push_back({found[k].multiplier, found[k].mode, found[k].order, {}, {}});
      append(static_cast<int>(curves_.size()) - 1, value[k], x_fixed, x_is_value);
      open_.push_back({static_cast<int>(curves_.size()) - 1, index, value[k]});
    }
  }

  const std::vector<BoundaryCurve>& curves() const { return curves_; }

private:
  struct Open {
    int curve, index;
    double value;
  };
  void append(int curve, double value, double fixed, bool x_is_value) {
    curves_[curve].x.push_back(x_is_value ? value : fixed);
    curves_[curve].fbar.push_back(x_is_value ? fixed : value);
  }
  double max_jump_;
  std::vector<Open> open_;
  std::vector<BoundaryCurve> curves_;
};

}  // namespace

StabilityMap stability_map(const Scene& scene, const MapOptions& o, const std::function<void(int, int)>& progress) {
  const BladeModel model = assemble_model(scene.blade, scene.model);
  const double fcr = model.blade.critical_load();
  const bool theta_plane = o.plane == MapPlane::theta_fmax;
  const double speed = scene.operation.speed_rad_s;
  if (!theta_plane && o.grid_x.front() <= 0) {
    throw InputError("--speeds: the speed plane needs speeds > 0 (θ = kΩ must be a pulse frequency)");
  }
  const int nx = static_cast<int>(o.grid_x.size()), ny = static_cast<int>(o.grid_fbar.size());
  const int total = nx * ny + static_cast<int>(o.trace.size());
  std::atomic<int> done{0};
  std::mutex report;
  const auto tick = [&] {
    const int d = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(report);
      progress(d, total);
    }
  };

  StabilityMap map;
  map.plane = o.plane;
  map.grid_x = o.grid_x;
  map.grid_fbar = o.grid_fbar;
  map.max_abs_multiplier = Eigen::MatrixXd::Constant(ny, nx, std::nan(""));

  // Boundary curves, traced within the plotted window.
  const double x_lo = o.grid_x.front(), x_hi = o.grid_x.back(), y_hi = o.grid_fbar.back();
  Tracer tracer(0.05 * (theta_plane ? x_hi - x_lo : y_hi));
  for (std::size_t i = 0; i < o.trace.size(); ++i) {
    std::vector<Boundary> found;
    std::vector<double> value;
    if (theta_plane) {
      const double fbar = o.trace[i];
      if (fbar > 0) {
        const Scene at = scene_at(scene, speed, two_pi, fbar);  // θ is the unknown; any value will do
        for (const Boundary& b : boundary_frequencies(system_for(model, at, ReductionKind::none), fbar * fcr, o.approximation)) {
          if (b.theta_rad_s >= x_lo && b.theta_rad_s <= x_hi) found.push_back(b), value.push_back(b.theta_rad_s);
        }
      }
      tracer.add(static_cast<int>(i), found, value, fbar, true);
    } else {
      const double W = o.trace[i], theta = o.engine_order * W;
      const Scene at = scene_at(scene, W, theta, 1.0);
      for (const Boundary& b : boundary_loads(system_for(model, at, ReductionKind::none), fcr, theta, o.approximation)) {
        if (b.peak_force_n / fcr <= y_hi) found.push_back(b), value.push_back(b.peak_force_n / fcr);
      }
      tracer.add(static_cast<int>(i), found, value, W, false);
    }
    tick();
  }
  map.curves = tracer.curves();
  map.curves.erase(std::remove_if(map.curves.begin(), map.curves.end(), [](const BoundaryCurve& c) { return c.x.size() < 2; }),
                   map.curves.end());

  // Shading, rows shared among threads.
  std::atomic<int> next_row{0};
  std::mutex error_lock;
  double max_error = 0;
  std::exception_ptr failure;
  const std::function<void()> rows = [&] {
    for (int j = next_row++; j < ny; j = next_row++) {
      for (int i = 0; i < nx; ++i) {
        const double x = o.grid_x[i], fbar = o.grid_fbar[j];
        const Scene at = theta_plane ? scene_at(scene, speed, x, fbar) : scene_at(scene, x, o.engine_order * x, fbar);
        if (x > 0) {
          const FloquetResult r = floquet_multipliers(system_for(model, at, ReductionKind::automatic),
                                                      {FloquetMethod::automatic, 0, o.tolerance, false});
          map.max_abs_multiplier(j, i) = r.max_abs_multiplier;
          std::lock_guard<std::mutex> lock(error_lock);
          max_error = std::max(max_error, r.error_estimate / std::max(1.0, r.max_abs_multiplier));
        }
        tick();
      }
    }
  };
  const auto worker = [&] {
    try {
      rows();
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_lock);
      if (!failure) failure = std::current_exception();
      next_row = ny;  // the other threads stop at their next row
    }
  };
  // OpenBLAS's own threads would fight the workers for the cores.
  const int blas_threads = openblas_get_num_threads();
  use_single_threaded_blas();
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, o.threads); ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  openblas_set_num_threads(blas_threads);
  if (failure) std::rethrow_exception(failure);
  map.max_error_estimate = max_error;
  return map;
}

}  // namespace bladestab
