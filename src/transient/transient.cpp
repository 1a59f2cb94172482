#include "bladestab/transient/transient.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/transient/casing_contact.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/blade/undamped_modes.hpp"

namespace bladestab {
namespace {
}

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

TransientResult run_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o) {
  const double speed = scene.operation.speed_rad_s;
  const int n = model.layout.size();
  const PulseTrain pulses = pulse_train(scene);
  if (!pulses.frequency_known) {
    throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz");
  }
  const double revolution = speed > 0 ? two_pi / speed : pulses.period_s * scene.load.pulses_per_rev;
  const double t_end = o.revolutions * revolution;
  std::optional<CasingContact> casing;
  if (scene.load.mode == LoadMode::clearance) casing = casing_contact(model, scene);

  // ḟ' = M⁻¹(…): every matrix premultiplied once.
  const Eigen::LLT<Eigen::MatrixXd> mass(model.M);
  const Eigen::MatrixXd K = model.stiffness(speed);
  const Eigen::MatrixXd D = damping_matrix(model, scene.damping, speed);
  const Eigen::MatrixXd C = D + model.gyroscopic(speed);
  const Eigen::MatrixXd MiK = mass.solve(K), MiC = mass.solve(C), MiG = mass.solve(model.G);
  const Eigen::VectorXd Mi_cf = mass.solve(model.steady_load(speed));
  const Eigen::VectorXd Mi_axial = mass.solve(Eigen::VectorXd(model.tip_axial.transpose()));
  const Eigen::VectorXd Mi_lateral = mass.solve(Eigen::VectorXd(model.tip_lateral.transpose()));
  const double mu = scene.load.friction, cos_beta = std::cos(model.blade.beta_rad);
  const double rim_speed = speed * model.blade.tip_radius();

  const auto tip_load = [&](double t, const Eigen::VectorXd& x) {
    return casing ? casing->force(t, x.head(n)) : pulses.force(t);
  };
  const auto friction = [&](double F, const Eigen::VectorXd& x) {
    if (mu == 0 || F == 0) return 0.0;
    const double v_rel = rim_speed + cos_beta * model.tip_lateral.dot(x.segment(n, n));
    return -mu * std::abs(F) * cos_beta * std::tanh(v_rel / o.friction_velocity);
  };
  // The tip loads the equations apply for a tip load F: along the span (also the tension of the
  // geometric stiffness) and laterally (the friction); with the follower correction (docs/theory.md §5) F turns
  // with the tip slope ψ = v'(L): F cos ψ along the span, −F sin ψ added laterally.
  struct TipLoads {
    double axial = 0, lateral = 0;
  };
  const auto tip_loads = [&](double F, const Eigen::VectorXd& x) {
    TipLoads loads{F, friction(F, x)};
    if (o.follower && F != 0) {
      const double psi = model.tip_slope.dot(x.head(n));
      loads.axial = F * std::cos(psi);
      loads.lateral -= F * std::sin(psi);
    }
    return loads;
  };
  // The state is x = [f; ḟ; W], W the work done on the blade since the start: the energy balance
  // dE/dt = Ẇ = ḟᵀ(F_ax (p_u − G f) + F_lat p_v − D ḟ), E = ½ḟᵀMḟ + ½fᵀK(Ω)f − P_steadyᵀf the
  // rotating-frame energy ((55)–(58); the Coriolis forces do no work; a static tip compression is
  // in K(Ω) and P_steady, so its potential is in E). A Runge–Kutta method keeps
  // no quadratic invariant, so a step that spuriously amplifies a mode breaks E(t) − E(0) = W(t).
  const bool damped = !D.isZero(0);
  Eigen::VectorXd work(n);  // the products below, without a temporary per evaluation
  const OdeFunction rhs = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    const auto f = x.head(n), v = x.segment(n, n);
    const double F = tip_load(t, x);
    dx.resize(2 * n + 1);
    dx.head(n) = v;
    auto a = dx.segment(n, n);
    a = Mi_cf;
    a.noalias() -= MiK * f;
    a.noalias() -= MiC * v;
    dx(2 * n) = 0;
    if (damped) {
      work.noalias() = D * v;
      dx(2 * n) = -v.dot(work);
    }
    if (F == 0) return;
    const auto [axial, lateral] = tip_loads(F, x);
    work.noalias() = MiG * f;
    a += axial * (Mi_axial - work) + lateral * Mi_lateral;
    work.noalias() = model.G * v;
    dx(2 * n) += axial * (model.tip_axial.dot(v) - f.dot(work)) + lateral * model.tip_lateral.dot(v);
  };

  TransientResult result;
  const Eigen::VectorXd equilibrium = rotating_equilibrium(model, speed);
  const Eigen::VectorXd start = o.initial_state ? *o.initial_state : equilibrium;
  if (start.size() != 2 * n) throw std::invalid_argument("initial state has the wrong size");
  Eigen::VectorXd x(2 * n + 1);
  x << start, 0.0;
  result.static_tip_axial_m = model.tip_axial.dot(equilibrium.head(n));
  const Eigen::VectorXd steady = model.steady_load(speed);
  const Eigen::MatrixXd K_E = model.elastic_stiffness();
  const auto blade_energy = [&](const Eigen::VectorXd& s) {  // E, the energy the balance is about
    const auto f = s.head(n), v = s.segment(n, n);
    return 0.5 * v.dot(model.M * v) + 0.5 * f.dot(K * f) - steady.dot(f);
  };
  const double initial_energy = blade_energy(x);
  result.initial_vibration_energy_j = initial_energy - blade_energy(equilibrium);

  // Clearance mode: land on every closing and opening (g = 0) and on every deepest overlap (ġ = 0).
  std::vector<OdeEvent> events;
  double contact_start = 0;
  if (casing) {
    result.contact = ContactSummary{casing->stiffness_n_m};
    ContactSummary& c = *result.contact;
    if (casing->overlap(0, x.head(n)) > 0) c.closures = 1;  // starts in contact
    const auto rate = [&](double t, const Eigen::VectorXd& y) { return casing->overlap_rate(t, y.head(n), y.segment(n, n)); };
    events.push_back({[&](double t, const Eigen::VectorXd& y) { return casing->overlap(t, y.head(n)); },
                      [&](double t, const Eigen::VectorXd&, int direction) {
                        if (direction > 0) {
                          ++c.closures, contact_start = t;
                        } else {
                          c.contact_time_s += t - contact_start;
                        }
                      }});
    events.push_back({rate, [&](double t, const Eigen::VectorXd& y, int direction) {
                        if (direction > 0) return;  // the shallowest point
                        const double g = casing->overlap(t, y.head(n));
                        c.max_overlap_m = std::max(c.max_overlap_m, g);
                        c.peak_force_n = std::max(c.peak_force_n, casing->stiffness_n_m * g);
                      }});
  }

  StepControl control;
  control.adaptive = o.adaptive;
  control.rtol = o.tolerance;
  // Absolute floor: a millionth of the tolerance on the scale of the static stretch (≈ mm).
  control.atol = o.tolerance * 1e-6;
  result.fixed = transient_step(model, scene, o, t_end);
  // Adaptive steps never exceed that step. The error control alone cannot keep RKF45 stable on the
  // undamped stiff modes: it measures the error relative to |x|, so once a mode amplified by
  // |R(iωh)| > 1 dominates a component it sets its own allowance, and at rtol 1e-2 it was accepted
  // to grow ×1e21 in two revolutions. Below this cap the growth per unit time, ln|R(iωh)|/h, is
  // smaller still for every mode (it rises with ωh), so the whole run stays within the 1 % bound.
  (o.adaptive ? control.max_step : control.fixed_step) = result.fixed.step_s;

  const auto sample = [&](double t, const Eigen::VectorXd& s) {
    const Eigen::VectorXd f = s.head(n), v = s.segment(n, n);
    const double F = tip_load(t, s), E = blade_energy(s), W = s(2 * n);
    const TipLoads applied = tip_loads(F, s);
    result.samples.push_back({t, speed > 0 ? t * speed / two_pi : t / revolution, model.tip_lateral.dot(f),
                              model.tip_axial.dot(f), model.tip_lateral.dot(v), model.tip_axial.dot(v), F,
                              friction(F, s), casing ? casing->overlap(t, f) : 0, 0.5 * f.dot(K_E * f),
                              0.5 * v.dot(model.M * v), E + (casing ? casing->energy(t, f) : 0), W,
                              E - initial_energy - W, applied.axial, applied.lateral});
  };
  const int per_rev = o.samples_per_revolution;
  const int total_revs = static_cast<int>(std::ceil(o.revolutions));
  // The change of the state over each whole revolution, in the energy norm (K(Ω) is positive
  // definite below the blade's spin divergence): for a load periodic in a revolution the map over a
  // revolution is affine, x_{k+1} = Φ x_k + c, so x_{k+1} − x_k = Φ^k (x_1 − x_0) grows like max|ρ|^k
  // whatever the forced periodic response (docs/theory.md §5's cross-check with the Floquet multipliers).
  const auto energy_norm = [&](const Eigen::VectorXd& d) {
    return std::sqrt(0.5 * d.head(n).dot(K * d.head(n)) + 0.5 * d.segment(n, n).dot(model.M * d.segment(n, n)));
  };
  Eigen::VectorXd last_whole = x;
  // One revolution at a time, so long runs can report progress. The samples are evenly spaced, also
  // in a last, partial revolution (the spectra assume it).
  for (int r = 0; r < total_revs; ++r) {
    const double a = r * revolution, b = std::min(t_end, (r + 1) * revolution);
    std::vector<double> outputs;
    for (int k = (r == 0 ? 0 : 1); k <= per_rev && a + k * revolution / per_rev <= b * (1 + 1e-12); ++k) {
      outputs.push_back(k == per_rev ? b : a + k * revolution / per_rev);
    }
    const StepStatistics s =
        rkf45_integrate(rhs, x, a, b, control, pulses.edges(a, b), outputs, sample, events);
    result.steps.accepted += s.accepted;
    result.steps.rejected += s.rejected;
    result.steps.evaluations += s.evaluations;
    result.steps.event_landings += s.event_landings;
    result.steps.smallest_step = r == 0 ? s.smallest_step : std::min(result.steps.smallest_step, s.smallest_step);
    result.steps.largest_step = std::max(result.steps.largest_step, s.largest_step);
    if (b == (r + 1) * revolution) {
      result.revolution_change.push_back(energy_norm(x - last_whole));
      last_whole = x;
    }
    if (o.progress) o.progress(r + 1, total_revs);
  }
  result.growth = fit_growth(result.revolution_change);
  if (casing && casing->overlap(t_end, x.head(n)) > 0) result.contact->contact_time_s += t_end - contact_start;
  return result;
}

}  // namespace bladestab
