#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "bladestab/modal/basis_error.hpp"
#include "bladestab/blade/reduction.hpp"
#include "stability/map_parts.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {
// The most harmonics per multiplier sign the curves are raised to.
constexpr int max_curve_approximation = 20;

// The largest distance along the line, over the window's span, from a boundary of `a` or `b`
// shown at the approximation to the nearest boundary of the same multiplier sign (±1) in the other; one
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

// Joins boundary points into curves by continuity: at each new parameter value, every curve
// still open takes the point of its multiplier sign (±1) nearest to where it is heading (its last two
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

// Boundaries of a line, kept for the map's run: the check lines recur across the fidelity's
// iterations (the whole model at min(K, 4) harmonics, the costliest, when only K or the vectors
// change), and the chosen model's check lines are lines of the trace. Closing a fold asks for
// one sign's boundaries on a line between two of the trace: half the eigen-solves.
class LineCache {
public:
  std::vector<Boundary> on_line(const CurveWindow& w, const Scene& scene, const CurveModel& m, double line,
                                int sign = 0) {
    const Key key{m.model, static_cast<int>(m.reduction.kind), m.reduction.vectors, m.approximation, line, sign};
    {
      std::lock_guard<std::mutex> hold(lock_);
      const auto it = cache_.find(key);
      if (it != cache_.end()) return it->second;
    }
    std::vector<Boundary> found = w.on_line(scene, m, line, sign);
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
//   basis      the reduced model of the richer basis reference_terms(basis, N), times
//              basis_tail_factor
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
      {{&richer, m.reduction, m.approximation}, m, basis_tail_factor(basis_convergence(scene.blade, scene.model.basis, scene.model.terms)), &ErrorBudget::basis},
      {{m.model, m.reduction, m.approximation + 2}, m, 2, &ErrorBudget::method}};
  if (reduced) {
    variants.push_back({{m.model, {ReductionKind::none, 0, 0}, whole_k}, {m.model, m.reduction, whole_k}, 1,
                        &ErrorBudget::reduction});
    variants.push_back({{m.model, {ReductionKind::automatic, 2 * m.reduction.vectors, 0}, m.approximation}, m, 2,
                        &ErrorBudget::reduction});
  }
  const std::vector<double> distance = run_indexed(variants.size() * lines.size(), o.threads, [&](std::size_t k) {
    const Variant& v = variants[k % variants.size()];
    const double line = o.trace[lines[k / variants.size()]];
    return v.factor * curve_distance(w, v.same.approximation, cache.on_line(w, scene, v.same, line),
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

// The dofs of the curves' model: the automatic reduction's 3 vectors per `vectors` (modes at two
// load levels and their gyroscopic corrections, reduction.hpp) at most.
int curve_dofs(const CurveModel& m) {
  const int all = static_cast<int>(m.model->layout.size());
  return m.reduction.kind == ReductionKind::automatic ? std::min(3 * m.reduction.vectors, all) : all;
}

// The models check_curves at m solves on each of its lines: m, and each variant and its pair.
std::vector<CurveModel> check_models(const CurveModel& m, const BladeModel& richer) {
  std::vector<CurveModel> models{m, {&richer, m.reduction, m.approximation}, {m.model, m.reduction, m.approximation + 2}};
  if (m.reduction.kind == ReductionKind::automatic) {
    const int whole_k = std::min(m.approximation, 4);
    models.push_back({m.model, {ReductionKind::none, 0, 0}, whole_k});
    models.push_back({m.model, m.reduction, whole_k});
    models.push_back({m.model, {ReductionKind::automatic, 2 * m.reduction.vectors, 0}, m.approximation});
  }
  return models;
}

// Flops of check_curves at m beyond the models of the checks before (`solved`, which the line
// cache keeps): boundary_level_flops at each model's dofs, in θ (the larger), on three lines. The
// whole model's check at 4 harmonics is solved once for every later level (the fan blade at 16
// terms stopped at 4 harmonics and a curve error of 0.4, counting it again, where 8 take 20 s).
double new_check_flops(const CurveModel& m, const BladeModel& richer, const std::vector<CurveModel>& solved) {
  const auto same = [](const CurveModel& a, const CurveModel& b) {
    return a.model == b.model && a.reduction.kind == b.reduction.kind && a.reduction.vectors == b.reduction.vectors &&
           a.approximation == b.approximation;
  };
  double flops = 0;
  std::vector<CurveModel> counted = solved;
  for (const CurveModel& x : check_models(m, richer)) {
    if (std::any_of(counted.begin(), counted.end(), [&](const CurveModel& y) { return same(x, y); })) continue;
    flops += 3 * boundary_level_flops(x.approximation, curve_dofs(x), true);
    counted.push_back(x);
  }
  return flops;
}

// The curves' model: the window's reduction at the map's harmonics, raised part by part (the
// reduction's vectors, then the harmonics) while the curves' check misses the tolerance. A pulse's
// own series (not the cosine approximation) puts many harmonics into the balance, and its
// boundaries need many more harmonics, not monotonically: on the paper blade with t_c = 0.3 rev,
// the +1 boundary at θ = 400 rad/s, F̄ = 1.93 is absent at k = 4 and 6 and appears by k = 12, which
// a k-against-k + 2 check on a few lines cannot see. Its θ-plane lines are also not eigenproblems
// in θ (the duty t_c/T changes with θ). Such maps are shaded, without curves (fidelity.drawn false).
MapCurves chosen_model(const Scene& scene, const BladeModel& model, const CurveWindow& window, const MapOptions& o,
                       bool cosine_load, LineCache& cache) {
  MapCurves c;
  c.model = CurveModel{&model, {ReductionKind::automatic, window_vectors(model, scene, window), 0}, o.approximation};
  ModelSpec richer_spec = scene.model;
  richer_spec.terms = reference_terms(richer_spec.basis, richer_spec.terms);
  const BladeModel richer = assemble_model(scene, richer_spec);
  c.fidelity.drawn = cosine_load;
  double spent = 0;
  std::vector<CurveModel> solved;
  while (c.fidelity.drawn) {
    c.fidelity = check_curves(scene, window, c.model, richer, o, cache);
    spent += new_check_flops(c.model, richer, solved);
    for (const CurveModel& m : check_models(c.model, richer)) solved.push_back(m);
    const ErrorBudget& b = c.fidelity.budget;
    if (c.fidelity.tolerance_met) break;
    CurveModel next = c.model;
    const bool reducible = c.model.reduction.kind == ReductionKind::automatic;
    if (reducible && b.reduction >= std::max(b.method, b.basis)) {
      next.reduction = automatic_or_whole(2 * c.model.reduction.vectors, model.layout.size());
    } else if (b.method >= b.basis && c.model.approximation + 2 <= max_curve_approximation) {
      next.approximation += 2;
    } else {
      break;  // the basis is the scene's (model.terms): reported, not raised
    }
    // The next level's check and the trace lines solved at it (traced_curves) within half the
    // work: the shading takes the rest.
    const double traces = static_cast<double>(o.trace.size()) *
                          boundary_level_flops(next.approximation, curve_dofs(next), true);
    if (spent + new_check_flops(next, richer, solved) + traces > o.work_flops / 2) {
      c.fidelity.work_limited = true;
      break;
    }
    c.model = next;
  }
  return c;
}

// Every trace line solved on the chosen model, and its boundaries joined into curves.
std::vector<TracedCurve> traced_curves(const Scene& scene, const CurveWindow& window, const MapCurves& c,
                                       const MapOptions& o, LineCache& cache, MapProgress& progress) {
  const std::vector<std::vector<Boundary>> found =
      run_indexed(c.fidelity.drawn ? o.trace.size() : 0, o.threads, [&](std::size_t i) {
        std::vector<Boundary> on_line = cache.on_line(window, scene, c.model, o.trace[i]);
        progress.tick();
        return on_line;
      });
  Tracer tracer(0.05 * window.span());
  for (std::size_t i = 0; i < found.size(); ++i) {
    std::vector<Boundary> traced;
    std::vector<double> along;
    for (const Boundary& b : found[i]) {
      if (window.traced(b, c.model.approximation)) traced.push_back(b), along.push_back(window.along(b));
    }
    tracer.add(static_cast<int>(i), traced, along, o.trace[i], window.theta_plane);
  }
  return tracer.curves();
}

}  // namespace

// Reduced-basis vectors per load level for the map: enough to hold every tongue drawn
// (tongue_vectors, at the window's lowest speed). Each use checks its choice (check_curves,
// check_shading) and raises it where the check fails.
int window_vectors(const BladeModel& model, const Scene& scene, const CurveWindow& w) {
  const double slowest = w.theta_plane ? w.speed : w.x_lo;
  const double theta_max = w.theta_plane ? w.x_hi : w.engine_order * w.x_hi;
  return tongue_vectors(model, scene_at(scene, slowest, theta_max, 0), theta_max, w.max_order);
}

MapCurves map_curves(const Scene& scene, const BladeModel& model, const CurveWindow& window, const MapOptions& o,
                     bool cosine_load, MapProgress& progress) {
  LineCache cache;
  MapCurves c = chosen_model(scene, model, window, o, cosine_load, cache);
  const std::vector<TracedCurve> closed = close_folds(
      traced_curves(scene, window, c, o, cache, progress), o.trace, window.theta_plane, 0.05 * window.span(),
      o.threads,
      [&](int sign, double line) {
        std::vector<double> values;
        for (const Boundary& b : cache.on_line(window, scene, c.model, line, sign)) {
          if (window.traced(b, c.model.approximation)) values.push_back(window.along(b));
        }
        return values;
      },
      [&](const TracedCurve& curve) { return window.drawn(curve); });
  c.drawn = drawn_curves(closed, window);
  return c;
}

}  // namespace bladestab
