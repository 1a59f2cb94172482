#include "bladestab/modal/campbell.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "bladestab/base/constants.hpp"
#include "bladestab/modal/mode_tracking.hpp"
#include "bladestab/modal/speed_sweep.hpp"
#include "modal/campbell_parts.hpp"
#include "support/scalar_search.hpp"

namespace bladestab {

int tracked_count(const BladeModel& model, const CampbellOptions& options) {
  return std::min(options.mode_count, model.layout.size());
}

// Modes solved per speed: a few more than tracked, so that modes entering from above can be followed.
int solve_count(const BladeModel& model, const CampbellOptions& options) {
  return tracking_candidates(tracked_count(model, options), model.layout.size());
}

// Index of the mode in `modes` most like `shape` (unit columns: MAC = |aᴴ b|²).
int most_like(const SpeedModes& modes, const Eigen::VectorXcd& shape, double* mac) {
  Eigen::Index best = 0;
  const double value = (modes.shapes.adjoint() * shape).cwiseAbs2().maxCoeff(&best);
  if (mac) *mac = value;
  return static_cast<int>(best);
}

namespace {

// Greedy assignment by largest MAC (unit columns: MAC = |aᴴ b|²): result[i] = index in
// `candidates` for tracked shape i.
std::vector<int> match_by_shape(const Eigen::MatrixXcd& tracked, const Eigen::MatrixXcd& candidates,
                                std::vector<double>& mac_out) {
  return assign_by_correlation((tracked.adjoint() * candidates).cwiseAbs2(), mac_out);
}

// The sweep's frequency [Hz] at `speed` of the mode most like `shape`: the curve between the speeds.
double frequency_of(SpeedSweep& sweep, const Eigen::VectorXcd& shape, double speed) {
  const SpeedModes modes = sweep.at(speed, false);
  return modes.frequency_hz[most_like(modes, shape)];
}

}  // namespace

// The sweep's modes at `speed` with their bounds against the whole model; ReducedSweepUnavailable
// where a reduced sweep cannot bound some of them (the dense sweep then serves the estimate).
SpeedModes certified_modes(SpeedSweep& sweep, double speed) {
  SpeedModes modes = sweep.at(speed, true);
  require_certified(modes);
  return modes;
}

Tracked track(SpeedSweep& sweep, const BladeModel& model, const CampbellOptions& options, CampbellDiagram& d,
              const std::function<void(int, int)>& progress) {
  const auto& speeds = options.speeds_rad_s;
  const int ns = static_cast<int>(speeds.size()), nt = tracked_count(model, options);
  Tracked t{sweep.solve(speeds, progress), std::vector<std::vector<int>>(nt, std::vector<int>(ns))};
  d = CampbellDiagram{};
  d.speeds_rad_s = speeds;
  d.engine_orders = options.engine_orders;
  d.curves.resize(nt);
  d.solver = sweep.solver();
  d.reduced = sweep.reduced();
  d.basis_vectors = sweep.vectors();
  d.sample_speeds_rad_s = sweep.sample_speeds();
  for (CampbellCurve& c : d.curves) {
    c.frequency_hz.reserve(ns);
    c.families.reserve(ns);
    c.damping_ratio.reserve(ns);
    c.correlation.reserve(ns);
    c.reduction_bound.reserve(ns);
    c.rounding.reserve(ns);
  }
  Eigen::MatrixXcd previous;
  std::vector<int> pick(nt);
  std::vector<double> mac(nt, 1.0);
  for (int s = 0; s < ns; ++s) {
    const SpeedModes& here = t.modes[s];
    if (s == 0) {
      for (int i = 0; i < nt; ++i) {
        pick[i] = i;
        d.curves[i].mode = i + 1;
        d.curves[i].family = here.family[i];
      }
    } else {
      previous.resize(here.shapes.rows(), nt);
      for (int i = 0; i < nt; ++i) previous.col(i) = t.modes[s - 1].shapes.col(t.pick[i][s - 1]);
      pick = match_by_shape(previous, here.shapes, mac);
    }
    for (int i = 0; i < nt; ++i) {
      CampbellCurve& c = d.curves[i];
      t.pick[i][s] = pick[i];
      c.frequency_hz.push_back(here.frequency_hz[pick[i]]);
      c.families.push_back(here.family[pick[i]]);
      c.damping_ratio.push_back(here.damping_ratio[pick[i]]);
      c.correlation.push_back(mac[i]);
      c.reduction_bound.push_back(here.bound[pick[i]]);
      c.rounding.push_back(here.rounding[pick[i]]);
    }
  }
  return t;
}

// Engine-order crossings, refined on the sweep's modes and then confirmed and corrected on the
// whole model. `shapes` receives, per crossing, the shape it followed.
void find_crossings(SpeedSweep& sweep, const Tracked& t, CampbellDiagram& d, std::vector<Eigen::VectorXcd>& shapes) {
  const auto& speeds = d.speeds_rad_s;
  const int ns = static_cast<int>(speeds.size());
  std::vector<std::pair<EngineOrderCrossing, Eigen::VectorXcd>> found;
  for (int k : d.engine_orders) {
    const double line = k / two_pi;  // Hz per rad/s
    for (std::size_t i = 0; i < d.curves.size(); ++i) {
      const CampbellCurve& curve = d.curves[i];
      for (int s = 0; s + 1 < ns; ++s) {
        const double g0 = curve.frequency_hz[s] - line * speeds[s];
        const double g1 = curve.frequency_hz[s + 1] - line * speeds[s + 1];
        if (!((g0 > 0 && g1 <= 0) || (g0 < 0 && g1 >= 0))) continue;
        // A pair that does not oscillate at either end (heavy damping) meets no line.
        if (curve.frequency_hz[s] <= 0 || curve.frequency_hz[s + 1] <= 0) continue;
        const Eigen::VectorXcd shape = t.modes[s].shapes.col(t.pick[i][s]);
        const auto g = [&](double speed) { return frequency_of(sweep, shape, speed) - line * speed; };
        const double root = g1 == 0 ? speeds[s + 1] : bracketed_root(g, speeds[s], g0, speeds[s + 1], g1);
        // Slope of g by a central difference on the sweep's modes.
        const double h = 1e-4 * (speeds[s + 1] - speeds[s]);
        const double lo = std::max(speeds[s], root - h), hi = std::min(speeds[s + 1], root + h);
        const double slope = (g(hi) - g(lo)) / (hi - lo);
        // The whole model at the root, one secant step with that slope, and the whole model again.
        const double first = sweep.whole_frequency(root, shape) - line * root;
        const bool steep = std::abs(slope) > 1e-9 * line;
        double speed = steep ? root - first / slope : root;
        if (!(speed >= speeds[s] && speed <= speeds[s + 1])) speed = root;
        const double residual = sweep.whole_frequency(speed, shape) - line * speed;
        EngineOrderCrossing x;
        x.engine_order = k;
        x.mode = curve.mode;
        x.speed_rad_s = speed;
        x.frequency_hz = line * speed;
        x.residual = x.frequency_hz > 0 ? std::abs(residual) / x.frequency_hz : std::abs(residual);
        x.amplification = steep ? line / std::abs(slope) : 1e9;
        found.emplace_back(x, shape);
      }
    }
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first.speed_rad_s < b.first.speed_rad_s; });
  d.crossings.clear();
  shapes.clear();
  for (auto& [x, shape] : found) {
    d.crossings.push_back(x);
    shapes.push_back(std::move(shape));
  }
}

// Each curve's closest approach to each engine-order line (EngineOrderApproach), after the
// crossings. `shapes` receives, per approach, the shape it followed.
void find_closest_approaches(SpeedSweep& sweep, const Tracked& t, CampbellDiagram& d,
                             std::vector<Eigen::VectorXcd>& shapes) {
  const auto& speeds = d.speeds_rad_s;
  const int ns = static_cast<int>(speeds.size());
  d.approaches.clear();
  shapes.clear();
  for (int k : d.engine_orders) {
    const double line = k / two_pi;  // Hz per rad/s
    for (std::size_t i = 0; i < d.curves.size(); ++i) {
      const CampbellCurve& curve = d.curves[i];
      EngineOrderApproach a;
      a.engine_order = k;
      a.mode = curve.mode;
      const auto crossing = std::find_if(d.crossings.begin(), d.crossings.end(), [&](const EngineOrderCrossing& x) {
        return x.engine_order == k && x.mode == curve.mode;
      });
      // The speed of least |f − kΩ/2π| / f among those where the pair oscillates.
      int nearest = -1;
      double least = 0;
      for (int s = 0; s < ns; ++s) {
        const double f = curve.frequency_hz[s];
        if (f <= 0) continue;
        const double distance = std::abs(f - line * speeds[s]) / f;
        if (nearest < 0 || distance < least) nearest = s, least = distance;
      }
      if (nearest < 0) continue;  // overdamped throughout: it meets no line
      Eigen::VectorXcd shape = t.modes[nearest].shapes.col(t.pick[i][nearest]);
      if (crossing != d.crossings.end()) {
        a.speed_rad_s = crossing->speed_rad_s;
        a.frequency_hz = crossing->frequency_hz;
        a.distance = 0;
      } else {
        const auto distance = [&](double speed) {
          const double f = frequency_of(sweep, shape, speed);
          return f > 0 ? std::abs(f - line * speed) / f : 1.0;
        };
        const double lo = speeds[std::max(0, nearest - 1)], hi = speeds[std::min(ns - 1, nearest + 1)];
        a.speed_rad_s = golden_minimum(distance, lo, hi, 1e-10 * std::max(1.0, hi));
        a.frequency_hz = sweep.whole_frequency(a.speed_rad_s, shape);
        a.distance = std::abs(a.frequency_hz - line * a.speed_rad_s) / a.frequency_hz;
      }
      d.approaches.push_back(a);
      shapes.push_back(std::move(shape));
    }
  }
}

namespace {

// The diagram from one sweep; a reduced sweep that cannot certify some speed gives way to the
// dense one.
CampbellDiagram diagram_from(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                             const std::function<void(int, int)>& progress) {
  const double lo = options.speeds_rad_s.front(), hi = options.speeds_rad_s.back();
  std::unique_ptr<SpeedSweep> sweep = make_speed_sweep(model, damping, solve_count(model, options), options.solver,
                                                       options.reduction_tolerance, lo, hi);
  CampbellDiagram d;
  Tracked t;
  try {
    t = track(*sweep, model, options, d, progress);
  } catch (const ReducedSweepUnavailable&) {
    sweep = make_dense_speed_sweep(model, damping, solve_count(model, options), options.solver);
    t = track(*sweep, model, options, d, progress);
  }
  std::vector<Eigen::VectorXcd> shapes;
  find_crossings(*sweep, t, d, shapes);
  if (options.closest_approaches) find_closest_approaches(*sweep, t, d, shapes);
  return d;
}

}  // namespace

CampbellDiagram campbell_diagram(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                                 const std::function<void(int, int)>& progress) {
  return diagram_from(model, damping, options, progress);
}

}  // namespace bladestab
