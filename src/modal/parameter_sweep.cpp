#include "bladestab/modal/parameter_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/modal/mode_tracking.hpp"
#include "bladestab/scene/scene.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

constexpr double not_matched_by_shape = std::numeric_limits<double>::quiet_NaN();

void check_key_form(const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size() || key.find('=') != std::string::npos) {
    throw ParameterError("key", fmt::format("{}: must be section.key, a scene key that takes a number (e.g. "
                                 "blade.slenderness, operation.tip_compression_over_fcr)",
                                 key));
  }
}

// The scene at one value. The scene without the swept key was read first, so what fails here
// fails because of the key or its value.
Scene scene_with_value(const std::string& text, const std::string& source, std::vector<std::string> overrides,
               const ParameterSweepOptions& o, double value) {
  overrides.push_back(o.key + "=" + scene_value_text(value));
  try {
    return parse_scene(text, source, overrides);
  } catch (const SceneKeyError& e) {
    switch (e.reason()) {
      case SceneKeyError::Reason::unknown:
      case SceneKeyError::Reason::unused:
        throw ParameterError("key", fmt::format("{}: {}", o.key, e.what()));
      case SceneKeyError::Reason::not_numeric:
        throw ParameterError("key", fmt::format("{}: takes no number: {}", o.key, e.what()));
      case SceneKeyError::Reason::not_allowed:
        break;
    }
    throw ParameterError("values", fmt::format("{}: {}", o.values_text, e.what()));
  } catch (const InputError& e) {
    throw ParameterError("values", fmt::format("{}: {}", o.values_text, e.what()));
  }
}

// The modes of the scene at one value with their error estimates; all of them where the dense
// solver serves (so a tracked mode cannot leave the candidates), the tracking window with ARPACK.
ConvergedModes modes_at(const Scene& scene, const ParameterSweepOptions& o) {
  const int candidates =
      o.solver == EigenSolverKind::arpack ? tracking_candidates(o.mode_count, std::numeric_limits<int>::max()) : 0;
  try {
    return modes_with_error_estimate(scene, candidates, o.solver);
  } catch (const InputError& e) {  // e.g. a static compression the blade cannot carry
    throw ParameterError("values", fmt::format("{}: {}", o.values_text, e.what()));
  }
}

// The values against the blade's static limits: at each, the scene's operating point on that
// value's model. model.terms takes integers only, so its limits lie at values, not between them.
PathWithinLimits values_within_limits(const std::string& text, const std::string& source,
                                      const std::vector<std::string>& overrides, const ParameterSweepOptions& o) {
  const auto point = [&](double value) {
    const Scene scene = scene_with_value(text, source, overrides, o, value);
    return std::pair{assemble_model_at_any_speed(scene, scene.model), scene.operation.speed_rad_s};
  };
  const PathWithinLimits path = path_within_limits(
      o.values,
      [&](double value) {
        const auto [model, speed] = point(value);
        return static_margin(model, speed);
      },
      [&](double value) {
        const auto [model, speed] = point(value);
        return static_limit_at(model, speed);
      },
      o.key != "model.terms");
  if (path.empty()) {
    const auto [model, speed] = point(o.values.front());
    throw ParameterError("values", fmt::format("{}: every value is past the blade's static limits; at the first, {}",
                                               o.values_text, static_limit_error(model, speed)->what()));
  }
  return path;
}

// The shapes of the modes `pick` (all of them when empty), as columns.
Eigen::MatrixXcd shapes_of(const ModalSolution& solution, const std::vector<int>& pick = {}) {
  const std::size_t count = pick.empty() ? solution.modes.size() : pick.size();
  Eigen::MatrixXcd shapes(solution.modes.front().shape.size(), count);
  for (std::size_t i = 0; i < count; ++i) shapes.col(i) = solution.modes[pick.empty() ? i : pick[i]].shape;
  return shapes;
}

// The sweep's curves, built value by value in order: the first value's lowest modes, followed by
// their shapes while the dofs stay the same, by frequency order where they change.
class SweepTracker {
public:
  // `values`: those solved, the run of the values asked for within the static limits.
  SweepTracker(const ParameterSweepOptions& o, std::vector<double> values) : o_(o), values_(std::move(values)) {}

  // Value v's modes joined to the curves.
  void add(int v, const Scene& scene, const ConvergedModes& here) {
    const ModalSolution& solution = here.solution;
    const int n = here.model.layout.size(), available = static_cast<int>(solution.modes.size());
    std::vector<double> correlation;
    if (v == 0) {
      first_model_ = here.model;
      first_solver_ = solution.solver;
      const int tracked = std::min(o_.mode_count, available);
      modes_.resize(tracked);
      pick_.resize(tracked);
      for (int i = 0; i < tracked; ++i) {
        pick_[i] = i;
        modes_[i].index = i + 1;
        modes_[i].family = solution.modes[i].family;
      }
      correlation.assign(tracked, 1.0);
      matched_by_.push_back(ModeMatch::first);
    } else if (n == dofs_.back()) {
      // Same dofs: the mode most like each tracked shape, by MAC in this value's mass matrix.
      pick_ = assign_by_correlation(modal_assurance_matrix(previous_shapes_, shapes_of(solution), here.model.M),
                                    correlation);
      matched_by_.push_back(ModeMatch::shape);
    } else {
      // Other dofs (another basis size or field set): the shapes do not compare; by frequency order.
      for (std::size_t i = 0; i < pick_.size(); ++i) pick_[i] = static_cast<int>(i);
      correlation.assign(pick_.size(), not_matched_by_shape);
      matched_by_.push_back(ModeMatch::order);
    }
    if (std::any_of(pick_.begin(), pick_.end(), [&](int k) { return k < 0 || k >= available; })) {
      throw ParameterError("count", fmt::format("{}: the model at {} = {} has only {} modes", o_.mode_count, o_.key,
                                                scene_value_text(values_[v]), available));
    }
    for (std::size_t i = 0; i < pick_.size(); ++i) {
      const Mode& m = solution.modes[pick_[i]];
      SweptMode& curve = modes_[i];
      curve.families.push_back(m.family);
      curve.frequency_hz.push_back(m.frequency_hz);
      curve.lambda.push_back(m.lambda);
      curve.damping_ratio.push_back(m.damping_ratio);
      curve.correlation.push_back(correlation[i]);
      curve.error_estimate.push_back(here.budget(pick_[i]).total());
    }
    previous_shapes_ = shapes_of(solution, pick_);
    speeds_.push_back(scene.operation.speed_rad_s);
    dofs_.push_back(n);
    reference_terms_.push_back(here.reference_terms);
  }

  // The curves, with where the values asked for meet the static limits and whether they ascend.
  ParameterSweep sweep(const PathWithinLimits& limits, bool ascending) {
    return ParameterSweep{std::move(*first_model_), o_.key,
                          std::move(values_),       limits,
                          ascending,                std::move(speeds_),
                          std::move(dofs_),         std::move(reference_terms_),
                          std::move(matched_by_),   first_solver_,
                          std::move(modes_)};
  }

private:
  const ParameterSweepOptions& o_;
  std::vector<double> values_;
  std::vector<SweptMode> modes_;
  std::vector<double> speeds_;
  std::vector<int> dofs_, reference_terms_;
  std::vector<ModeMatch> matched_by_;
  std::optional<BladeModel> first_model_;
  EigenSolverKind first_solver_ = EigenSolverKind::dense;
  std::vector<int> pick_;             // per tracked mode: its index among this value's modes
  Eigen::MatrixXcd previous_shapes_;  // the tracked modes' shapes at the previous value
};

}  // namespace

const char* to_string(ModeMatch m) {
  switch (m) {
    case ModeMatch::first: return "first";
    case ModeMatch::shape: return "shape";
    case ModeMatch::order: return "order";
  }
  return "?";
}

std::string scene_value_text(double value) {
  if (std::abs(value) < 1e15 && value == std::round(value)) return fmt::format("{}", static_cast<long long>(value));
  return fmt::format("{}", value);
}

double ParameterSweep::max_error_estimate() const {
  double worst = 0;
  for (const SweptMode& m : modes) {
    for (double e : m.error_estimate) worst = std::max(worst, e);
  }
  return worst;
}

double ParameterSweep::min_correlation() const {
  double lowest = 1;
  for (const SweptMode& m : modes) {
    for (double c : m.correlation) {
      if (!std::isnan(c)) lowest = std::min(lowest, c);
    }
  }
  return lowest;
}

ParameterSweep parameter_sweep(const std::string& text, const std::string& source,
                               const std::vector<std::string>& overrides, const ParameterSweepOptions& o,
                               const std::function<void(int, int)>& progress) {
  check_key_form(o.key);
  if (o.mode_count < 1) throw ParameterError("count", fmt::format("{}: must be an integer >= 1", o.mode_count));
  if (o.values.size() < 2) throw ParameterError("values", fmt::format("{}: needs at least 2 values", o.values_text));
  parse_scene(text, source, overrides);  // the scene itself, before the key is touched

  const PathWithinLimits limits = values_within_limits(text, source, overrides, o);
  const std::vector<double> values(o.values.begin() + limits.first, o.values.begin() + limits.end);
  // The values are independent: solved a batch at a time, one per worker thread (BLAS runs single-threaded;
  // ARPACK runs one solve at a time, arpack_modes.cpp), then tracked in order; a batch bounds the
  // memory held for large models. The first value that fails, in the order given, is the one reported.
  struct Solved {
    Scene scene;
    ConvergedModes modes;
  };
  const int nv = static_cast<int>(values.size());
  const int workers = std::min(nv, worker_threads(o.threads));
  SweepTracker tracker(o, values);
  for (int start = 0; start < nv; start += workers) {
    const int batch = std::min(workers, nv - start);
    WorkPool<Solved> solved(workers, batch, [&](std::size_t b) {
      Scene scene = scene_with_value(text, source, overrides, o, values[start + b]);
      ConvergedModes modes = modes_at(scene, o);
      return Solved{std::move(scene), std::move(modes)};
    });
    for (int b = 0; b < batch; ++b) {
      const Solved value = solved.get(b);
      tracker.add(start + b, value.scene, value.modes);
      if (progress) progress(start + b + 1, nv);
    }
  }
  return tracker.sweep(limits, o.values.front() < o.values.back());
}

}  // namespace bladestab
