#include "bladestab/stability/stability_map.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/mode_convergence.hpp"
#include "bladestab/blade/reduction.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "support/worker_threads.hpp"

namespace bladestab {
namespace {
// The most harmonics per family the curves are raised to.
constexpr int max_curve_approximation = 20;

// The scene at one map point: speed Ω, pulse frequency θ, load F̄.
Scene scene_at(Scene scene, double speed, double theta, double fbar) {
  scene.operation.speed_rad_s = speed;
  scene.load.pulse_frequency_hz = theta / two_pi;
  scene.load.fmax_over_fcr = fbar;
  return scene;
}

// The Floquet multipliers at one map point, on the automatic reduced model with the map's vectors
// (0: the whole Ritz model):
// the load's series by the automatic method, the true pulse train (load.approximation = "exact")
// by its piecewise monodromy — the free flight's exponential and the contact's Magnus steps
// (pulse_monodromy.hpp).
FloquetResult point_multipliers(const BladeModel& model, const Scene& scene, int vectors, double tolerance) {
  const LoadSeries load = load_series(scene);
  const ReductionSpec reduction = vectors > 0 ? ReductionSpec{ReductionKind::automatic, vectors, 0}
                                              : ReductionSpec{ReductionKind::none, 0, 0};
  const PeriodicSystem sys = periodic_system(model, scene, load, reduction);
  if (load.exact_pulse) {
    return pulse_train_multipliers(sys, pulse_train(scene), {FloquetMethod::automatic, 0, tolerance, false});
  }
  return floquet_multipliers(sys, {FloquetMethod::automatic, 0, tolerance, false});
}

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

// One model of the boundary equations: a Ritz model, its reduction, K harmonics per family.
struct CurveModel {
  const BladeModel* model = nullptr;
  ReductionSpec reduction;
  int approximation = 4;
};

// Where the boundary curves are traced: each trace value is a line of the plane (F̄ = const in the
// θ plane, Ω = const in the speed plane) on which the boundary equations give every boundary at
// once (SPEC §4, (B.15)–(B.23)).
struct CurveWindow {
  bool theta_plane = true;
  double speed = 0, fcr = 0;
  int engine_order = 1;
  double x_lo = 0, x_hi = 0, y_hi = 0;
  int max_order = 4;  // orders n (θ ≈ 2ω/n) drawn

  // The boundaries on line `line` of `m`. In the θ plane the system carries the line's load; in
  // the speed plane it carries the window's top load F̄ = y_hi, so the reduced basis (the modes at
  // F = 0 and at the most compressive load) spans every load the line crosses.
  // `family`: both (0) or the one of multiplier −1 or +1.
  std::vector<Boundary> on_line(const Scene& scene, const CurveModel& m, double line, int family = 0) const {
    if (theta_plane) {
      if (line <= 0) return {};
      const Scene at = scene_at(scene, speed, two_pi, line);  // θ is the unknown; any value will do
      return boundary_frequencies(periodic_system(*m.model, at, load_series(at), m.reduction), line * fcr,
                                  m.approximation, family);
    }
    return along_fbar(scene, m, line, engine_order * line, family);
  }
  // Every boundary F_max at speed Ω and pulse frequency θ (the speed plane's lines).
  std::vector<Boundary> along_fbar(const Scene& scene, const CurveModel& m, double omega, double theta,
                                   int family = 0) const {
    if (y_hi <= 0) return {};
    const Scene at = scene_at(scene, omega, theta, y_hi);
    return boundary_loads(periodic_system(*m.model, at, load_series(at), m.reduction), y_hi * fcr, theta,
                          m.approximation, family);
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
  // The measure of the curves' error; a window of one line has none, and its value serves.
  double span() const {
    const double s = theta_plane ? x_hi - x_lo : y_hi;
    return s > 0 ? s : std::max(1.0, std::abs(theta_plane ? x_hi : y_hi));
  }
};

// The largest distance along the line, over the window's span, from a boundary of `a` or `b`
// shown at the approximation to the nearest boundary of the same family (±1) in the other; one
// with none counts as the whole span. Nearest, not matched by mode and order: at high loads the
// dominant harmonic of a boundary's eigenvector, which names its mode and order, changes with the
// approximation (measured on the paper blade at Ω = 142 rad/s, F̄ ≈ 7.9: "mode 1, order 6" at
// K = 4 is "mode 2, order 8" at K = 6).
double curve_distance(const CurveWindow& w, int approximation, const std::vector<Boundary>& a,
                      const std::vector<Boundary>& b) {
  double worst = 0;
  for (const auto& [base, other] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    for (const Boundary& x : *base) {
      if (!w.traced(x, approximation)) continue;
      double nearest = w.span();
      for (const Boundary& y : *other) {
        if (y.multiplier == x.multiplier) nearest = std::min(nearest, std::abs(w.along(x) - w.along(y)));
      }
      worst = std::max(worst, nearest / w.span());
    }
  }
  return worst;
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
  for (int t = 0; t < worker_threads(threads); ++t) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

// Joins boundary points into curves by continuity: at each new parameter value, every curve
// still open takes the point of its family (±1) nearest to where it is heading (its last two
// points extrapolated, or its last point), within `max_jump` of its last point and, once it has
// two, within max(max_jump / 5, 2 |last step|) of the heading: a curve does not leap to another's
// point where its own ends (measured on the paper blade below θ = 160 rad/s, where the tongues of
// orders 5 to 8 crowd, jumps of 40 rad/s along a line of F̄). Points left over start new curves
// and curves left over end.
class Tracer {
public:
  explicit Tracer(double max_jump) : max_jump_(max_jump) {}

  // `value` is the coordinate that varies between curves (θ in the θ plane, F̄ in the speed plane).
  void add(int index, const std::vector<Boundary>& found, const std::vector<double>& value, double x_fixed,
           bool x_is_value) {
    std::vector<bool> used(found.size(), false);
    for (Open& open : open_) {
      if (open.index != index - 1) continue;
      const bool straight = !std::isnan(open.previous);
      const double heading = straight ? 2 * open.value - open.previous : open.value;
      const double turn = std::max(max_jump_ / 5, 2 * std::abs(open.value - open.previous));
      int best = -1;
      for (std::size_t k = 0; k < found.size(); ++k) {
        if (used[k] || found[k].multiplier != curves_[open.curve].multiplier) continue;
        if (std::abs(value[k] - open.value) > max_jump_ || (straight && std::abs(value[k] - heading) > turn)) continue;
        if (best < 0 || std::abs(value[k] - heading) < std::abs(value[best] - heading)) best = static_cast<int>(k);
      }
      if (best < 0) continue;
      used[best] = true;
      append(open.curve, found[best], value[best], x_fixed, x_is_value);
      open = {open.curve, index, value[best], open.value};
    }
    for (std::size_t k = 0; k < found.size(); ++k) {
      if (used[k]) continue;
      curves_.push_back({found[k].multiplier, {}, {}, {}, {}});
      append(static_cast<int>(curves_.size()) - 1, found[k], value[k], x_fixed, x_is_value);
      open_.push_back({static_cast<int>(curves_.size()) - 1, index, value[k], std::nan("")});
    }
  }

  const std::vector<TracedCurve>& curves() const { return curves_; }

private:
  struct Open {
    int curve, index;
    double value, previous;  // along the line, on the last line and the one before (NaN: none)
  };
  void append(int curve, const Boundary& b, double value, double fixed, bool x_is_value) {
    curves_[curve].push(x_is_value ? value : fixed, x_is_value ? fixed : value, b.mode, b.order);
  }
  double max_jump_;
  std::vector<Open> open_;
  std::vector<TracedCurve> curves_;
};

// Closes curves through their turning points. Where two curves of one family start (or end) on the
// same trace line with no boundary of that family between them there, a region's boundary may
// fold back between that line and the one before (after): the pair of boundaries coalesces at the
// turning point and vanishes beyond it. The fold's line is found by bisection on the trace
// parameter — the pair exists on one side only — to 2^−fold_bisections of the line spacing; the
// curves are joined through the pair there (two boundary points a hair apart) if it did coalesce (its gap shrank tenfold: near a fold
// it shrinks like the square root of the distance, 64× over the bisection), or if it was closer
// than the boundary equations resolve a pair (a thin tongue, drawn as one line). In the θ plane a
// pair on the lowest line above F̄ = 0 belongs to a region that opens on the axis, at its tip
// θ ≈ 2ω_m/n for mode m and order n: the boundary equations' pair at F̄ = tip_load times that
// line's, one point to the eye (not 2ω_m/n from the undamped, non-gyroscopic frequencies, which on
// the paper blade at 300 rad/s put 2ω₁ at 855.52 rad/s, where the pair meets at 854.93). Curves that leave
// the window, and pairs that belong to two regions, stay open. Only pairs with a curve that is
// `drawn` are closed: the others' bisections would be spent on curves never shown.
constexpr int fold_bisections = 12;
constexpr double tip_load = 1e-12;

struct CurveEnd {
  int curve;
  bool at_start;
};

std::vector<TracedCurve> close_folds(std::vector<TracedCurve> curves, const std::vector<double>& trace,
                                      bool theta_plane, double max_jump, int threads,
                                      const std::function<std::vector<double>(int multiplier, double line)>& along,
                                      const std::function<bool(const TracedCurve&)>& drawn) {
  // Points as (line value, value along the line): F̄ and θ in the θ plane, Ω and F̄ in the speed plane.
  const auto line_value = [&](const TracedCurve& c, std::size_t k) { return theta_plane ? c.fbar[k] : c.x[k]; };
  const auto value = [&](const TracedCurve& c, std::size_t k) { return theta_plane ? c.x[k] : c.fbar[k]; };
  const auto end_index = [](const TracedCurve& c, bool start) { return start ? std::size_t{0} : c.x.size() - 1; };
  const auto line_of = [&](const TracedCurve& c, bool start) {
    return static_cast<int>(std::find(trace.begin(), trace.end(), line_value(c, end_index(c, start))) - trace.begin());
  };
  // Whether a boundary of the family lies strictly between u and v on the line.
  const auto between = [&](int multiplier, double line, double u, double v) {
    const double lo = std::min(u, v), hi = std::max(u, v);
    for (const TracedCurve& c : curves) {
      if (c.multiplier != multiplier) continue;
      for (std::size_t k = 0; k < c.x.size(); ++k) {
        if (line_value(c, k) == line && value(c, k) > lo && value(c, k) < hi) return true;
      }
    }
    return false;
  };
  // Pairs of ends on one line, of one family, nearest each other with nothing between.
  std::vector<std::pair<CurveEnd, CurveEnd>> folds;
  std::vector<bool> taken(curves.size(), false);
  for (std::size_t a = 0; a < curves.size(); ++a) {
    for (const bool start : {true, false}) {
      if (taken[a] || curves[a].x.empty()) continue;
      const int line = line_of(curves[a], start), beyond = start ? line - 1 : line + 1;
      if (beyond < 0 || beyond >= static_cast<int>(trace.size())) continue;
      const double va = value(curves[a], end_index(curves[a], start));
      int best = -1;
      double best_gap = std::numeric_limits<double>::infinity();
      for (std::size_t b = 0; b < curves.size(); ++b) {
        if (b == a || taken[b] || curves[b].multiplier != curves[a].multiplier || curves[b].x.empty()) continue;
        if (line_of(curves[b], start) != line) continue;
        const double gap = std::abs(value(curves[b], end_index(curves[b], start)) - va);
        if (gap < best_gap) best_gap = gap, best = static_cast<int>(b);
      }
      if (best < 0 || between(curves[a].multiplier, trace[line], va, value(curves[best], end_index(curves[best], start))) ||
          !(drawn(curves[a]) || drawn(curves[best]))) {
        continue;
      }
      taken[a] = taken[best] = true;
      folds.push_back({{static_cast<int>(a), start}, {best, start}});
    }
  }
  // Each fold's turning point by bisection between the line the pair is on and the one beyond.
  // The points that join a fold's two curves, (line, value along it), boundary points all; unset
  // where the pair is not joined.
  using Join = std::vector<std::pair<double, double>>;
  std::vector<std::optional<Join>> joins(folds.size());
  parallel_for(folds.size(), threads, [&](std::size_t f) {
    const auto& [a, b] = folds[f];
    const int line = line_of(curves[a.curve], a.at_start);
    double inside = trace[line], outside = trace[a.at_start ? line - 1 : line + 1];
    double va = value(curves[a.curve], end_index(curves[a.curve], a.at_start));
    double vb = value(curves[b.curve], end_index(curves[b.curve], b.at_start));
    const double first_gap = std::abs(va - vb);
    const TracedCurve &ca = curves[a.curve], &cb = curves[b.curve];
    const std::size_t ea = end_index(ca, a.at_start), eb = end_index(cb, b.at_start);
    if (theta_plane && outside <= 0 && ca.mode[ea] == cb.mode[eb] && ca.order[ea] == cb.order[eb] && ca.order[ea] > 0) {
      const double reach = std::max(max_jump, first_gap), middle = 0.5 * (va + vb);
      double tip = std::numeric_limits<double>::quiet_NaN();
      for (double x : along(ca.multiplier, tip_load * inside)) {
        if (std::abs(x - middle) <= reach && (std::isnan(tip) || std::abs(x - middle) < std::abs(tip - middle))) tip = x;
      }
      if (std::isfinite(tip)) joins[f] = Join{{0.0, tip}};
      return;
    }
    if (first_gap <= 1e-3 * max_jump) {  // one line to the eye: joined where the pair ends
      joins[f] = Join{};
      return;
    }
    for (int step = 0; step < fold_bisections; ++step) {
      const double middle = 0.5 * (inside + outside);
      const std::vector<double> found = along(curves[a.curve].multiplier, middle);
      // Each of the pair's boundaries continued by the nearest one within a jump (or the pair's gap).
      const double reach = std::max(max_jump, std::abs(va - vb));
      const auto nearest = [&](double v) {
        double best = std::numeric_limits<double>::quiet_NaN();
        for (double x : found) {
          if (std::abs(x - v) <= reach && (std::isnan(best) || std::abs(x - v) < std::abs(best - v))) best = x;
        }
        return best;
      };
      const double na = nearest(va), nb = nearest(vb);
      if (std::isfinite(na) && std::isfinite(nb) && na != nb) {
        inside = middle, va = na, vb = nb;
      } else {
        outside = middle;
      }
    }
    if (std::abs(va - vb) <= 0.1 * first_gap) joins[f] = Join{{inside, va}, {inside, vb}};
  });
  // Joined: a reversed, the turning point, b (or the mirror for ends).
  std::vector<bool> merged(curves.size(), false);
  std::vector<TracedCurve> out;
  for (std::size_t f = 0; f < folds.size(); ++f) {
    if (!joins[f]) continue;
    const auto& [a, b] = folds[f];
    TracedCurve first = curves[a.curve], second = curves[b.curve];
    (a.at_start ? first : second).reverse();
    for (const auto& [line, along_line] : *joins[f]) {  // named as the point they continue
      first.push(theta_plane ? along_line : line, theta_plane ? line : along_line, first.mode.back(), first.order.back());
    }
    first.extend(second);
    out.push_back(std::move(first));
    merged[a.curve] = merged[b.curve] = true;
  }
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (!merged[c]) out.push_back(std::move(curves[c]));
  }
  return out;
}

// Whether segments pq and rs of the plane cross (touching counts).
bool segments_cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
  const auto side = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return (cross > 0) - (cross < 0);
  };
  return side(p, q, r) * side(p, q, s) <= 0 && side(r, s, p) * side(r, s, q) <= 0;
}

// Distance from point p to segment rs.
double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
  const Eigen::Vector2d d = s - r;
  const double t = d.squaredNorm() > 0 ? std::clamp((p - r).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (r + t * d)).norm();
}

// Within this distance in the plot's unit square a continued curve has met another: a hair on
// the chart, and a pair of boundaries closer than this is one line to the eye.
constexpr double meeting_distance = 5e-3;

// The parts of the traced curves that are drawn. A curve's cores are its runs of points of order
// ≤ max_order; from each end of a core it is continued along its own traced points, whatever their
// names, until it meets another curve (crosses any traced curve, or comes within meeting_distance
// of another's core), reaches its next core, or its traced points end (it leaves the plot, or
// passes into orders beyond those traced). Continued to its end instead, a thin high-order tongue
// would cross the whole plot (measured on the paper blade at Ω = 300 rad/s: the −1 pair of mode 2,
// order 7, "order 3" above F̄ = 9, would run down to θ = 426 rad/s on the axis). Each point drawn
// is a traced boundary point: the meeting point is the first beyond, not interpolated. A drawn
// part is named as at its lowest load, where a region opens on the F̄ = 0 axis at θ ≈ 2ω/n.
std::vector<BoundaryCurve> drawn_curves(const std::vector<TracedCurve>& curves, const CurveWindow& w) {
  std::vector<std::vector<Eigen::Vector2d>> unit(curves.size());
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t k = 0; k < curves[c].x.size(); ++k) unit[c].push_back(w.unit(curves[c].x[k], curves[c].fbar[k]));
  }
  const auto in_core = [&](std::size_t c, std::size_t k) { return curves[c].order[k] <= w.max_order; };
  // Whether the step from point k to point next of curve c meets another curve.
  const auto meets = [&](std::size_t c, std::size_t k, std::size_t next) {
    const Eigen::Vector2d &p = unit[c][k], &q = unit[c][next];
    for (std::size_t o = 0; o < curves.size(); ++o) {
      if (o == c) continue;
      for (std::size_t j = 0; j < unit[o].size(); ++j) {
        const bool segment = j + 1 < unit[o].size();
        if (segment && segments_cross(p, q, unit[o][j], unit[o][j + 1])) return true;
        if (!in_core(o, j)) continue;
        const bool core_segment = segment && in_core(o, j + 1);
        if (distance_to_segment(q, unit[o][j], unit[o][core_segment ? j + 1 : j]) <= meeting_distance) return true;
      }
    }
    return false;
  };
  std::vector<BoundaryCurve> out;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const TracedCurve& t = curves[c];
    const std::size_t n = t.x.size();
    // Each core continued both ways, as index ranges [first, last]; overlapping ones are one part.
    std::vector<std::pair<std::size_t, std::size_t>> parts;
    for (std::size_t k = 0; k < n; ++k) {
      if (!in_core(c, k) || (k > 0 && in_core(c, k - 1))) continue;
      std::size_t first = k, last = k;
      while (last + 1 < n && in_core(c, last + 1)) ++last;
      while (first > 0 && !in_core(c, first - 1) && !meets(c, first, first - 1)) --first;
      if (first > 0 && !in_core(c, first - 1)) --first;  // the point that meets
      while (last + 1 < n && !in_core(c, last + 1) && !meets(c, last, last + 1)) ++last;
      if (last + 1 < n && !in_core(c, last + 1)) ++last;
      if (!parts.empty() && first <= parts.back().second + 1) {
        parts.back().second = last;
      } else {
        parts.emplace_back(first, last);
      }
    }
    for (const auto& [first, last] : parts) {
      if (last == first) continue;
      const std::size_t name = std::min_element(t.fbar.begin() + first, t.fbar.begin() + last + 1) - t.fbar.begin();
      out.push_back({t.multiplier, t.mode[name], t.order[name],
                     std::vector<double>(t.x.begin() + first, t.x.begin() + last + 1),
                     std::vector<double>(t.fbar.begin() + first, t.fbar.begin() + last + 1)});
    }
  }
  return out;
}

// Reduced-basis vectors per load level for the map: enough to hold every tongue drawn
// (tongue_vectors, at the window's lowest speed). Each use checks its choice (check_curves,
// check_shading) and raises it where the check fails.
int window_vectors(const BladeModel& model, const Scene& scene, const CurveWindow& w) {
  const double slowest = w.theta_plane ? w.speed : w.x_lo;
  const double theta_max = w.theta_plane ? w.x_hi : w.engine_order * w.x_hi;
  return tongue_vectors(model, scene_at(scene, slowest, theta_max, 0), theta_max, w.max_order);
}

// Boundaries of a line, kept for the map's run: the check lines recur across the fidelity's
// iterations (the whole model at min(K, 4) harmonics, the costliest, when only K or the vectors
// change), and the chosen model's check lines are lines of the trace. Closing a fold asks for
// one family's boundaries on a line between two of the trace: half the eigen-solves.
class LineCache {
public:
  std::vector<Boundary> on_line(const CurveWindow& w, const Scene& scene, const CurveModel& m, double line,
                                int family = 0) {
    const Key key{m.model, static_cast<int>(m.reduction.kind), m.reduction.vectors, m.approximation, line, family};
    {
      std::lock_guard<std::mutex> hold(lock_);
      const auto it = cache_.find(key);
      if (it != cache_.end()) return it->second;
    }
    std::vector<Boundary> found = w.on_line(scene, m, line, family);
    std::lock_guard<std::mutex> hold(lock_);
    return cache_.emplace(key, std::move(found)).first->second;
  }

private:
  using Key = std::tuple<const BladeModel*, int, int, int, double, int>;
  std::mutex lock_;
  std::map<Key, std::vector<Boundary>> cache_;
};

// The curves' error on three lines of the trace (at 1/6, 1/2 and 5/6 of it), as distances
// over the window's span (curve_distance), each against a model that differs in one part only:
//   reduction  the whole Ritz model — the check that shares nothing with the reduction — at
//              min(K, 4) harmonics (its boundary equations grow like dofs·K; the reduction's error
//              hardly depends on K), and twice the change to twice the vectors at K
//   basis      the reduced model of the richer basis reference_terms(basis, N) (sine: times
//              basis_tail_factor)
//   method     K + 2 harmonics, twice the change (the tail of a convergence at least geometric
//              with ratio 1/2, as for `boundaries`)
//   load       0: curves are drawn for the cosine approximation (42) only, the scene's load
CurveFidelity check_curves(const Scene& scene, const CurveWindow& w, const CurveModel& m, const BladeModel& richer,
                           const MapOptions& o, LineCache& cache) {
  CurveFidelity f;
  f.reduction = m.reduction;
  f.approximation = m.approximation;
  const std::size_t n = o.trace.size();
  std::vector<std::size_t> lines{n / 6, n / 2, 5 * n / 6};
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  const bool reduced = m.reduction.kind == ReductionKind::automatic;
  const int whole_k = std::min(m.approximation, 4);
  // Pairs (model compared, the answer's model at the same K, factor, part).
  struct Variant {
    CurveModel other, same;
    double factor;
    double ErrorBudget::*part;
  };
  std::vector<Variant> variants{
      {{&richer, m.reduction, m.approximation}, m, basis_tail_factor(scene.model.basis), &ErrorBudget::basis},
      {{m.model, m.reduction, m.approximation + 2}, m, 2, &ErrorBudget::method}};
  if (reduced) {
    variants.push_back({{m.model, {ReductionKind::none, 0, 0}, whole_k}, {m.model, m.reduction, whole_k}, 1,
                        &ErrorBudget::reduction});
    variants.push_back({{m.model, {ReductionKind::automatic, 2 * m.reduction.vectors, 0}, m.approximation}, m, 2,
                        &ErrorBudget::reduction});
  }
  std::vector<double> distance(variants.size() * lines.size(), 0);
  parallel_for(distance.size(), o.threads, [&](std::size_t k) {
    const Variant& v = variants[k % variants.size()];
    const double line = o.trace[lines[k / variants.size()]];
    distance[k] = v.factor * curve_distance(w, v.same.approximation, cache.on_line(w, scene, v.same, line),
                                            cache.on_line(w, scene, v.other, line));
  });
  for (std::size_t k = 0; k < distance.size(); ++k) {
    double& part = f.budget.*(variants[k % variants.size()].part);
    part = std::max(part, distance[k]);
  }
  for (std::size_t line : lines) f.checked_at.push_back(o.trace[line]);
  f.tolerance_met = f.budget.total() <= o.tolerance;
  return f;
}

// The shading's reduction checked on up to 12 points of the grid, spread over it: max|ρ| with the
// map's vectors against twice as many (which reduce() keeps whole where they would span the Ritz
// model: the exact reference), each to a quarter of the tolerance; the part is twice the
// difference (Galerkin projections do not converge monotonically in max|ρ|, as in `stability`)
// plus both method errors, relative to max(1, max|ρ|).
ShadingFidelity check_shading(const BladeModel& model, const MapOptions& o, int vectors,
                              const std::function<Scene(double, double)>& scene_at_point) {
  ShadingFidelity f;
  f.reduction_vectors = vectors;
  const std::size_t nx = o.grid_x.size(), ny = o.grid_fbar.size(), count = nx * ny;
  std::vector<std::pair<double, double>> points;
  std::size_t previous = count;
  for (std::size_t k = 0; k < 12; ++k) {
    const std::size_t at = (2 * k + 1) * count / 24;  // the middles of 12 equal runs of the grid
    if (at != previous && o.grid_x[at % nx] > 0) points.emplace_back(o.grid_x[at % nx], o.grid_fbar[at / nx]);
    previous = at;
  }
  std::vector<double> part(points.size(), 0);
  parallel_for(points.size(), o.threads, [&](std::size_t k) {
    const Scene at = scene_at_point(points[k].first, points[k].second);
    const FloquetResult r = point_multipliers(model, at, vectors, o.tolerance / 4);
    const FloquetResult richer = point_multipliers(model, at, 2 * vectors, o.tolerance / 4);
    part[k] = (2 * std::abs(r.max_abs_multiplier - richer.max_abs_multiplier) + r.error_estimate + richer.error_estimate) /
              std::max(1.0, r.max_abs_multiplier);
  });
  for (std::size_t k = 0; k < points.size(); ++k) {
    f.checked.push_back({points[k].first, points[k].second, part[k]});
    f.reduction_error = std::max(f.reduction_error, part[k]);
  }
  f.tolerance_met = f.reduction_error <= o.tolerance;
  return f;
}

}  // namespace

StabilityMap stability_map(const Scene& scene, const MapOptions& o, const std::function<void(int, int)>& progress) {
  const BladeModel model = assemble_model(scene);
  const double fcr = model.blade.critical_load();
  const bool theta_plane = o.plane == MapPlane::theta_fmax;
  const double speed = scene.operation.speed_rad_s;
  if (!theta_plane && o.grid_x.front() <= 0) {
    throw InputError("map: the speed plane needs speeds > 0 (θ = kΩ must be a pulse frequency)");
  }
  const LoadSeries scene_load = load_series(scene);
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

  // Boundary curves, traced within the plotted window on a reduced model. Its fidelity is chosen
  // on a few lines (check_curves), raising what misses the tolerance; then every line is traced.
  const CurveWindow window{theta_plane,      speed,           fcr, o.engine_order, o.grid_x.front(), o.grid_x.back(),
                           o.grid_fbar.back(), o.max_order};
  CurveModel curve_model{&model, {ReductionKind::automatic, window_vectors(model, scene, window), 0},
                         o.approximation};
  ModelSpec richer_spec = scene.model;
  richer_spec.terms = reference_terms(richer_spec.basis, richer_spec.terms);
  const BladeModel richer = assemble_model(scene, richer_spec);
  LineCache cache;
  // A pulse's own series (not the cosine approximation) puts many harmonics into the balance, and
  // its boundaries need many more harmonics, not monotonically: on the paper blade with t_c = 0.3
  // rev, the +1 boundary at θ = 400 rad/s, F̄ = 1.93 is absent at k = 4 and 6 and appears by k = 12,
  // which a k-against-k + 2 check on a few lines cannot see. Its θ-plane lines are also not
  // eigenproblems in θ (the duty t_c/T changes with θ). Such maps are shaded, without curves.
  map.curve_fidelity.drawn = scene_load.cosine_approximation;
  while (map.curve_fidelity.drawn) {
    map.curve_fidelity = check_curves(scene, window, curve_model, richer, o, cache);
    const ErrorBudget& b = map.curve_fidelity.budget;
    if (map.curve_fidelity.tolerance_met) break;
    const bool reducible = curve_model.reduction.kind == ReductionKind::automatic;
    if (reducible && b.reduction >= std::max(b.method, b.basis)) {
      const int doubled = 2 * curve_model.reduction.vectors;
      curve_model.reduction = reduction_keeps_whole(doubled, model.layout.size())
                                  ? ReductionSpec{ReductionKind::none, 0, 0}
                                  : ReductionSpec{ReductionKind::automatic, doubled, 0};
    } else if (b.method >= b.basis && curve_model.approximation + 2 <= max_curve_approximation) {
      curve_model.approximation += 2;
    } else {
      break;  // the basis is the scene's (model.terms): reported, not raised
    }
  }
  std::vector<std::vector<Boundary>> found(o.trace.size());
  parallel_for(map.curve_fidelity.drawn ? o.trace.size() : 0, o.threads, [&](std::size_t i) {
    found[i] = cache.on_line(window, scene, curve_model, o.trace[i]);
    tick();
  });
  Tracer tracer(0.05 * window.span());
  for (std::size_t i = 0; i < o.trace.size(); ++i) {
    std::vector<Boundary> traced;
    std::vector<double> along;
    for (const Boundary& b : found[i]) {
      if (window.traced(b, curve_model.approximation)) traced.push_back(b), along.push_back(window.along(b));
    }
    tracer.add(static_cast<int>(i), traced, along, o.trace[i], theta_plane);
  }
  const std::vector<TracedCurve> closed = close_folds(
      tracer.curves(), o.trace, theta_plane, 0.05 * window.span(), o.threads,
      [&](int multiplier, double line) {
        std::vector<double> values;
        for (const Boundary& b : cache.on_line(window, scene, curve_model, line, multiplier)) {
          if (window.traced(b, curve_model.approximation)) values.push_back(window.along(b));
        }
        return values;
      },
      [&](const TracedCurve& c) { return window.drawn(c); });
  map.curves = drawn_curves(closed, window);

  // The shading's reduction: the window's vectors, doubled while the check on the grid fails.
  const auto scene_at_point = [&](double x, double fbar) {
    return theta_plane ? scene_at(scene, speed, x, fbar) : scene_at(scene, x, o.engine_order * x, fbar);
  };
  // Where the reduction would keep the whole Ritz model, the whole model is used (0 vectors), and
  // its reduction part is 0. So it is for the true pulse
  // train, as in `stability`: it is integrated only through the contacts, and its narrow tongues
  // hang on the pulse's high harmonics, which a few vectors miss (on the paper blade's speed plane,
  // 4 vectors per level against the 24-dof model's failed the check).
  for (int vectors = window_vectors(model, scene, window);; vectors *= 2) {
    if (scene_load.exact_pulse || reduction_keeps_whole(vectors, model.layout.size())) {
      map.shading_fidelity = ShadingFidelity{0, {}, 0.0, true};
      break;
    }
    map.shading_fidelity = check_shading(model, o, vectors, scene_at_point);
    if (map.shading_fidelity.tolerance_met) break;
  }

  // The scene's own point, where the window holds it: its max|ρ| on the shading's model and the
  // nearest drawn boundary along F̄ (the margin a designer reads off the map).
  const double scene_theta = scene_load.angular_frequency;
  const double scene_x = theta_plane ? scene_theta : speed;
  const bool scene_in_plane = theta_plane || std::abs(scene_theta - o.engine_order * speed) <= 1e-9 * scene_theta;
  const double scene_fbar = scene.load.fmax_over_fcr;
  if (scene_in_plane && scene_x >= window.x_lo && scene_x <= window.x_hi && scene_fbar >= o.grid_fbar.front() &&
      scene_fbar <= window.y_hi && scene_theta > 0) {
    MapPoint p;
    p.x = scene_x;
    p.fbar = scene_fbar;
    const FloquetResult r =
        point_multipliers(model, scene_at_point(scene_x, scene_fbar), map.shading_fidelity.reduction_vectors, o.tolerance);
    p.max_abs_multiplier = r.max_abs_multiplier;
    const std::vector<Boundary> along = map.curve_fidelity.drawn ? window.along_fbar(scene, curve_model, speed, scene_theta)
                                                                 : std::vector<Boundary>{};
    for (const Boundary& b : along) {
      const double f = b.peak_force_n / fcr;
      if (b.order > window.max_order || f > window.y_hi) continue;
      if (!p.nearest_boundary || std::abs(f - scene_fbar) < std::abs(p.nearest_boundary->fbar - scene_fbar)) {
        p.nearest_boundary = MapPoint::Nearest{f, b.multiplier, b.mode, b.order};
      }
    }
    map.scene_point = p;
  }

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
    if (grid.size() == 1) return grid.front();  // before the cell: it would be −1, and −1 << k undefined
    const int cell = std::min(i >> k, static_cast<int>(grid.size()) - 2), first = cell << k;
    return grid[cell] + (grid[cell + 1] - grid[cell]) * (i - first) / static_cast<double>(1 << k);
  };
  const auto lattice_x = [&](int i) { return on_lattice(o.grid_x, kx, i); };
  const auto lattice_y = [&](int j) { return on_lattice(o.grid_fbar, ky, j); };
  std::unordered_map<long long, double> value;  // by i · (cells_y + 1) + j
  const auto key = [&](int i, int j) { return static_cast<long long>(i) * (map.cells_y + 1) + j; };

  std::mutex error_lock;
  double max_error = 0;
  const double stable_below = 1 + o.tolerance;
  std::vector<NamedSample> named_samples;
  // max|ρ| at the lattice points `points`, shared among the threads; an unstable point whose
  // dominant multiplier is complex is named by the combination it lies in.
  const auto evaluate = [&](const std::vector<std::pair<int, int>>& points) {
    std::vector<double> result(points.size(), std::nan(""));
    std::vector<std::optional<Combination>> named(points.size());
    parallel_for(points.size(), o.threads, [&](std::size_t k) {
      const double x = lattice_x(points[k].first), fbar = lattice_y(points[k].second);
      if (x > 0) {
        const Scene at = scene_at_point(x, fbar);
        const FloquetResult r = point_multipliers(model, at, map.shading_fidelity.reduction_vectors, o.tolerance);
        result[k] = r.max_abs_multiplier;
        named[k] = combination_at(model, at, r, stable_below, window.max_order);
        std::lock_guard<std::mutex> lock(error_lock);
        max_error = std::max(max_error, r.error_estimate / std::max(1.0, r.max_abs_multiplier));
      }
      tick();
    });
    for (std::size_t k = 0; k < points.size(); ++k) {
      value[key(points[k].first, points[k].second)] = result[k];
      map.samples.push_back({lattice_x(points[k].first), lattice_y(points[k].second), result[k]});
      if (named[k]) named_samples.push_back({points[k].first, points[k].second, *named[k], map.samples.back()});
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
  map.combinations = combination_islands(named_samples, 1 << kx, 1 << ky);
  return map;
}

}  // namespace bladestab
