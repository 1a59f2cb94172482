#include "bladestab/transient/transient.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/transient/casing_contact.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/transient/transient_system.hpp"
#include "bladestab/blade/undamped_modes.hpp"

namespace bladestab {

Eigen::VectorXd rotating_equilibrium(const BladeModel& model, double speed) {
  const int n = model.layout.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n);
  x.head(n) = model.stiffness(speed).ldlt().solve(model.steady_load(speed));
  return x;
}

FixedStep choose_fixed_step(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, double duration, int steps_per_period) {
  if (steps_per_period != 0 && steps_per_period < 8) {
    throw std::invalid_argument("steps per period below the paper's bound (54) of 8");
  }
  const double omega_max = std::sqrt(generalized_modes(K, M, 0, false).omega2.maxCoeff());
  const auto growth = [&](int n) {
    const double y = two_pi / n;  // ω_max Δt
    return std::pow(std::abs(rkf45_stability_function({0, y})), duration * omega_max / y);
  };
  FixedStep fixed;
  fixed.steps_per_period = steps_per_period != 0 ? steps_per_period : 8;
  if (steps_per_period == 0) {
    while (growth(fixed.steps_per_period) > 1.01) ++fixed.steps_per_period;
  }
  fixed.step_s = two_pi / (fixed.steps_per_period * omega_max);  // (54)
  fixed.parasitic_growth = growth(fixed.steps_per_period);
  return fixed;
}

FixedStep transient_step(const BladeModel& model, const Scene& scene, const TransientOptions& o, double duration_s) {
  Eigen::MatrixXd K_stiffest = model.stiffness(scene.operation.speed_rad_s);
  // In clearance mode the stiffest mode is the one with the casing in contact.
  if (scene.load.mode == LoadMode::clearance) {
    K_stiffest += casing_contact(model, scene).stiffness_n_m * model.tip_axial.transpose() * model.tip_axial;
  }
  return choose_fixed_step(K_stiffest, model.M, duration_s, o.adaptive ? 0 : o.steps_per_period);
}

TransientSystem::TransientSystem(const BladeModel& model, const Scene& scene, const TransientOptions& o)
    : n_(model.layout.size()), pulses_(pulse_train(scene)) {
  if (!pulses_.frequency_known) {
    throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz");
  }
  const double speed = scene.operation.speed_rad_s;
  if (scene.load.mode == LoadMode::clearance) casing_ = casing_contact(model, scene);
  const Eigen::LLT<Eigen::MatrixXd> mass(model.M);
  M_ = model.M;
  K_ = model.stiffness(speed);
  D_ = damping_matrix(model, scene.damping, speed);
  G_ = model.G;
  const Eigen::MatrixXd C = D_ + model.gyroscopic(speed);
  MiK_ = mass.solve(K_), MiC_ = mass.solve(C), MiG_ = mass.solve(model.G);
  steady_ = model.steady_load(speed);
  Mi_cf_ = mass.solve(steady_);
  Mi_axial_ = mass.solve(Eigen::VectorXd(model.tip_axial.transpose()));
  Mi_lateral_ = mass.solve(Eigen::VectorXd(model.tip_lateral.transpose()));
  tip_axial_ = model.tip_axial, tip_lateral_ = model.tip_lateral, tip_slope_ = model.tip_slope;
  mu_ = scene.load.friction, cos_beta_ = std::cos(model.blade.beta_rad);
  rim_speed_ = speed * model.blade.tip_radius();
  friction_velocity_ = o.friction_velocity;
  follower_ = o.follower;
  damped_ = !D_.isZero(0);
  work_.resize(n_);
}

double TransientSystem::tip_load(double t, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return casing_ ? casing_->force(t, x.head(n_)) : pulses_.force(t);
}

double TransientSystem::friction(double F, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (mu_ == 0 || F == 0) return 0.0;
  const double v_rel = rim_speed_ + cos_beta_ * tip_lateral_.dot(x.segment(n_, n_));
  return -mu_ * std::abs(F) * cos_beta_ * std::tanh(v_rel / friction_velocity_);
}

TipLoads TransientSystem::tip_loads(double F, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  TipLoads loads{F, friction(F, x)};
  if (follower_ && F != 0) {
    const double psi = tip_slope_.dot(x.head(n_));
    loads.axial = F * std::cos(psi);
    loads.lateral -= F * std::sin(psi);
  }
  return loads;
}

double TransientSystem::energy(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const auto f = x.head(n_), v = x.segment(n_, n_);
  return 0.5 * v.dot(M_ * v) + 0.5 * f.dot(K_ * f) - steady_.dot(f);
}

void TransientSystem::derivative(double t, const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::VectorXd> dx) const {
  const int n = n_;
  const auto f = x.head(n), v = x.segment(n, n);
  const double F = tip_load(t, x);
  dx.head(n) = v;
  auto a = dx.segment(n, n);
  a = Mi_cf_;
  a.noalias() -= MiK_ * f;
  a.noalias() -= MiC_ * v;
  dx(2 * n) = 0;
  if (damped_) {
    work_.noalias() = D_ * v;
    dx(2 * n) = -v.dot(work_);
  }
  if (F == 0) return;
  const auto [axial, lateral] = tip_loads(F, x);
  work_.noalias() = MiG_ * f;
  a += axial * (Mi_axial_ - work_) + lateral * Mi_lateral_;
  work_.noalias() = G_ * v;
  dx(2 * n) += axial * (tip_axial_.dot(v) - f.dot(work_)) + lateral * tip_lateral_.dot(v);
}

namespace {

// Clearance mode: what the casing did, from landings on every closing and opening (g = 0) and on
// every deepest overlap (ġ = 0).
class ContactEvents {
public:
  ContactEvents(const CasingContact& casing, const Eigen::VectorXd& start) : casing_(casing), summary_{casing.stiffness_n_m} {
    if (casing.overlap(0, start.head(start.size() / 2)) > 0) summary_.closures = 1;  // starts in contact
  }
  std::vector<OdeEvent> events(int n) {
    const auto overlap = [this, n](double t, const Eigen::VectorXd& y) { return casing_.overlap(t, y.head(n)); };
    const auto rate = [this, n](double t, const Eigen::VectorXd& y) {
      return casing_.overlap_rate(t, y.head(n), y.segment(n, n));
    };
    const auto closing_or_opening = [this](double t, const Eigen::VectorXd&, int direction) {
      if (direction > 0) {
        ++summary_.closures, contact_start_ = t;
      } else {
        summary_.contact_time_s += t - contact_start_;
      }
    };
    const auto deepest = [this, n](double t, const Eigen::VectorXd& y, int direction) {
      if (direction > 0) return;  // the shallowest point
      const double g = casing_.overlap(t, y.head(n));
      summary_.max_overlap_m = std::max(summary_.max_overlap_m, g);
      summary_.peak_force_n = std::max(summary_.peak_force_n, casing_.stiffness_n_m * g);
    };
    return {{overlap, closing_or_opening}, {rate, deepest}};
  }
  // The summary at the run's end `t_end` with the state x there (a contact still open counts).
  ContactSummary finished(double t_end, const Eigen::VectorXd& x, int n) {
    if (casing_.overlap(t_end, x.head(n)) > 0) summary_.contact_time_s += t_end - contact_start_;
    return summary_;
  }

private:
  const CasingContact& casing_;
  ContactSummary summary_;
  double contact_start_ = 0;
};

// The steps: adaptive ones never exceed the fixed step (54). The error control alone cannot keep
// RKF45 stable on the undamped stiff modes: it measures the error relative to |x|, so once a mode
// amplified by |R(iωh)| > 1 dominates a component it sets its own allowance: at rtol 1e-2 it
// accepts a growth of ×1e21 in two revolutions. Below this cap the growth per unit time,
// ln|R(iωh)|/h, is smaller still for every mode (it rises with ωh), so the whole run stays within
// the 1 % bound.
StepControl step_control(const TransientOptions& o, const FixedStep& fixed) {
  StepControl control;
  control.adaptive = o.adaptive;
  control.rtol = o.tolerance;
  // Absolute floor: a millionth of the tolerance on the scale of the static stretch (≈ mm).
  control.atol = o.tolerance * 1e-6;
  (o.adaptive ? control.max_step : control.fixed_step) = fixed.step_s;
  return control;
}

// The samples of a run: tip motion, loads and the energy balance at each output time.
class Recorder {
public:
  Recorder(const BladeModel& model, const TransientSystem& system, double speed, double revolution,
           double initial_energy, std::vector<TransientSample>& samples)
      : model_(model), system_(system), K_E_(model.elastic_stiffness()), speed_(speed), revolution_(revolution),
        initial_energy_(initial_energy), samples_(samples) {}
  void operator()(double t, const Eigen::VectorXd& s) const {
    const int n = system_.dofs();
    const Eigen::VectorXd f = s.head(n), v = s.segment(n, n);
    const std::optional<CasingContact>& casing = system_.casing();
    const double F = system_.tip_load(t, s), E = system_.energy(s), W = s(2 * n);
    const TipLoads applied = system_.tip_loads(F, s);
    samples_.push_back({t, speed_ > 0 ? t * speed_ / two_pi : t / revolution_, model_.tip_lateral.dot(f),
                        model_.tip_axial.dot(f), model_.tip_lateral.dot(v), model_.tip_axial.dot(v), F,
                        system_.friction(F, s), casing ? casing->overlap(t, f) : 0, 0.5 * f.dot(K_E_ * f),
                        0.5 * v.dot(model_.M * v), E + (casing ? casing->energy(t, f) : 0), W,
                        E - initial_energy_ - W, applied.axial, applied.lateral});
  }

private:
  const BladeModel& model_;
  const TransientSystem& system_;
  const Eigen::MatrixXd K_E_;
  double speed_, revolution_, initial_energy_;
  std::vector<TransientSample>& samples_;
};

void add_statistics(StepStatistics& total, const StepStatistics& s, bool first) {
  total.accepted += s.accepted;
  total.rejected += s.rejected;
  total.evaluations += s.evaluations;
  total.event_landings += s.event_landings;
  total.smallest_step = first ? s.smallest_step : std::min(total.smallest_step, s.smallest_step);
  total.largest_step = std::max(total.largest_step, s.largest_step);
}

// The output times of revolution r in [a, b]: evenly spaced, also in a last, partial revolution
// (the spectra assume it); the start only in the first.
std::vector<double> output_times(int r, double a, double b, double revolution, int per_rev) {
  std::vector<double> outputs;
  for (int k = (r == 0 ? 0 : 1); k <= per_rev && a + k * revolution / per_rev <= b * (1 + 1e-12); ++k) {
    outputs.push_back(k == per_rev ? b : a + k * revolution / per_rev);
  }
  return outputs;
}

}  // namespace

TransientResult run_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o) {
  const double speed = scene.operation.speed_rad_s;
  const int n = model.layout.size();
  const TransientSystem system(model, scene, o);
  const double revolution = speed > 0 ? two_pi / speed : system.pulses().period_s * scene.load.pulses_per_rev;
  const double t_end = o.revolutions * revolution;
  const OdeFunction rhs = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    dx.resize(2 * n + 1);
    system.derivative(t, x, dx);
  };

  TransientResult result;
  const Eigen::VectorXd equilibrium = rotating_equilibrium(model, speed);
  const Eigen::VectorXd start = o.initial_state ? *o.initial_state : equilibrium;
  if (start.size() != 2 * n) throw std::invalid_argument("initial state has the wrong size");
  Eigen::VectorXd x(2 * n + 1);
  x << start, 0.0;
  result.static_tip_axial_m = model.tip_axial.dot(equilibrium.head(n));
  const double initial_energy = system.energy(x);
  result.initial_vibration_energy_j = initial_energy - system.energy(equilibrium);

  std::optional<ContactEvents> contact;
  if (system.casing()) contact.emplace(*system.casing(), start);
  const std::vector<OdeEvent> events = contact ? contact->events(n) : std::vector<OdeEvent>{};
  result.fixed = transient_step(model, scene, o, t_end);
  const StepControl control = step_control(o, result.fixed);
  const Recorder sample(model, system, speed, revolution, initial_energy, result.samples);
  const int total_revs = static_cast<int>(std::ceil(o.revolutions));
  // The change of the state over each whole revolution, in the energy norm (K(Ω) is positive
  // definite below the blade's spin divergence): for a load periodic in a revolution the map over a
  // revolution is affine, x_{k+1} = Φ x_k + c, so x_{k+1} − x_k = Φ^k (x_1 − x_0) grows like max|ρ|^k
  // whatever the forced periodic response (docs/theory.md §5's cross-check with the Floquet multipliers).
  const auto energy_norm = [&](const Eigen::VectorXd& d) {
    const Eigen::MatrixXd& K = system.stiffness();
    return std::sqrt(0.5 * d.head(n).dot(K * d.head(n)) + 0.5 * d.segment(n, n).dot(model.M * d.segment(n, n)));
  };
  Eigen::VectorXd last_whole = x;
  // One revolution at a time, so long runs can report progress.
  for (int r = 0; r < total_revs; ++r) {
    const double a = r * revolution, b = std::min(t_end, (r + 1) * revolution);
    const StepStatistics s = rkf45_integrate(rhs, x, a, b, control, system.pulses().edges(a, b),
                                             output_times(r, a, b, revolution, o.samples_per_revolution),
                                             std::cref(sample), events);
    add_statistics(result.steps, s, r == 0);
    if (b == (r + 1) * revolution) {
      result.revolution_change.push_back(energy_norm(x - last_whole));
      last_whole = x;
    }
    if (o.progress) o.progress(r + 1, total_revs);
  }
  result.growth = fit_growth(result.revolution_change);
  if (contact) result.contact = contact->finished(t_end, x, n);
  return result;
}

}  // namespace bladestab
