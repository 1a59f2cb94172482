#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/blade/reduction.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "stability/map_parts.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

// The combination resonance an unstable point lies in, where its dominant multiplier is complex
// (away from ±1 by more than 0.05 rad): named from the Ritz model's lowest frequencies under the
// point's mean load (combination_resonance.hpp; the gyroscopic coupling left out of them).
std::optional<Combination> combination_at(const BladeModel& model, const Scene& at, const FloquetResult& r,
                                          double stable_below, int max_order) {
  if (!(r.max_abs_multiplier > stable_below)) return std::nullopt;
  const double phase = std::abs(std::arg(r.multipliers(0)));
  if (phase < 0.05 || phase > pi - 0.05) return std::nullopt;
  const LoadSeries load = load_series(at);
  const double mean = load.coefficients.at(0).real();  // F₀, kept for the exact pulse too
  const int count = std::min(8, static_cast<int>(model.M.rows()));
  // Buckled under the mean load: no frequencies to name.
  if (!(static_margin(model, at.operation.speed_rad_s, mean) > 0)) return std::nullopt;
  const UndampedModes modes = undamped_modes(model, at.operation.speed_rad_s, mean, count, false);
  return nearest_combination(modes.omega2.head(count).cwiseSqrt(), load.angular_frequency, r.multipliers(0), max_order);
}

// The map's Floquet options: the automatic method to `tolerance` without the independent check,
// its ladder within `max_flops`.
FloquetOptions with_work(double tolerance, double max_flops) {
  FloquetOptions o{FloquetMethod::automatic, 0, tolerance, false};
  o.max_flops = max_flops;
  return o;
}

// A shading sample named by its combination, at lattice point (i, j).
struct NamedSample {
  int i = 0, j = 0;
  Combination combination;
  MapSample sample;
};

// The combination regions of the shading: samples of one combination within one coarse grid cell
// (reach_i × reach_j lattice steps) of each other form an island, reported at its sample of
// largest max|ρ|. Islands of fewer than 3 samples are left out: a refined island's edge alone
// holds more, and a stray point's name is not confirmed by any neighbour.
std::vector<CombinationRegion> combination_islands(const std::vector<NamedSample>& named, int reach_i, int reach_j) {
  std::vector<std::size_t> parent(named.size());
  for (std::size_t a = 0; a < named.size(); ++a) parent[a] = a;
  const std::function<std::size_t(std::size_t)> root = [&](std::size_t a) {
    return parent[a] == a ? a : parent[a] = root(parent[a]);
  };
  const auto same = [](const Combination& a, const Combination& b) {
    return a.mode_i == b.mode_i && a.mode_j == b.mode_j && a.sum == b.sum && a.order == b.order;
  };
  for (std::size_t a = 0; a < named.size(); ++a) {
    for (std::size_t b = a + 1; b < named.size(); ++b) {
      if (same(named[a].combination, named[b].combination) && std::abs(named[a].i - named[b].i) <= reach_i &&
          std::abs(named[a].j - named[b].j) <= reach_j) {
        parent[root(a)] = root(b);
      }
    }
  }
  std::map<std::size_t, CombinationRegion> islands;
  for (std::size_t a = 0; a < named.size(); ++a) {
    CombinationRegion& r = islands[root(a)];
    const MapSample& p = named[a].sample;
    if (r.samples++ == 0 || p.max_abs_multiplier > r.max_abs_multiplier) {
      r.combination = named[a].combination;
      r.x = p.x, r.fbar = p.fbar, r.max_abs_multiplier = p.max_abs_multiplier;
    }
  }
  std::vector<CombinationRegion> out;
  for (const auto& [first, r] : islands) {
    if (r.samples >= 3) out.push_back(r);
  }
  std::sort(out.begin(), out.end(), [](const CombinationRegion& a, const CombinationRegion& b) {
    return std::tie(a.x, a.fbar) < std::tie(b.x, b.fbar);
  });
  return out;
}

namespace {

// Up to 12 points of the grid that check the shading, spread over it: the middles of 12 equal runs.
std::vector<std::pair<double, double>> check_points(const MapOptions& o) {
  const std::size_t nx = o.grid_x.size(), ny = o.grid_fbar.size(), count = nx * ny;
  std::vector<std::pair<double, double>> points;
  std::size_t previous = count;
  for (std::size_t k = 0; k < 12; ++k) {
    const std::size_t at = (2 * k + 1) * count / 24;
    if (at != previous && o.grid_x[at % nx] > 0) points.emplace_back(o.grid_x[at % nx], o.grid_fbar[at / nx]);
    previous = at;
  }
  return points;
}

}  // namespace

// The shading's reduction checked on up to 12 points of the grid, spread over it: max|ρ| with the
// map's vectors against twice as many (which reduce() keeps whole where they would span the Ritz
// model: the exact reference), each to a quarter of the tolerance; the part is twice the
// difference (Galerkin projections do not converge monotonically in max|ρ|, as in `stability`)
// plus both method errors, relative to max(1, max|ρ|).
ShadingFidelity check_shading(const BladeModel& model, const Scene& scene, const CurveWindow& window,
                              const MapOptions& o, int vectors) {
  ShadingFidelity f;
  f.reduction_vectors = vectors;
  const std::vector<std::pair<double, double>> points = check_points(o);
  // A point whose ladders do not converge within their work cannot check the reduction: +∞, so
  // the vectors are doubled toward the whole Ritz model, which needs no check. A point no model can
  // take (a period too long for the Magnus ladder) checks nothing.
  const std::vector<double> part = run_indexed(points.size(), o.threads, [&](std::size_t k) {
    const Scene at = window.point(scene, points[k].first, points[k].second);
    try {
      const FloquetResult r = point_multipliers(model, at, vectors, o.tolerance / 4, point_work_flops(o));
      const FloquetResult richer = point_multipliers(model, at, 2 * vectors, o.tolerance / 4, point_work_flops(o));
      return (2 * std::abs(r.max_abs_multiplier - richer.max_abs_multiplier) + r.error_estimate +
              richer.error_estimate) / std::max(1.0, r.max_abs_multiplier);
    } catch (const WorkLimitError&) {
      return std::numeric_limits<double>::infinity();
    } catch (const NumericalError&) {  // the point itself cannot be taken (its shading says why): no check
      return std::numeric_limits<double>::quiet_NaN();
    }
  });
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (std::isfinite(part[k])) f.checked.push_back({points[k].first, points[k].second, part[k]});
    f.reduction_error = std::max(f.reduction_error, part[k]);
  }
  f.tolerance_met = f.reduction_error <= o.tolerance;
  return f;
}

// A lattice point's max|ρ| (NaN where it has no periodic load or is undecided), the combination it
// is named by and its error relative to max(1, max|ρ|); `undecided`: why its ladder stopped.
struct PointValue {
  double max_abs_multiplier = std::numeric_limits<double>::quiet_NaN();
  std::optional<Combination> combination;
  double relative_error = 0;
  std::string undecided;
};

// The shading on the fine lattice: the grid's cells split 2^k times in each direction. Lattice
// point i lies in grid cell i >> k, linearly between its grid points. Every cell whose corners
// disagree about stability (NaN counts as its own verdict) or that holds a drawn boundary point
// is split in four until the cells reach the lattice; a single row or column has no cells, and its
// points are the shading.
class Refinement {
public:
  Refinement(StabilityMap& map, const BladeModel& model, const Scene& scene, const CurveWindow& window,
             const MapOptions& o, MapProgress& progress)
      : map_(map), model_(model), scene_(scene), window_(window), o_(o), progress_(progress),
        nx_(static_cast<int>(o.grid_x.size())), ny_(static_cast<int>(o.grid_fbar.size())), refine_(nx_ > 1 && ny_ > 1),
        kx_(refine_ ? levels(nx_ - 1, o.resolution_x) : 0), ky_(refine_ ? levels(ny_ - 1, o.resolution_y) : 0),
        stable_below_(1 + o.tolerance) {
    map_.cells_x = (nx_ - 1) << kx_;
    map_.cells_y = (ny_ - 1) << ky_;
  }

  void run() {
    std::vector<MapCell> cells;
    for (int j = 0; j + 1 < ny_; ++j) {
      for (int i = 0; i + 1 < nx_; ++i) cells.push_back({i << kx_, j << ky_, 1 << kx_, 1 << ky_, 0});
    }
    if (!refine_) {
      std::vector<std::pair<int, int>> points;
      for (int j = 0; j < ny_; ++j) {
        for (int i = 0; i < nx_; ++i) points.emplace_back(i, j);
      }
      evaluate(points);
    }
    progress_.add(-nx_ * ny_);  // counted at the start; from here the points are counted as they are known
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
          map_.cells.push_back(leaf(c));
        }
      }
      evaluate_new(split);
      cells.swap(split);
    }
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) map_.max_abs_multiplier(j, i) = value_[key(i << kx_, j << ky_)];
    }
    map_.max_error_estimate = max_error_;
    map_.combinations = combination_islands(named_, 1 << kx_, 1 << ky_);
  }

private:
  // The levels of splitting that give a coarse axis of `coarse_cells` at least `wanted` cells.
  static int levels(int coarse_cells, int wanted) {
    int k = 0;
    while (coarse_cells << k < wanted && k < 12) ++k;
    return k;
  }
  static double on_lattice(const std::vector<double>& grid, int k, int i) {
    if (grid.size() == 1) return grid.front();  // before the cell: it would be −1, and −1 << k undefined
    const int cell = std::min(i >> k, static_cast<int>(grid.size()) - 2), first = cell << k;
    return grid[cell] + (grid[cell + 1] - grid[cell]) * (i - first) / static_cast<double>(1 << k);
  }
  double lattice_x(int i) const { return on_lattice(o_.grid_x, kx_, i); }
  double lattice_y(int j) const { return on_lattice(o_.grid_fbar, ky_, j); }
  long long key(int i, int j) const { return static_cast<long long>(i) * (map_.cells_y + 1) + j; }
  // The corners of a cell, as lattice points.
  static std::array<std::pair<int, int>, 4> corners(const MapCell& c) {
    return {{{c.i, c.j}, {c.i + c.width, c.j}, {c.i, c.j + c.height}, {c.i + c.width, c.j + c.height}}};
  }

  // max|ρ| at the lattice points `points`, shared among the threads; an unstable point whose
  // dominant multiplier is complex is named by the combination it lies in.
  void evaluate(const std::vector<std::pair<int, int>>& points) {
    const std::vector<PointValue> values = run_indexed(points.size(), o_.threads, [&](std::size_t k) {
      PointValue v;
      const double x = lattice_x(points[k].first), fbar = lattice_y(points[k].second);
      if (x > 0) {
        const Scene at = window_.point(scene_, x, fbar);
        if (const auto r = decided_multipliers(model_, at, map_.shading_fidelity.reduction_vectors, o_, v.undecided)) {
          v.max_abs_multiplier = r->max_abs_multiplier;
          v.combination = combination_at(model_, at, *r, stable_below_, window_.max_order);
          v.relative_error = r->error_estimate / std::max(1.0, r->max_abs_multiplier);
        }
      }
      progress_.tick();
      return v;
    });
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto [i, j] = points[k];
      max_error_ = std::max(max_error_, values[k].relative_error);
      value_[key(i, j)] = values[k].max_abs_multiplier;
      map_.samples.push_back({lattice_x(i), lattice_y(j), values[k].max_abs_multiplier});
      if (!values[k].undecided.empty()) {
        map_.undecided.push_back(map_.samples.back());
        if (map_.undecided_reason.empty()) map_.undecided_reason = values[k].undecided;
      }
      if (values[k].combination) named_.push_back({i, j, *values[k].combination, map_.samples.back()});
    }
  }
  // The corners of `cells` not yet evaluated, evaluated.
  void evaluate_new(const std::vector<MapCell>& cells) {
    std::vector<std::pair<int, int>> points;
    std::unordered_map<long long, bool> queued;
    for (const MapCell& c : cells) {
      for (const auto& [i, j] : corners(c)) {
        if (!value_.count(key(i, j)) && !queued[key(i, j)]) queued[key(i, j)] = true, points.emplace_back(i, j);
      }
    }
    progress_.add(static_cast<int>(points.size()));
    evaluate(points);
  }
  // Whether a cell's corners disagree about stability (NaN counts as its own verdict).
  bool mixed(const MapCell& c) {
    const auto verdict = [&](double r) { return std::isnan(r) ? 2 : r > stable_below_ ? 1 : 0; };
    const auto points = corners(c);
    for (int k = 1; k < 4; ++k) {
      if (verdict(value_[key(points[k].first, points[k].second)]) != verdict(value_[key(points[0].first, points[0].second)])) {
        return true;
      }
    }
    return false;
  }
  bool holds_curve(const MapCell& c) const {
    const double a = lattice_x(c.i), b = lattice_x(c.i + c.width), lo = lattice_y(c.j), hi = lattice_y(c.j + c.height);
    for (const BoundaryCurve& curve : map_.curves) {
      for (std::size_t k = 0; k < curve.x.size(); ++k) {
        if (curve.x[k] >= a && curve.x[k] <= b && curve.fbar[k] >= lo && curve.fbar[k] <= hi) return true;
      }
    }
    return false;
  }
  // A cell kept whole: the largest max|ρ| of its corners, NaN if one has none.
  MapCell leaf(const MapCell& c) {
    MapCell out = c;
    out.max_abs_multiplier = -std::numeric_limits<double>::infinity();
    for (const auto& [i, j] : corners(c)) {
      const double v = value_[key(i, j)];
      out.max_abs_multiplier =
          std::isnan(v) || std::isnan(out.max_abs_multiplier) ? std::nan("") : std::max(out.max_abs_multiplier, v);
    }
    return out;
  }

  StabilityMap& map_;
  const BladeModel& model_;
  const Scene& scene_;
  const CurveWindow& window_;
  const MapOptions& o_;
  MapProgress& progress_;
  const int nx_, ny_;
  const bool refine_;
  const int kx_, ky_;
  const double stable_below_;
  std::unordered_map<long long, double> value_;  // by i · (cells_y + 1) + j
  double max_error_ = 0;
  std::vector<NamedSample> named_;
};

}  // namespace

// The Floquet multipliers at one map point, on the automatic reduced model with the map's vectors
// (0: the whole Ritz model):
// the load's series by the automatic method, the true pulse train (load.approximation = "exact")
// by its piecewise monodromy — the free flight's exponential and the contact's Magnus steps
// (pulse_monodromy.hpp).
FloquetResult point_multipliers(const BladeModel& model, const Scene& scene, int vectors, double tolerance,
                                double max_flops) {
  const LoadSeries load = load_series(scene);
  const ReductionSpec reduction = vectors > 0 ? ReductionSpec{ReductionKind::automatic, vectors, 0}
                                              : ReductionSpec{ReductionKind::none, 0, 0};
  const PeriodicSystem sys = periodic_system(model, scene, load, reduction);
  if (load.exact_pulse) {
    return pulse_train_multipliers(sys, periodic_pulse(pulse_train(scene)), with_work(tolerance, max_flops));
  }
  return floquet_multipliers(sys, with_work(tolerance, max_flops));
}

std::optional<FloquetResult> decided_multipliers(const BladeModel& model, const Scene& scene, int vectors,
                                                 const MapOptions& o, std::string& undecided) {
  // A point the analysis cannot take (its work share, or a period too long for the Magnus ladder,
  // such as Ω = 1 rad/s among points from 21 rad/s on) is undecided; the map's other points stand.
  try {
    return point_multipliers(model, scene, vectors, o.tolerance, point_work_flops(o));
  } catch (const NumericalError& e) {
    undecided = e.what();
    return std::nullopt;
  }
}

namespace {

// The shading's basis part on the check points (the map's vectors, or the whole Ritz model): max|ρ|
// against each richer model of `stability`'s budget — the richer basis times its tail factor, and
// for the sine basis the same terms in the Legendre basis, which shares none of its spurious
// tongues (stability_analysis.cpp) — plus both method errors, relative to max(1, max|ρ|). A point
// a model cannot take checks nothing.
void check_shading_basis(const BladeModel& model, const Scene& scene, const CurveWindow& window, const MapOptions& o,
                         ShadingFidelity& f) {
  std::vector<std::pair<BladeModel, double>> richer;  // each model and its factor
  ModelSpec spec = scene.model;
  spec.terms = reference_terms(spec.basis, spec.terms);
  richer.emplace_back(assemble_model(scene, spec), basis_tail_factor(basis_convergence(scene.blade, spec.basis, scene.model.terms)));
  if (scene.model.basis == BasisKind::sine) {
    spec = scene.model;
    spec.basis = BasisKind::legendre;
    richer.emplace_back(assemble_model(scene, spec), basis_tail_factor(BasisConvergence::exponential));
  }
  const std::vector<std::pair<double, double>> points = check_points(o);
  const std::vector<double> part = run_indexed(points.size(), o.threads, [&](std::size_t k) {
    const Scene at = window.point(scene, points[k].first, points[k].second);
    try {
      const FloquetResult r = point_multipliers(model, at, f.reduction_vectors, o.tolerance / 4, point_work_flops(o));
      double largest = 0;
      for (const auto& [other, factor] : richer) {
        const FloquetResult x = point_multipliers(other, at, f.reduction_vectors, o.tolerance / 4, point_work_flops(o));
        largest = std::max(largest, factor * std::abs(r.max_abs_multiplier - x.max_abs_multiplier) + r.error_estimate +
                                        x.error_estimate);
      }
      return largest / std::max(1.0, r.max_abs_multiplier);
    } catch (const NumericalError&) {
      return std::numeric_limits<double>::quiet_NaN();
    }
  });
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!std::isfinite(part[k])) continue;
    f.basis_checked.push_back({points[k].first, points[k].second, part[k]});
    f.basis_error = std::max(f.basis_error, part[k]);
  }
}

// The shading's reduction: the automatic reduction's vectors doubled until its check meets the tolerance.
ShadingFidelity reduced_shading(const BladeModel& model, const Scene& scene, const CurveWindow& window,
                                const MapOptions& o, bool exact_pulse) {
  // Where the reduction would keep the whole Ritz model, the whole model is used (0 vectors), and
  // its reduction part is 0. So it is for the true pulse train, as in `stability`: it is integrated
  // only through the contacts, and its narrow tongues hang on the pulse's high harmonics, which a
  // few vectors miss (on the paper blade's speed plane, 4 vectors per level against the 24-dof
  // model's failed the check).
  for (int vectors = window_vectors(model, scene, window);; vectors *= 2) {
    if (exact_pulse || reduction_keeps_whole(vectors, model.layout.size())) {
      ShadingFidelity whole;
      whole.tolerance_met = true;
      return whole;
    }
    ShadingFidelity f = check_shading(model, scene, window, o, vectors);
    if (f.tolerance_met) return f;
  }
}

}  // namespace

ShadingFidelity shading_fidelity(const BladeModel& model, const Scene& scene, const CurveWindow& window,
                                 const MapOptions& o, bool exact_pulse) {
  ShadingFidelity f = reduced_shading(model, scene, window, o, exact_pulse);
  check_shading_basis(model, scene, window, o, f);
  return f;
}

void shade(StabilityMap& map, const BladeModel& model, const Scene& scene, const CurveWindow& window,
           const MapOptions& o, MapProgress& progress) {
  Refinement(map, model, scene, window, o, progress).run();
}

}  // namespace bladestab
