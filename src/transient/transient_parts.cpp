#include "transient_parts.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/transient/transient_checks.hpp"

namespace bladestab::detail {

Recorder::Recorder(const BladeModel& model, const TransientSystem& system, double revolution, int samples_per_revolution,
                   double revolutions, double initial_energy, double max_lateral_m, double static_tip_axial_m,
                   std::vector<TransientSample>& samples)
    : model_(model), system_(system), K_E_(model.elastic_stiffness()), revolution_(revolution),
      per_revolution_(samples_per_revolution), run_revolutions_(revolutions), initial_energy_(initial_energy), max_lateral_m_(max_lateral_m), static_axial_m_(static_tip_axial_m),
      samples_(samples) {}

std::optional<TransientStop> Recorder::operator()(double t, const Eigen::VectorXd& s) const {
  const int n = system_.dofs();
  const Eigen::VectorXd f = s.head(n), v = s.segment(n, n);
  const std::optional<CasingContact>& casing = system_.casing();
  const double F = system_.tip_load(t, s), E = system_.energy(s), W = s(2 * n);
  const TipLoads applied = system_.tip_loads(F, s);
  const double revolutions = revolutions_at(t);
  const TransientSample& sample = samples_.emplace_back(TransientSample{
      t, revolutions, model_.tip_lateral.dot(f), model_.tip_axial.dot(f), model_.tip_lateral.dot(v),
      model_.tip_axial.dot(v), F, system_.friction(F, s), casing ? casing->overlap(t, f) : 0, 0.5 * f.dot(K_E_ * f),
      0.5 * v.dot(model_.M * v), E + (casing ? casing->energy(t, f) : 0), W, E - initial_energy_ - W, applied.axial,
      applied.lateral});
  const double L = model_.blade.L;
  if (std::isinf(max_lateral_m_)) return std::nullopt;
  std::optional<std::string> beyond;
  // Written as !(x ≤ limit) so that NaN stops the run too.
  if (!(std::abs(sample.tip_lateral_m) <= max_lateral_m_)) {
    beyond = fmt::format("the lateral tip deflection passed the small-deflection range of {:g} L", max_lateral_m_ / L);
  } else if (const double change = sample.tip_axial_m - static_axial_m_;
             !(std::abs(change) <= TransientChecks::max_axial_strain * L)) {
    beyond = fmt::format("the axial tip deflection changed by more than the elastic range's mean strain of {:g}",
                         TransientChecks::max_axial_strain);
  }
  if (!beyond) return std::nullopt;
  // A sample beyond the range is the linear model's, not the blade's (within one sample interval a
  // diverging blade reaches any size): the history ends at the last sample within the range.
  if (samples_.size() == 1) return TransientStop{revolutions, *beyond + " at the start"};
  samples_.pop_back();
  return TransientStop{revolutions, fmt::format("{} after revolution {:.4g}, its last sample within the range, where "
                                                "the history ends",
                                                *beyond, samples_.back().revolutions)};
}

double Recorder::revolutions_at(double t) const {
  const double r = t / revolution_, on_grid = std::round(r * per_revolution_) / per_revolution_;
  const double close = 1e-9 * std::max(1.0, r);
  if (std::abs(r - run_revolutions_) <= close) return run_revolutions_;
  return std::abs(r - on_grid) <= close ? on_grid : r;
}

std::vector<double> output_times(int r, double a, double b, double revolution, int per_rev) {
  std::vector<double> outputs;
  // A sample within rounding past b (the end of a fractional run) is taken at b, where the
  // integration ends.
  for (int k = (r == 0 ? 0 : 1); k <= per_rev && a + k * revolution / per_rev <= b * (1 + 1e-12); ++k) {
    outputs.push_back(k == per_rev ? b : std::min(b, a + k * revolution / per_rev));
  }
  return outputs;
}

double energy_norm(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::VectorXd& d) {
  const Eigen::Index n = K.rows();
  return std::sqrt(0.5 * d.head(n).dot(K * d.head(n)) + 0.5 * d.segment(n, n).dot(M * d.segment(n, n)));
}

RunStart run_start(const BladeModel& model, const Scene& scene, const TransientSystem& system,
                   const TransientOptions& o, TransientResult& result) {
  const double speed = scene.operation.speed_rad_s;
  const int n = model.layout.size();
  RunStart begin;
  begin.speed = speed;
  begin.revolution = speed > 0 ? two_pi / speed : system.pulses().period_s * scene.load.pulses_per_rev;
  begin.t_end = o.revolutions * begin.revolution;
  const Eigen::VectorXd equilibrium = rotating_equilibrium(model, speed);
  const Eigen::VectorXd start = o.initial_state ? *o.initial_state : equilibrium;
  if (start.size() != 2 * n) throw std::invalid_argument("initial state has the wrong size");
  begin.x.resize(2 * n + 1);
  begin.x << start, 0.0;
  result.static_tip_axial_m = model.tip_axial.dot(equilibrium.head(n));
  begin.initial_energy = system.energy(begin.x);
  result.initial_vibration_energy_j = begin.initial_energy - system.energy(equilibrium);
  result.energy_terms_j = 2 * std::abs(system.energy(equilibrium));  // E_eq = −½ P_steadyᵀ f_eq
  return begin;
}

Recorder RunStart::recorder(const BladeModel& model, const TransientSystem& system, const TransientOptions& o,
                            TransientResult& result) const {
  return Recorder(model, system, revolution, o.samples_per_revolution, o.revolutions, initial_energy,
                  o.max_lateral_over_length * model.blade.L, result.static_tip_axial_m, result.samples);
}

std::vector<Landing> landings(const ExactStepper& stepper, const RunStart& begin, const TransientOptions& o,
                              double check_time) {
  std::vector<Landing> all;
  const int total_revs = static_cast<int>(std::ceil(o.revolutions));
  for (int r = 0; r < total_revs; ++r) {
    const double a = r * begin.revolution, b = std::min(begin.t_end, (r + 1) * begin.revolution);
    for (double t : output_times(r, a, b, begin.revolution, o.samples_per_revolution)) all.push_back({t, true});
    if (b == (r + 1) * begin.revolution) all.push_back({b, false, true});
  }
  const PulseTrain& pulses = stepper.pulses();
  for (double t : pulses.edges(0, begin.t_end)) all.push_back({t, false, false, false, true});
  for (double kink : stepper.kinks()) {
    for (double t : pulses.edges(0, begin.t_end)) {
      if (pulses.time_in_pulse(t) == 0.0 && t + kink < begin.t_end) all.push_back({t + kink, false, false, false, true});
    }
  }
  if (check_time > 0) all.push_back({check_time, false, false, true});
  std::sort(all.begin(), all.end(), [](const Landing& a, const Landing& b) { return a.t < b.t; });
  std::vector<Landing> merged;
  for (const Landing& l : all) {
    if (!merged.empty() && l.t - merged.back().t <= 1e-9 * std::min(pulses.period_s, begin.revolution)) {
      Landing& m = merged.back();
      if (l.edge && !m.edge) m.t = l.t;
      m.output |= l.output, m.whole_revolution |= l.whole_revolution, m.check |= l.check, m.edge |= l.edge;
    } else {
      merged.push_back(l);
    }
  }
  return merged;
}

LandingLog::LandingLog(const BladeModel& model, const TransientSystem& system, const Recorder& record,
                       const TransientOptions& options, TransientResult& result, const Eigen::VectorXd& start,
                       Eigen::VectorXd& check_state)
    : model_(model), system_(system), record_(record), options_(options), result_(result), last_whole_(start),
      check_state_(check_state), total_revolutions_(static_cast<int>(std::ceil(options.revolutions))) {}

bool LandingLog::sample(const Landing& l, double t, const Eigen::VectorXd& x) {
  if (l.check) check_state_ = x.head(2 * system_.dofs());
  return l.output && (result_.stopped = record_(t, x));
}

bool LandingLog::revolution(const Landing& l, const Eigen::VectorXd& x) {
  if (!l.whole_revolution) return false;
  result_.revolution_change.push_back(energy_norm(system_.stiffness(), model_.M, x - last_whole_));
  last_whole_ = x;
  if (options_.progress) options_.progress(static_cast<int>(result_.revolution_change.size()), total_revolutions_);
  return true;
}

}  // namespace bladestab::detail
