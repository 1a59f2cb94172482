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
#include "bladestab/damping.hpp"
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

PeriodicSystem system_for(const BladeModel& model, const Scene& scene) {
  const double speed = scene.operation.speed_rad_s;
  return periodic_system(model, speed, damping_matrix(model, scene.damping, speed), load_series(scene));
}

// Groups boundary points (parameter index, x, F̄) into curves by (multiplier, mode, order) and
// rank within that group at each parameter value; a curve is cut where a parameter value lacks it.
struct Tracer {
  using Key = std::tuple<int, int, int, int>;
  std::map<Key, std::vector<std::tuple<int, double, double>>> points;

  void add(int index, std::vector<Boundary> found, double fcr, bool x_is_theta, double x_fixed, double fbar_fixed) {
    std::map<std::tuple<int, int, int>, int> rank;
    for (const Boundary& b : found) {
      const int r = rank[{b.multiplier, b.mode, b.order}]++;
      const double x = x_is_theta ? b.theta_rad_s : x_fixed;
      const double y = x_is_theta ? fbar_fixed : b.peak_force_n / fcr;
      points[{b.multiplier, b.mode, b.order, r}].emplace_back(index, x, y);
    }
  }

  std::vector<BoundaryCurve> curves() const {
    std::vector<BoundaryCurve> out;
    for (const auto& [key, list] : points) {
      int last = -2;
      for (const auto& [index, x, y] : list) {
        if (index != last + 1) out.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key), {}, {}});
        out.back().x.push_back(x);
        out.back().fbar.push_back(y);
        last = index;
      }
    }
    return out;
  }
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

  // Boundary curves.
  Tracer tracer;
  for (std::size_t i = 0; i < o.trace.size(); ++i) {
    if (theta_plane) {
      const double fbar = o.trace[i];
      if (fbar > 0) {
        const Scene at = scene_at(scene, speed, two_pi, fbar);  // θ is the unknown; any value will do
        tracer.add(static_cast<int>(i), boundary_frequencies(system_for(model, at), fbar * fcr, o.approximation), fcr,
                   true, 0, fbar);
      }
    } else {
      const double W = o.trace[i], theta = o.engine_order * W;
      const Scene at = scene_at(scene, W, theta, 1.0);
      tracer.add(static_cast<int>(i), boundary_loads(system_for(model, at), fcr, theta, o.approximation), fcr, false,
                 W, 0);
    }
    tick();
  }
  map.curves = tracer.curves();
  const double x_lo = o.grid_x.front(), x_hi = o.grid_x.back();
  const double y_hi = o.grid_fbar.back();
  for (BoundaryCurve& c : map.curves) {  // keep what lies in the plotted window
    BoundaryCurve kept{c.multiplier, c.mode, c.order, {}, {}};
    for (std::size_t k = 0; k < c.x.size(); ++k) {
      if (c.x[k] >= x_lo && c.x[k] <= x_hi && c.fbar[k] <= y_hi) kept.x.push_back(c.x[k]), kept.fbar.push_back(c.fbar[k]);
    }
    c = kept;
  }
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
          const FloquetResult r = floquet_multipliers(system_for(model, at), {FloquetMethod::automatic, 0, o.tolerance});
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
