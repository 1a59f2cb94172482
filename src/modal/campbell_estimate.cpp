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
#include "bladestab/modal/speed_sweep.hpp"
#include "modal/campbell_parts.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

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

// The least work of a round at `spec`, in flops: the screen's whole solves, at three speeds, of the
// model and of its richer models (EstimateRound::work). Its speeds are within the static limits
// (campbell_speeds).
double least_round_work(const Scene& scene, const ModelSpec& spec) {
  return 3 * reference_solves(spec, scene.blade.two_planes(), scene.damping.damped(), true).flops;
}

// The round at `spec` would pass CampbellOptions::work_flops; `reached`: the terms and whole
// estimate of the round before, if any.
WorkLimitError round_past_work_limit(double tolerance, const ModelSpec& spec,
                                     const std::optional<BasisRound>& reached) {
  const std::string before =
      reached ? fmt::format("at model.terms = {} their estimate is {:.2g}; ", reached->terms, reached->estimate) : "";
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
        convergence_(basis_convergence(scene.blade, spec.basis, spec.terms)) {
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

  // The eigensolves the round has taken, in flops (whole_eigensolve_flops, within the static
  // limits): each model's whole solves at its reduced sweep's samples, or at the screen's three
  // speeds, and once the diagram is solved, sweep_work().
  double work() const {
    const bool damped = scene_.damping.damped();
    const auto samples = [](const SpeedSweep& sweep) {
      return std::max<double>(3, static_cast<double>(sweep.sample_speeds().size()));
    };
    double flops = samples(*base_) * whole_eigensolve_flops(model_->M.rows(), damped, true);
    for (const Reference& r : refs_) flops += samples(*r.sweep) * whole_eigensolve_flops(r.model->M.rows(), damped, true);
    return flops + (swept_ ? sweep_work() : 0);
  }

  // The diagram's work, in flops: at every speed, the solves of the reduced basis where a sweep is
  // reduced, 12 m³ for m vectors (200 m³ damped: about 1.7–1.9× their time), else of the whole
  // model, and the points' budgets, which map each shape into each richer sweep's coordinates and
  // find its counterpart there (point_budget: two complex products of m_richer × m); and for the
  // closest approaches (check's margin), a golden-section search of each curve to each line, ~40
  // solves. With many modes the reduced basis nears the whole model (the fan blade's 64 modes at
  // 201 speeds took 5 s, 3.2× its whole solves at the samples); with few, a reduced speed's fixed
  // work (its matrices, modes and bounds) is about 0.1 ms, counted as 1e6 flops (the paper blade's
  // 8 modes at 20000 speeds: 8.7 s for two rounds).
  double sweep_work() const {
    constexpr double reduced_speed_overhead = 1e6;
    const double speeds = static_cast<double>(options_.speeds_rad_s.size());
    const bool damped = scene_.damping.damped();
    const auto one_solve = [&](const SpeedSweep& sweep, const BladeModel& model) {
      if (sweep.sample_speeds().empty()) return whole_eigensolve_flops(model.M.rows(), damped, true);
      const double m = sweep.vectors();
      return (damped ? 200 : 12) * m * m * m + reduced_speed_overhead;
    };
    const double m = base_->vectors(), lines = static_cast<double>(options_.engine_orders.size());
    double flops = (speeds + (options_.closest_approaches ? 40 * tracked_ * lines : 0)) * one_solve(*base_, *model_);
    for (const Reference& r : refs_) flops += speeds * (one_solve(*r.sweep, *r.model) + tracked_ * 16 * m * r.sweep->vectors());
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

ErrorBudget CampbellWithErrors::worst() const {
  ErrorBudget w;
  for (std::size_t i = 0; i < budget.size(); ++i) {
    for (std::size_t s = 0; s < budget[i].size(); ++s) {
      if (diagram.curves[i].frequency_hz[s] > 0) w.raise_to(budget[i][s]);  // as worst_total
    }
  }
  for (const ErrorBudget& b : crossing_budget) w.raise_to(b);
  return w;
}

int CampbellWithErrors::points_not_oscillating() const {
  int count = 0;
  for (const CampbellCurve& c : diagram.curves) {
    count += static_cast<int>(std::count_if(c.frequency_hz.begin(), c.frequency_hz.end(), [](double f) { return !(f > 0); }));
  }
  return count;
}

ErrorBudget CampbellWithErrors::worst_at(std::size_t speed) const {
  ErrorBudget w;
  for (const auto& curve : budget) w.raise_to(curve[speed]);
  return w;
}

CampbellWithErrors campbell_with_error_estimate(const Scene& scene, const CampbellOptions& options, double tolerance,
                                                const std::function<void(int, int)>& progress) {
  check_tolerance(tolerance);
  check_mode_count(scene.blade, scene.model, options.mode_count);
  CampbellOptions wanted = options;
  wanted.reduction_tolerance = tolerance / 20;
  ModelSpec spec = scene.model;
  bool dense = false;  // set when a reduced sweep could not certify some speed
  double spent = 0;    // the whole-model eigensolves of the rounds before (EstimateRound::work)
  std::optional<BasisRound> reached;  // the last round's terms and estimate
  const auto raise = [&](double worst, const EstimateRound& round) {
    const std::optional<int> next =
        terms_for_tolerance(scene.blade, spec, worst, tolerance, reached);
    if (!next) throw tolerance_not_met(tolerance, spec, worst);
    spent += round.work();
    reached = BasisRound{spec.terms, worst};
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
      if (spent + round.work() + round.sweep_work() > options.work_flops) {
        throw round_past_work_limit(tolerance, spec, reached);
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
      const double work = round.work();  // before the result takes the round's model
      CampbellWithErrors result = round.with_engine_order_budgets(std::move(solved), tolerance);
      result.work_flops = spent + work;
      return result;
    } catch (const ReducedSweepUnavailable&) {
      dense = true;
    }
  }
}

}  // namespace bladestab
