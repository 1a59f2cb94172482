#include "bladestab/modal/campbell.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/modal/mode_tracking.hpp"
#include "support/scalar_search.hpp"
#include "bladestab/modal/speed_sweep.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {
// A richer model's mode is the counterpart of a base mode if their shapes correlate at least this
// well (MAC); below it nothing is known about that point's basis error.
constexpr double counterpart_mac = 0.5;

int tracked_count(const BladeModel& model, const CampbellOptions& options) {
  return std::min(options.mode_count, model.layout.size());
}

// Modes solved per speed: a few more than tracked, so that modes entering from above can be followed.
int solve_count(const BladeModel& model, const CampbellOptions& options) {
  return tracking_candidates(tracked_count(model, options), model.layout.size());
}

// Index of the mode in `modes` most like `shape` (unit columns: MAC = |aᴴ b|²).
int most_like(const SpeedModes& modes, const Eigen::VectorXcd& shape, double* mac = nullptr) {
  Eigen::Index best = 0;
  const double value = (modes.shapes.adjoint() * shape).cwiseAbs2().maxCoeff(&best);
  if (mac) *mac = value;
  return static_cast<int>(best);
}

// Greedy assignment by largest MAC (unit columns: MAC = |aᴴ b|²): result[i] = index in
// `candidates` for tracked shape i.
std::vector<int> match_by_shape(const Eigen::MatrixXcd& tracked, const Eigen::MatrixXcd& candidates,
                                std::vector<double>& mac_out) {
  return assign_by_correlation((tracked.adjoint() * candidates).cwiseAbs2(), mac_out);
}

// The sweep's modes at `speed` with their bounds against the whole model; ReducedSweepUnavailable
// where a reduced sweep cannot bound some of them (the dense sweep then serves the estimate).
SpeedModes certified_modes(SpeedSweep& sweep, double speed) {
  SpeedModes modes = sweep.at(speed, true);
  require_certified(modes);
  return modes;
}

// The sweep's frequency [Hz] at `speed` of the mode most like `shape`: the curve between the speeds.
double frequency_of(SpeedSweep& sweep, const Eigen::VectorXcd& shape, double speed) {
  const SpeedModes modes = sweep.at(speed, false);
  return modes.frequency_hz[most_like(modes, shape)];
}

// The sweep's modes at every speed and, per curve, which of them it follows.
struct Tracked {
  std::vector<SpeedModes> modes;       // per speed
  std::vector<std::vector<int>> pick;  // [curve][speed]
};

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

// ---------------------------------------------------------------------------------------------
// Error estimates.

// The richer models of the basis estimate, each with its sweep and the map from the base
// sweep's coordinates into its own.
struct Reference {
  std::unique_ptr<BladeModel> model;
  std::unique_ptr<SpeedSweep> sweep;
  Eigen::MatrixXcd map;
};

// Base dofs → richer dofs: the bases are hierarchical (the first N shape functions of each field
// are the same in both), so a base vector is the richer vector with zeros in the added terms.
Eigen::MatrixXd embedding(const BladeModel& base, const BladeModel& richer) {
  const DofLayout &a = base.layout, &b = richer.layout;
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(b.size(), a.size());
  const std::vector<std::pair<int, int>> from = a.fields(), to = b.fields();
  for (std::size_t f = 0; f < from.size(); ++f) {
    for (int k = 0; k < from[f].second; ++k) E(to[f].first + k, from[f].first + k) = 1;
  }
  return E;
}

Eigen::MatrixXcd coordinate_map(const SpeedSweep& base, const BladeModel& base_model, const SpeedSweep& richer,
                                const BladeModel& richer_model) {
  return (richer.metric() * (embedding(base_model, richer_model) * base.dofs())).cast<std::complex<double>>();
}

// Budget of one point: mode j of the base model's modes `here`, with its shape, against the
// richer models' modes at the same speed. Relative on the frequency; on |λ| for a pair that does
// not oscillate (frequency 0, heavy damping), as `modes` does.
ErrorBudget point_budget(const SpeedModes& here, int j, const Eigen::VectorXcd& shape,
                         const std::vector<Reference>& refs, const std::vector<const SpeedModes*>& at,
                         const std::vector<int>& terms, BasisConvergence convergence) {
  const bool oscillates = here.frequency_hz[j] > 0;
  const auto value = [&](const SpeedModes& m, int k) { return oscillates ? m.frequency_hz[k] : m.natural_hz[k]; };
  ErrorBudget b;
  const double f0 = value(here, j), b0 = here.bound[j];
  b.reduction = b0;
  b.method = here.rounding[j];
  std::vector<double> f{f0};
  double f1_bound = 0;
  for (std::size_t r = 0; r < refs.size(); ++r) {
    double mac = 0;
    const int k = most_like(*at[r], refs[r].map * shape, &mac);
    if (mac < counterpart_mac || value(*at[r], k) <= 0) {
      b.basis = 1;  // no counterpart: nothing is known
      return b;
    }
    f.push_back(value(*at[r], k));
    if (r == 0) f1_bound = f.back() * at[r]->bound[k];
  }
  // |f_N − f_ref| of the whole models is at most the reduced values' difference plus both bounds.
  const BasisTail tail = basis_tail(f, terms, convergence);
  b.basis = tail.relative + tail.factor * (f0 * b0 + f1_bound) / std::abs(f[1]);
  return b;
}

// The largest whole estimate over the points that oscillate. A pair that does not (frequency 0,
// heavy damping) keeps its estimate on |λ| but does not steer the terms: the 0 printed for it is
// right whatever they are, as long as the pair stays overdamped.
double worst_total(const CampbellDiagram& d, const std::vector<std::vector<ErrorBudget>>& budget) {
  double worst = 0;
  for (std::size_t i = 0; i < budget.size(); ++i) {
    for (std::size_t s = 0; s < budget[i].size(); ++s) {
      if (d.curves[i].frequency_hz[s] > 0) worst = std::max(worst, budget[i][s].total());
    }
  }
  return worst;
}

// The asked-for speeds against the static limits of `model` (at the scene's static compression);
// ParameterError "speeds" when none is within them.
PathWithinLimits campbell_speeds(const BladeModel& model, const CampbellOptions& options) {
  const std::vector<double>& speeds = options.speeds_rad_s;
  const PathWithinLimits path = speeds_within_limits(model, speeds);
  if (path.empty()) {
    const std::string text = options.speeds_text.empty()
                                 ? fmt::format("{:g}:{:g}:{}", speeds.front(), speeds.back(), speeds.size())
                                 : options.speeds_text;
    throw ParameterError("speeds", fmt::format("{}: every speed is past the blade's static limits; at the first, {}",
                                               text, static_limit_error(model, speeds.front(), "Ω")->what()));
  }
  return path;
}

// The least work of a round at `spec`, in flops: the screen's whole solves of the model and of its
// richer models (EstimateRound::work).
double least_round_work(const Scene& scene, ModelSpec spec) {
  double flops = 0;
  for (int model = 0; model <= (spec.basis == BasisKind::sine ? 2 : 1); ++model) {
    flops += 3 * whole_eigensolve_flops(dof_layout(spec, scene.blade.two_planes()).size());
    spec.terms = reference_terms(spec.basis, spec.terms);
  }
  return flops;
}

// The round at `spec` would pass CampbellOptions::work_flops; `reached`: the terms and whole
// estimate of the round before, if any.
WorkLimitError round_past_work_limit(double tolerance, const ModelSpec& spec,
                                     const std::optional<std::pair<int, double>>& reached) {
  const std::string before =
      reached ? fmt::format("at model.terms = {} their estimate is {:.2g}; ", reached->first, reached->second) : "";
  return WorkLimitError(fmt::format("the Campbell frequencies cannot be brought within the tolerance {:g}: {}the "
                                    "diagram at model.terms = {} would pass all that the work limit affords",
                                    tolerance, before, spec.terms));
}

// The largest whole estimate and rounding part over the screened points.
struct Screening {
  double worst = 0, rounding = 0;
};

// The diagram of one round with every point's budget.
struct RoundDiagram {
  CampbellDiagram diagram;
  Tracked tracked;
  std::vector<std::vector<ErrorBudget>> budget;  // [curve][speed]
};

// One round of the estimate at a fixed basis: the base model, its richer models (one for the
// Legendre basis, two for the sine basis) and their sweeps. The richer models' sweeps run beside
// the base model's (each sweep is its own; BLAS runs single-threaded and is thread-safe), or in
// turn where one thread is allowed. The richer models are solved densely where they are solved
// whole, as `modes` does (ARPACK is for the lowest modes of large models, and some damped pairs
// defeat it). Throws ReducedSweepUnavailable where a reduced sweep cannot certify some speed.
class EstimateRound {
public:
  EstimateRound(const Scene& scene, const ModelSpec& spec, const CampbellOptions& options, bool dense)
      : scene_(scene), options_(options), dense_(dense),
        model_(std::make_unique<BladeModel>(assemble_model_at_any_speed(scene, spec))),
        limits_(campbell_speeds(*model_, options)), terms_{spec.terms},
        convergence_(basis_convergence(scene.blade, spec.basis)) {
    // The speeds within the static limits of the model the curves belong to.
    options_.speeds_rad_s.assign(options.speeds_rad_s.begin() + limits_.first, options.speeds_rad_s.begin() + limits_.end);
    count_ = solve_count(*model_, options_);
    tracked_ = tracked_count(*model_, options_);
    for (int level = 0; level < (spec.basis == BasisKind::sine ? 2 : 1); ++level) {
      ModelSpec richer = spec;
      richer.terms = reference_terms(spec.basis, terms_.back());
      terms_.push_back(richer.terms);
      refs_.push_back({std::make_unique<BladeModel>(assemble_model_at_any_speed(scene, richer)), nullptr, {}});
    }
    const EigenSolverKind richer_solver =
        options_.solver == EigenSolverKind::arpack ? EigenSolverKind::dense : options_.solver;
    run_indexed(2, options_.threads, [&](std::size_t part) {
      if (part == 0) {
        base_ = sweep_of(*model_, options_.solver);
        return;
      }
      for (Reference& r : refs_) {
        r.sweep = sweep_of(*r.model, reduced_sweep_applies(*r.model, scene.damping) ? richer_solver
                                                                                    : EigenSolverKind::dense);
      }
    });
    update_maps();
  }

  // The screen at the ends and the middle of the speeds (the reduced sweeps' samples, where they
  // are exact), over the modes that oscillate.
  Screening screen() {
    const double lo = options_.speeds_rad_s.front(), hi = options_.speeds_rad_s.back();
    Screening s;
    for (double speed : {lo, 0.5 * (lo + hi), hi}) {
      const SpeedModes here = certified_modes(*base_, speed);
      std::vector<SpeedModes> richer;
      for (Reference& r : refs_) richer.push_back(certified_modes(*r.sweep, speed));
      for (int j = 0; j < tracked_; ++j) {
        if (here.frequency_hz[j] > 0) {
          const ErrorBudget b = point_budget(here, j, here.shapes.col(j), refs_, pointers(richer), terms_, convergence_);
          s.worst = std::max(s.worst, b.total());
          s.rounding = std::max(s.rounding, b.method);
        }
      }
    }
    return s;
  }

  // The whole-model eigensolves the round has taken, in flops (whole_eigensolve_flops): each
  // model's at its reduced sweep's samples, or at the screen's three speeds and, once the diagram
  // is solved, at every speed where it is solved densely. The reduced solves are not counted.
  double work() const {
    const int speeds = static_cast<int>(options_.speeds_rad_s.size());
    const auto solves = [&](const SpeedSweep& sweep) {
      const int samples = static_cast<int>(sweep.sample_speeds().size());
      return samples > 0 ? std::max(3, samples) : 3 + (swept_ ? speeds : 0);
    };
    double flops = solves(*base_) * whole_eigensolve_flops(model_->M.rows());
    for (const Reference& r : refs_) flops += solves(*r.sweep) * whole_eigensolve_flops(r.model->M.rows());
    return flops;
  }

  // The base model's diagram at every speed, the richer models solved beside it, and the budget of
  // every point.
  RoundDiagram diagram(const std::function<void(int, int)>& progress) {
    const std::vector<double>& speeds = options_.speeds_rad_s;
    swept_ = true;
    RoundDiagram d;
    std::vector<std::vector<SpeedModes>> richer(refs_.size());
    run_indexed(2, options_.threads, [&](std::size_t part) {
      if (part == 0) {
        d.tracked = track(*base_, *model_, options_, d.diagram, progress);
        return;
      }
      for (std::size_t r = 0; r < refs_.size(); ++r) richer[r] = refs_[r].sweep->solve(speeds);
    });
    update_maps();
    const int ns = static_cast<int>(speeds.size());
    d.budget.assign(tracked_, std::vector<ErrorBudget>(ns));
    std::vector<const SpeedModes*> at(refs_.size());
    for (int s = 0; s < ns; ++s) {
      for (std::size_t r = 0; r < refs_.size(); ++r) at[r] = &richer[r][s];
      const SpeedModes& here = d.tracked.modes[s];
      for (int i = 0; i < tracked_; ++i) {
        const int j = d.tracked.pick[i][s];
        d.budget[i][s] = point_budget(here, j, here.shapes.col(j), refs_, at, terms_, convergence_);
      }
    }
    return d;
  }

  // The result: the crossings' and closest approaches' budgets from their frequencies' (relative).
  CampbellWithErrors with_engine_order_budgets(RoundDiagram solved, double tolerance) {
    CampbellDiagram& diagram = solved.diagram;
    std::vector<Eigen::VectorXcd> shapes;
    find_crossings(*base_, solved.tracked, diagram, shapes);
    std::vector<ErrorBudget> crossing_budget;
    for (std::size_t c = 0; c < shapes.size(); ++c) {
      const EngineOrderCrossing& x = diagram.crossings[c];
      const ErrorBudget f = frequency_budget(x.speed_rad_s, shapes[c]);
      crossing_budget.push_back(scaled(f, x.amplification, x.amplification * x.residual));
    }
    std::vector<ErrorBudget> approach_budget;
    if (options_.closest_approaches) {
      find_closest_approaches(*base_, solved.tracked, diagram, shapes);
      for (std::size_t c = 0; c < shapes.size(); ++c) {
        const EngineOrderApproach& a = diagram.approaches[c];
        // distance = |1 − kΩ/(2πf)|: a relative error ε of f moves it by (kΩ/2πf)·ε.
        const double sensitivity = a.engine_order * a.speed_rad_s / (two_pi * a.frequency_hz);
        const ErrorBudget f = frequency_budget(a.speed_rad_s, shapes[c]);
        approach_budget.push_back(scaled(f, sensitivity, sensitivity * f.reduction));
      }
    }
    return CampbellWithErrors{std::move(*model_),
                              std::move(diagram),
                              limits_,
                              tolerance,
                              std::vector<int>(terms_.begin() + 1, terms_.end()),
                              std::move(solved.budget),
                              std::move(crossing_budget),
                              std::move(approach_budget),
                              0};
  }

private:
  std::unique_ptr<SpeedSweep> sweep_of(const BladeModel& m, EigenSolverKind solver) const {
    const double lo = options_.speeds_rad_s.front(), hi = options_.speeds_rad_s.back();
    return dense_ ? make_dense_speed_sweep(m, scene_.damping, count_, solver)
                  : make_speed_sweep(m, scene_.damping, count_, solver, options_.reduction_tolerance, lo, hi);
  }
  // The base sweep's coordinates in each richer sweep's (its basis may have grown since).
  void update_maps() {
    for (Reference& r : refs_) r.map = coordinate_map(*base_, *model_, *r.sweep, *r.model);
  }
  static std::vector<const SpeedModes*> pointers(const std::vector<SpeedModes>& modes) {
    std::vector<const SpeedModes*> at;
    for (const SpeedModes& m : modes) at.push_back(&m);
    return at;
  }
  // The budget of the frequency followed by `shape` at `speed` (relative).
  ErrorBudget frequency_budget(double speed, const Eigen::VectorXcd& shape) {
    const SpeedModes here = certified_modes(*base_, speed);
    std::vector<SpeedModes> there;
    for (Reference& r : refs_) there.push_back(certified_modes(*r.sweep, speed));
    const int j = most_like(here, shape);
    return point_budget(here, j, here.shapes.col(j), refs_, pointers(there), terms_, convergence_);
  }
  // A frequency's basis and method parts times `factor`, and the given reduction part.
  static ErrorBudget scaled(const ErrorBudget& f, double factor, double reduction) {
    ErrorBudget b;
    b.basis = factor * f.basis;
    b.reduction = reduction;
    b.method = factor * f.method;
    return b;
  }

  const Scene& scene_;
  CampbellOptions options_;  // its speeds those within the static limits
  bool dense_;
  std::unique_ptr<BladeModel> model_;
  PathWithinLimits limits_;
  int count_ = 0, tracked_ = 0;
  bool swept_ = false;      // the diagram has been solved
  std::vector<int> terms_;  // the base model's and each richer model's
  BasisConvergence convergence_;
  std::vector<Reference> refs_;
  std::unique_ptr<SpeedSweep> base_;
};


}  // namespace

CampbellDiagram campbell_diagram(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                                 const std::function<void(int, int)>& progress) {
  return diagram_from(model, damping, options, progress);
}

ErrorBudget CampbellWithErrors::worst() const {
  ErrorBudget w;
  for (const auto& curve : budget) {
    for (const ErrorBudget& b : curve) w.raise_to(b);
  }
  for (const ErrorBudget& b : crossing_budget) w.raise_to(b);
  return w;
}

ErrorBudget CampbellWithErrors::worst_at(std::size_t speed) const {
  ErrorBudget w;
  for (const auto& curve : budget) w.raise_to(curve[speed]);
  return w;
}

CampbellWithErrors campbell_with_error_estimate(const Scene& scene, const CampbellOptions& options, double tolerance,
                                                const std::function<void(int, int)>& progress) {
  check_tolerance(tolerance);
  CampbellOptions wanted = options;
  wanted.reduction_tolerance = tolerance / 20;
  ModelSpec spec = scene.model;
  bool dense = false;  // set when a reduced sweep could not certify some speed
  double spent = 0;    // the whole-model eigensolves of the rounds before (EstimateRound::work)
  std::optional<std::pair<int, double>> reached;  // the last round's terms and estimate
  const auto raise = [&](double worst, const EstimateRound& round) {
    const std::optional<int> next = terms_for_tolerance(basis_convergence(scene.blade, spec.basis), spec.terms,
                                                         worst, tolerance);
    if (!next) throw tolerance_not_met(tolerance, spec, worst);
    spent += round.work();
    reached = std::pair{spec.terms, worst};
    spec.terms = *next;
  };
  while (true) {
    if (spent + least_round_work(scene, spec) > options.work_flops) throw round_past_work_limit(tolerance, spec, reached);
    try {
      EstimateRound round(scene, spec, wanted, dense);
      // Screen at the ends and the middle: a basis that misses there is raised before the whole sweep.
      const Screening screened = round.screen();
      if (screened.rounding > tolerance) throw tolerance_below_rounding(tolerance, screened.rounding);
      if (screened.worst > tolerance) {
        raise(screened.worst, round);
        continue;
      }
      RoundDiagram solved = round.diagram(progress);
      const double worst = worst_total(solved.diagram, solved.budget);
      if (worst > tolerance) {
        double rounding = screened.rounding;
        for (const auto& curve : solved.budget) {
          for (const ErrorBudget& b : curve) rounding = std::max(rounding, b.method);
        }
        if (rounding > tolerance) throw tolerance_below_rounding(tolerance, rounding);
        raise(worst, round);
        continue;
      }
      CampbellWithErrors result = round.with_engine_order_budgets(std::move(solved), tolerance);
      result.work_flops = spent + round.work();
      return result;
    } catch (const ReducedSweepUnavailable&) {
      dense = true;
    }
  }
}

}  // namespace bladestab
