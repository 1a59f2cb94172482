#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "stability/map_parts.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

// Closes curves through their turning points. Where two curves of one multiplier sign start (or end) on the
// same trace line with no boundary of that sign between them there, a region's boundary may
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
using Fold = std::pair<CurveEnd, CurveEnd>;
// The points that join a fold's two curves, (line, value along it), boundary points all.
using Join = std::vector<std::pair<double, double>>;

// The value of `values` nearest v within `reach` of it; NaN if none.
double nearest_within(const std::vector<double>& values, double v, double reach) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (double x : values) {
    if (std::abs(x - v) <= reach && (std::isnan(best) || std::abs(x - v) < std::abs(best - v))) best = x;
  }
  return best;
}

class FoldCloser {
public:
  FoldCloser(std::vector<TracedCurve> curves, const std::vector<double>& trace, bool theta_plane, double max_jump,
             const std::function<std::vector<double>(int sign, double line)>& along)
      : curves_(std::move(curves)), trace_(trace), theta_plane_(theta_plane), max_jump_(max_jump), along_(along) {}

  // Pairs of ends on one line, of one sign, nearest each other with nothing between.
  std::vector<Fold> folds(const std::function<bool(const TracedCurve&)>& drawn) const {
    std::vector<Fold> out;
    std::vector<bool> taken(curves_.size(), false);
    for (std::size_t a = 0; a < curves_.size(); ++a) {
      for (const bool start : {true, false}) {
        if (taken[a] || curves_[a].x.empty()) continue;
        const int line = line_of(curves_[a], start), beyond = start ? line - 1 : line + 1;
        if (beyond < 0 || beyond >= static_cast<int>(trace_.size())) continue;
        const double va = end_value(curves_[a], start);
        int best = -1;
        double best_gap = std::numeric_limits<double>::infinity();
        for (std::size_t b = 0; b < curves_.size(); ++b) {
          if (b == a || taken[b] || curves_[b].multiplier != curves_[a].multiplier || curves_[b].x.empty()) continue;
          if (line_of(curves_[b], start) != line) continue;
          const double gap = std::abs(end_value(curves_[b], start) - va);
          if (gap < best_gap) best_gap = gap, best = static_cast<int>(b);
        }
        if (best < 0 || between(curves_[a].multiplier, trace_[line], va, end_value(curves_[best], start)) ||
            !(drawn(curves_[a]) || drawn(curves_[best]))) {
          continue;
        }
        taken[a] = taken[best] = true;
        out.push_back({{static_cast<int>(a), start}, {best, start}});
      }
    }
    return out;
  }

  // A fold's turning point by bisection between the line the pair is on and the one beyond;
  // unset where the pair is not joined.
  std::optional<Join> join(const Fold& fold) const {
    const auto& [a, b] = fold;
    const int line = line_of(curves_[a.curve], a.at_start);
    double inside = trace_[line], outside = trace_[a.at_start ? line - 1 : line + 1];
    double va = end_value(curves_[a.curve], a.at_start), vb = end_value(curves_[b.curve], b.at_start);
    const double first_gap = std::abs(va - vb);
    const TracedCurve &ca = curves_[a.curve], &cb = curves_[b.curve];
    const std::size_t ea = end_index(ca, a.at_start), eb = end_index(cb, b.at_start);
    if (theta_plane_ && outside <= 0 && ca.mode[ea] == cb.mode[eb] && ca.order[ea] == cb.order[eb] && ca.order[ea] > 0) {
      return tip(ca.multiplier, inside, va, vb);
    }
    if (first_gap <= 1e-3 * max_jump_) return Join{};  // one line to the eye: joined where the pair ends
    for (int step = 0; step < fold_bisections; ++step) {
      const double middle = 0.5 * (inside + outside);
      const std::vector<double> found = along_(ca.multiplier, middle);
      // Each of the pair's boundaries continued by the nearest one within a jump (or the pair's gap).
      const double reach = std::max(max_jump_, std::abs(va - vb));
      const double na = nearest_within(found, va, reach), nb = nearest_within(found, vb, reach);
      if (std::isfinite(na) && std::isfinite(nb) && na != nb) {
        inside = middle, va = na, vb = nb;
      } else {
        outside = middle;
      }
    }
    if (std::abs(va - vb) <= 0.1 * first_gap) return Join{{inside, va}, {inside, vb}};
    return std::nullopt;
  }

  // The curves with each joined fold's pair made one: a reversed, the turning point, b (or the
  // mirror for ends); the others as they were.
  std::vector<TracedCurve> joined(const std::vector<Fold>& folds, const std::vector<std::optional<Join>>& joins) {
    std::vector<bool> merged(curves_.size(), false);
    std::vector<TracedCurve> out;
    for (std::size_t f = 0; f < folds.size(); ++f) {
      if (!joins[f]) continue;
      const auto& [a, b] = folds[f];
      TracedCurve first = curves_[a.curve], second = curves_[b.curve];
      (a.at_start ? first : second).reverse();
      for (const auto& [line, along_line] : *joins[f]) {  // named as the point they continue
        first.push(theta_plane_ ? along_line : line, theta_plane_ ? line : along_line, first.mode.back(),
                   first.order.back());
      }
      first.extend(second);
      out.push_back(std::move(first));
      merged[a.curve] = merged[b.curve] = true;
    }
    for (std::size_t c = 0; c < curves_.size(); ++c) {
      if (!merged[c]) out.push_back(std::move(curves_[c]));
    }
    return out;
  }

private:
  // Points as (line value, value along the line): F̄ and θ in the θ plane, Ω and F̄ in the speed plane.
  double line_value(const TracedCurve& c, std::size_t k) const { return theta_plane_ ? c.fbar[k] : c.x[k]; }
  double value(const TracedCurve& c, std::size_t k) const { return theta_plane_ ? c.x[k] : c.fbar[k]; }
  static std::size_t end_index(const TracedCurve& c, bool start) { return start ? std::size_t{0} : c.x.size() - 1; }
  double end_value(const TracedCurve& c, bool start) const { return value(c, end_index(c, start)); }
  int line_of(const TracedCurve& c, bool start) const {
    return static_cast<int>(std::find(trace_.begin(), trace_.end(), line_value(c, end_index(c, start))) - trace_.begin());
  }
  // Whether a boundary of the sign lies strictly between u and v on the line.
  bool between(int sign, double line, double u, double v) const {
    const double lo = std::min(u, v), hi = std::max(u, v);
    for (const TracedCurve& c : curves_) {
      if (c.multiplier != sign) continue;
      for (std::size_t k = 0; k < c.x.size(); ++k) {
        if (line_value(c, k) == line && value(c, k) > lo && value(c, k) < hi) return true;
      }
    }
    return false;
  }
  // The tip of a region that opens on the F̄ = 0 axis, from the pair (va, vb) on the lowest line.
  std::optional<Join> tip(int sign, double lowest_line, double va, double vb) const {
    const double reach = std::max(max_jump_, std::abs(va - vb)), middle = 0.5 * (va + vb);
    const double at = nearest_within(along_(sign, tip_load * lowest_line), middle, reach);
    if (std::isfinite(at)) return Join{{0.0, at}};
    return std::nullopt;
  }

  std::vector<TracedCurve> curves_;
  const std::vector<double>& trace_;
  bool theta_plane_;
  double max_jump_;
  const std::function<std::vector<double>(int sign, double line)>& along_;
};

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

}  // namespace

std::vector<TracedCurve> close_folds(std::vector<TracedCurve> curves, const std::vector<double>& trace,
                                     bool theta_plane, double max_jump, int threads,
                                     const std::function<std::vector<double>(int sign, double line)>& along,
                                     const std::function<bool(const TracedCurve&)>& drawn) {
  FoldCloser closer(std::move(curves), trace, theta_plane, max_jump, along);
  const std::vector<Fold> folds = closer.folds(drawn);
  const std::vector<std::optional<Join>> joins =
      run_indexed(folds.size(), threads, [&](std::size_t f) { return closer.join(folds[f]); });
  return closer.joined(folds, joins);
}

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

}  // namespace bladestab
