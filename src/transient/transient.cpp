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
#include "bladestab/base/numerical_error.hpp"
#include "support/work_pool.hpp"
#include "transient_parts.hpp"

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
  mu_ = scene.load.friction, in_plane_share_ = model.in_plane_share;
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
  const double v_rel = rim_speed_ + in_plane_share_ * tip_lateral_.dot(x.segment(n_, n_));
  return -mu_ * std::abs(F) * in_plane_share_ * std::tanh(v_rel / friction_velocity_);
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

// Why the fast method does not apply to this run; empty when it does.
std::string fast_method_refusal(const BladeModel& model, const Scene& scene, const TransientOptions& o) {
  if (scene.load.mode == LoadMode::clearance && o.reduction) {
    return "clearance mode steps the whole model";
  }
  if (o.follower) return "the follower load is nonlinear in the tip slope";
  if (!o.adaptive) return "fixed steps are RKF45's (54)";
  if (!(undamped_modes(model, scene.operation.speed_rad_s, 0, 1, false).omega2(0) > 0)) {
    return "K(Ω) is not positive definite at this speed";
  }
  return {};
}

// The revolution changes up to the last one resolved (ResolvedChanges).
std::vector<double> resolved_changes(const std::vector<double>& changes) {
  ResolvedChanges resolved;
  std::size_t last = 0;
  for (std::size_t k = 0; k < changes.size(); ++k) {
    if (resolved.add(changes[k])) last = k + 1;
  }
  return {changes.begin(), changes.begin() + static_cast<std::ptrdiff_t>(last)};
}

// The growth per revolution of the run's revolution changes.
GrowthFit fit_run_growth(const TransientResult& r) {
  if (r.method == TransientMethod::fast && !r.contact && r.revolution_change.empty()) {
    // The fast method in force mode carries one whole revolution's change on: it needs one.
    GrowthFit none;
    none.omitted = fmt::format("0 whole revolutions{}; the growth needs 1", r.stopped ? " before the stop" : "");
    return none;
  }
  if (r.continued_log_change.empty() && !r.revolution_change.empty() && resolved_changes(r.revolution_change).empty()) {
    // No revolution changed the state beyond rounding (no load, or a load that excites nothing).
    GrowthFit none;
    none.omitted = fmt::format("the state did not change over its {} whole revolutions (no vibration): nothing "
                               "grows or decays", r.revolution_change.size());
    return none;
  }
  GrowthFit fit = !r.continued_log_change.empty() ? fit_continued_growth(r.continued_log_change)
                  : r.stopped                     ? latest_growth(resolved_changes(r.revolution_change))
                                                  : fit_growth(resolved_changes(r.revolution_change));
  // The fast method's contact propagators' own error, once per piece of a revolution.
  if (r.method == TransientMethod::fast) fit.error_estimate += fit.growth * r.exact.contact_pieces * r.exact.contact_error;
  // Not below the rounding of a growth taken through a revolution's products in doubles
  // (growth_rounding, response_analysis.hpp).
  fit.error_estimate = std::max(fit.error_estimate, growth_rounding * fit.growth);
  return fit;
}

}  // namespace

TransientResult run_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o) {
  const std::string refusal = o.method == TransientMethod::fast ? fast_method_refusal(model, scene, o) : "";
  if (o.method == TransientMethod::rkf45 || !refusal.empty()) {
    TransientResult r = detail::run_rkf45_transient(model, scene, o);
    r.fallback = refusal;
    r.growth = fit_run_growth(r);
    return r;
  }
  const double check_time = o.self_check && !o.reduction ? detail::check_stretch(scene, o) : 0;
  // The reference runs beside the fast run where there are threads for it; a fast run that fails
  // stops it (declared first, the flag outlives the pool that polls it).
  Cancellation fast_run_failed;
  std::optional<WorkPool<detail::ReferenceRun>> reference;
  if (check_time > 0) {
    reference.emplace(o.threads, 1, [&](std::size_t) {
      return detail::reference_run(model, scene, o, check_time, &fast_run_failed);
    });
  }
  Eigen::VectorXd check_state;
  TransientResult r;
  try {
    r = scene.load.mode == LoadMode::clearance
            ? detail::run_fast_clearance_transient(model, scene, o, check_time, check_state)
            : detail::run_fast_transient(model, scene, o, check_time, check_state);
  } catch (...) {
    fast_run_failed.cancel();
    throw;
  }
  if (reference) {
    detail::ReferenceRun checked_against = reference->get(0);
    double checked_until = check_time;
    if (check_state.size() == 0) {  // stopped within the stretch: the check covers what ran
      if (!r.stopped) throw std::logic_error("transient: the fast run ended before its self-check's time");
      checked_until = r.stopped->revolution * two_pi / scene.operation.speed_rad_s;
      check_state = r.final_state;
      checked_against = detail::reference_run(model, scene, o, checked_until);
    }
    r.self_check = detail::self_check(model, scene, o, checked_until, check_state, checked_against);
    if (!(r.self_check->difference <= r.self_check->allowed)) {
      throw NumericalError(fmt::format("the fast method's state at revolution {:.4g} differs from {}'s (rtol {:g}) by "
                                       "{:.3g} of the vibration, beyond the stated {:.3g}",
                                       r.self_check->until_revolutions, r.self_check->reference,
                                       r.self_check->reference_tolerance,
                                       r.self_check->difference, r.self_check->allowed));
    }
  }
  r.growth = fit_run_growth(r);
  return r;
}

std::string energy_balance_unchecked(const TransientResult& r) {
  if (r.method != TransientMethod::fast || r.contact || r.exact.free_exponentials > 0) return {};
  return "the run is in contact throughout, with no free flight to balance (the contact propagators are checked "
         "by their step doubling and the self-check)";
}

}  // namespace bladestab
