#include "bladestab/stability_map.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>
#include <unordered_map>

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

// task(k) for k = 0..count − 1 on `threads` threads; the first exception stops the others at
// their next task and is rethrown.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& task) {
  std::atomic<std::size_t> next{0};
  std::mutex failure_lock;
  std::exception_ptr failure;
  const auto worker = [&] {
    try {
      for (std::size_t k = next++; k < count; k = next++) task(k);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_lock);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
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
  // The refinement's points are known one level at a time: the total grows as they are.
  std::atomic<int> total{nx * ny + static_cast<int>(o.trace.size())};
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
  // The boundary equations of each parameter value in parallel, then joined in order.
  std::vector<std::vector<Boundary>> found(o.trace.size());
  std::vector<std::vector<double>> found_value(o.trace.size());
  parallel_for(o.trace.size(), o.threads, [&](std::size_t i) {
    if (theta_plane) {
      const double fbar = o.trace[i];
      if (fbar > 0) {
        const Scene at = scene_at(scene, speed, two_pi, fbar);  // θ is the unknown; any value will do
        for (const Boundary& b : boundary_frequencies(system_for(model, at, ReductionKind::none), fbar * fcr, o.approximation)) {
          if (b.theta_rad_s >= x_lo && b.theta_rad_s <= x_hi) found[i].push_back(b), found_value[i].push_back(b.theta_rad_s);
        }
      }
    } else {
      const double W = o.trace[i], theta = o.engine_order * W;
      const Scene at = scene_at(scene, W, theta, 1.0);
      for (const Boundary& b : boundary_loads(system_for(model, at, ReductionKind::none), fcr, theta, o.approximation)) {
        if (b.peak_force_n / fcr <= y_hi) found[i].push_back(b), found_value[i].push_back(b.peak_force_n / fcr);
      }
    }
    tick();
  });
  Tracer tracer(0.05 * (theta_plane ? x_hi - x_lo : y_hi));
  for (std::size_t i = 0; i < o.trace.size(); ++i) {
    tracer.add(static_cast<int>(i), found[i], found_value[i], o.trace[i], theta_plane);
  }
  map.curves = tracer.curves();
  map.curves.erase(std::remove_if(map.curves.begin(), map.curves.end(), [](const BoundaryCurve& c) { return c.x.size() < 2; }),
                   map.curves.end());

  // Shading on the fine lattice: the grid's cells split 2^k times in each direction.
  const auto levels = [](int coarse_cells, int wanted) {
    int k = 0;
    while (coarse_cells << k < wanted && k < 12) ++k;
    return k;
  };
  // A single row or column has no cells: its points are the shading.
  const bool refine = nx > 1 && ny > 1;
  const int kx = refine ? levels(nx - 1, o.resolution_x) : 0, ky = refine ? levels(ny - 1, o.resolution_y) : 0;
  map.cells_x = (nx - 1) << kx;
  map.cells_y = (ny - 1) << ky;
  // Lattice point i lies in grid cell i >> k, linearly between its grid points.
  const auto on_lattice = [](const std::vector<double>& grid, int k, int i) {
    const int cell = std::min(i >> k, static_cast<int>(grid.size()) - 2), first = cell << k;
    if (grid.size() == 1) return grid.front();
    return grid[cell] + (grid[cell + 1] - grid[cell]) * (i - first) / static_cast<double>(1 << k);
  };
  const auto lattice_x = [&](int i) { return on_lattice(o.grid_x, kx, i); };
  const auto lattice_y = [&](int j) { return on_lattice(o.grid_fbar, ky, j); };
  std::unordered_map<long long, double> value;  // by i · (cells_y + 1) + j
  const auto key = [&](int i, int j) { return static_cast<long long>(i) * (map.cells_y + 1) + j; };

  std::mutex error_lock;
  double max_error = 0;
  // max|ρ| at the lattice points `points`, shared among the threads.
  const auto evaluate = [&](const std::vector<std::pair<int, int>>& points) {
    std::vector<double> result(points.size(), std::nan(""));
    parallel_for(points.size(), o.threads, [&](std::size_t k) {
      const double x = lattice_x(points[k].first), fbar = lattice_y(points[k].second);
      if (x > 0) {
        const Scene at = theta_plane ? scene_at(scene, speed, x, fbar) : scene_at(scene, x, o.engine_order * x, fbar);
        const FloquetResult r = floquet_multipliers(system_for(model, at, ReductionKind::automatic),
                                                    {FloquetMethod::automatic, 0, o.tolerance, false});
        result[k] = r.max_abs_multiplier;
        std::lock_guard<std::mutex> lock(error_lock);
        max_error = std::max(max_error, r.error_estimate / std::max(1.0, r.max_abs_multiplier));
      }
      tick();
    });
    for (std::size_t k = 0; k < points.size(); ++k) {
      value[key(points[k].first, points[k].second)] = result[k];
      map.samples.push_back({lattice_x(points[k].first), lattice_y(points[k].second), result[k]});
    }
  };
  // Points not yet evaluated among the corners of `cells`.
  const auto missing_corners = [&](const std::vector<MapCell>& cells) {
    std::vector<std::pair<int, int>> points;
    std::unordered_map<long long, bool> queued;
    for (const MapCell& c : cells) {
      for (const auto& [i, j] : {std::pair{c.i, c.j}, {c.i + c.width, c.j}, {c.i, c.j + c.height},
                                 {c.i + c.width, c.j + c.height}}) {
        if (!value.count(key(i, j)) && !queued[key(i, j)]) queued[key(i, j)] = true, points.emplace_back(i, j);
      }
    }
    return points;
  };
  const double stable_below = 1 + o.tolerance;
  // Whether a cell's corners disagree about stability (NaN counts as its own verdict).
  const auto mixed = [&](const MapCell& c) {
    const double v[4] = {value[key(c.i, c.j)], value[key(c.i + c.width, c.j)], value[key(c.i, c.j + c.height)],
                         value[key(c.i + c.width, c.j + c.height)]};
    const auto verdict = [&](double r) { return std::isnan(r) ? 2 : r > stable_below ? 1 : 0; };
    for (int k = 1; k < 4; ++k) {
      if (verdict(v[k]) != verdict(v[0])) return true;
    }
    return false;
  };
  const auto holds_curve = [&](const MapCell& c) {
    const double a = lattice_x(c.i), b = lattice_x(c.i + c.width), lo = lattice_y(c.j), hi = lattice_y(c.j + c.height);
    for (const BoundaryCurve& curve : map.curves) {
      for (std::size_t k = 0; k < curve.x.size(); ++k) {
        if (curve.x[k] >= a && curve.x[k] <= b && curve.fbar[k] >= lo && curve.fbar[k] <= hi) return true;
      }
    }
    return false;
  };

  std::vector<MapCell> cells;
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) cells.push_back({i << kx, j << ky, 1 << kx, 1 << ky, 0});
  }
  if (!refine) {
    std::vector<std::pair<int, int>> points;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) points.emplace_back(i, j);
    }
    evaluate(points);
  }
  total -= nx * ny;
  const auto evaluate_new = [&](const std::vector<MapCell>& of) {
    const std::vector<std::pair<int, int>> points = missing_corners(of);
    total += static_cast<int>(points.size());
    evaluate(points);
  };
  evaluate_new(cells);
  while (!cells.empty()) {
    std::vector<MapCell> split;
    for (const MapCell& c : cells) {
      if ((c.width > 1 || c.height > 1) && (mixed(c) || holds_curve(c))) {
        const int w = std::max(1, c.width / 2), h = std::max(1, c.height / 2);
        for (int dj = 0; dj < c.height; dj += h) {
          for (int di = 0; di < c.width; di += w) split.push_back({c.i + di, c.j + dj, w, h, 0});
        }
      } else {
        MapCell leaf = c;
        leaf.max_abs_multiplier = -std::numeric_limits<double>::infinity();
        for (const double v : {value[key(c.i, c.j)], value[key(c.i + c.width, c.j)], value[key(c.i, c.j + c.height)],
                               value[key(c.i + c.width, c.j + c.height)]}) {
          leaf.max_abs_multiplier = std::isnan(v) || std::isnan(leaf.max_abs_multiplier) ? std::nan("")
                                                                                        : std::max(leaf.max_abs_multiplier, v);
        }
        map.cells.push_back(leaf);
      }
    }
    evaluate_new(split);
    cells.swap(split);
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) map.max_abs_multiplier(j, i) = value[key(i << kx, j << ky)];
  }
  map.max_error_estimate = max_error;
  return map;
}

}  // namespace bladestab
