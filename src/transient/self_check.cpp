// The fast method's self-check (transient.hpp SelfCheck, docs/theory.md §5.8): its state at the end
// of a stretch through the first contact against an independent integration of the whole
// equations (transient_system.hpp) at rtol 1e-10. The reference shares no part of the method it
// checks: in force mode the fast run has no Runge–Kutta step, and Boost.Odeint's
// Runge–Kutta–Fehlberg 7(8) integrates from pulse edge to pulse edge; in clearance mode the fast
// run's contacts are RKF78's, and the paper's RKF45 (rkf45_transient.cpp) is the reference.
#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/numeric/odeint/integrate/integrate_adaptive.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>

#include "bladestab/base/constants.hpp"
#include "transient_parts.hpp"

namespace bladestab::detail {
namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::vector<double>;

constexpr double reference_tolerance = 1e-10;

// [f; ḟ] at `until` from the run's start by RKF78, its steps landing on every pulse edge (where the
// load or its rate jumps); atol as RKF45's, a millionth of rtol on the scale of the static stretch.
Eigen::VectorXd rkf78_state(const BladeModel& model, const Scene& scene, const TransientOptions& o, double until,
                            const Cancellation* stop) {
  const TransientSystem system(model, scene, o);
  TransientResult ignored;
  const Eigen::VectorXd start = run_start(model, scene, system, o, ignored).x;
  OdeState x(start.data(), start.data() + start.size());
  // The stages at a piece's end take the load's left-hand limit: the piece the step integrates
  // (the pulse window is half-open, so at its end the force is already off).
  double last_inside = 0;
  const auto rhs = [&system, &last_inside](const OdeState& in, OdeState& out, double t) {
    out.resize(in.size());
    const Eigen::Map<const Eigen::VectorXd> state(in.data(), static_cast<Eigen::Index>(in.size()));
    Eigen::Map<Eigen::VectorXd> rate(out.data(), static_cast<Eigen::Index>(out.size()));
    system.derivative(std::min(t, last_inside), state, rate);
  };
  const auto poll = [stop](const OdeState&, double) {
    if (stop && stop->cancelled()) throw WorkCancelled();
  };
  std::vector<double> stops = system.pulses().edges(0, until);
  stops.push_back(until);
  double t = 0;
  for (const double end : stops) {
    if (!(end > t)) continue;
    last_inside = std::nextafter(end, t);
    auto stepper = odeint::make_controlled(1e-6 * reference_tolerance, reference_tolerance,
                                           odeint::runge_kutta_fehlberg78<OdeState>());
    odeint::integrate_adaptive(stepper, rhs, x, t, end, (end - t) / 64, poll);
    t = end;
  }
  return Eigen::Map<const Eigen::VectorXd>(x.data(), 2 * model.layout.size());
}

Eigen::VectorXd rkf45_state(const BladeModel& model, const Scene& scene, const TransientOptions& o, double until) {
  TransientOptions reference = o;
  reference.method = TransientMethod::rkf45;
  reference.revolutions = until * scene.operation.speed_rad_s / two_pi;
  reference.tolerance = reference_tolerance;
  reference.progress = nullptr;
  reference.max_lateral_over_length = HUGE_VAL;
  return run_rkf45_transient(model, scene, reference).final_state;
}

}  // namespace

double check_stretch(const Scene& scene, const TransientOptions& o) {
  const PulseTrain pulses = pulse_train(scene);
  const double revolution = two_pi / scene.operation.speed_rad_s;
  return std::min(o.revolutions, std::min(pulses.contact_time_s / revolution, 0.1) + 0.02) * revolution;
}

ReferenceRun reference_run(const BladeModel& model, const Scene& scene, const TransientOptions& o, double check_time,
                           const Cancellation* stop) {
  ReferenceRun run;
  const bool clearance = scene.load.mode == LoadMode::clearance;
  run.method = clearance ? "rkf45" : "rkf78";
  run.state = clearance ? rkf45_state(model, scene, o, check_time) : rkf78_state(model, scene, o, check_time, stop);
  return run;
}

SelfCheck self_check(const BladeModel& model, const Scene& scene, const TransientOptions& o, double check_time,
                     const Eigen::VectorXd& fast_state, const ReferenceRun& reference) {
  SelfCheck check;
  check.until_revolutions = check_time * scene.operation.speed_rad_s / two_pi;
  check.reference = reference.method;
  check.reference_tolerance = reference_tolerance;
  const Eigen::MatrixXd K = model.stiffness(scene.operation.speed_rad_s);
  const Eigen::VectorXd equilibrium = rotating_equilibrium(model, scene.operation.speed_rad_s);
  const Eigen::VectorXd start = o.initial_state ? *o.initial_state : equilibrium;
  // The reference controls its error relative to the whole state, f_eq included: it resolves a
  // vibration only down to its tolerance of that state, the scale of a feather touch's check.
  const double whole = energy_norm(K, model.M, reference.state);
  const double vibration = std::max(energy_norm(K, model.M, start - equilibrium),
                                    energy_norm(K, model.M, reference.state - equilibrium));
  const double scale = std::max(vibration, reference_tolerance * whole);
  check.relative_to_resolution = vibration < reference_tolerance * whole;
  // A blade the load leaves at rest in the zero state (no axial field) has no scale at all: its
  // difference counts only if it is not zero.
  const double difference = energy_norm(K, model.M, fast_state - reference.state);
  check.difference = scale > 0 ? difference / scale : difference > 0 ? HUGE_VAL : 0.0;
  // Each contact piece's propagator within the tolerance, the reference's local errors within its
  // own of the whole state, and a margin of 10 for the pieces and steps they add up over.
  check.reference_part = scale > 0 ? 10 * reference_tolerance * whole / scale : 0.0;
  check.allowed = 10 * o.contact_tolerance + check.reference_part;
  return check;
}

}  // namespace bladestab::detail
