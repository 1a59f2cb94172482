#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/transient/exact_stepping.hpp"
#include "bladestab/transient/transient_system.hpp"
#include "transient_parts.hpp"

namespace bladestab::detail {
namespace {

// The friction's sign is taken as +1 (exact_stepping.hpp): refuse a state where tanh(v_rel/ε)
// would not be 1 to the unit roundoff.
void check_sliding(const ExactStepper& stepper, const Eigen::VectorXd& z, double t, const TransientOptions& o) {
  const double v_rel = stepper.sliding_speed(z);
  if (!(v_rel >= 20 * o.friction_velocity)) {
    throw NumericalError(fmt::format("exact stepping: at t = {:.6g} s the tip slides past the casing at {:.4g} m/s, "
                                     "where the friction's direction is not fixed; use the rkf45 method",
                                     t, v_rel));
  }
}

}  // namespace

TransientResult run_fast_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o,
                                   double check_time, Eigen::VectorXd& check_state) {
  const int n = model.layout.size();
  const TransientSystem system(model, scene, o);
  ExactStepper stepper(model, scene, o.contact_tolerance, o.reduction, o.piece_work_flops);
  TransientResult result;
  result.method = TransientMethod::fast;
  RunStart begin = run_start(model, scene, system, o, result);
  const Recorder record = begin.recorder(model, system, o, result);
  Eigen::VectorXd x = begin.x, z = stepper.modal(x.head(2 * n)), z_whole = z;
  // The latest revolution change still resolved (ResolvedChanges, transient.hpp): a decaying change
  // reaches the rounding of the periodic state it is taken from, then exactly 0.
  Eigen::VectorXd resolved_change;
  ResolvedChanges resolved;
  double work = 0, t = 0;
  record(0, x);
  LandingLog log(model, system, record, o, result, x, check_state);
  const bool friction = scene.load.friction != 0;
  const std::vector<Landing> all = landings(stepper, begin, o, check_time);
  std::vector<double> times{0};
  for (const Landing& l : all) times.push_back(l.t);
  stepper.prepare(times, o.threads, o.contact_progress);
  for (const Landing& l : all) {
    if (l.t <= t) continue;  // the start
    const double energy_before = system.energy(x);
    const bool contact = stepper.step(t, l.t, z, work);
    t = l.t;
    x << stepper.physical(z), 0.0;
    // In contact the work is the energy's change (exact_stepping.hpp: the Magnus propagator's
    // accuracy is its step doubling's, and the self-check's); in free flight only damping works.
    if (contact) work += system.energy(x) - energy_before;
    x(2 * n) = work;
    if (contact && friction && !o.hold_friction_direction) check_sliding(stepper, z, t, o);
    if (log.sample(l, t, x)) break;
    // Without the small-deflection stop an unstable response would overflow: stop where its
    // vibration energy ½|y|² passes 1e200 J (the growth is carried on from there).
    if (!(z.head(2 * stepper.modes()).squaredNorm() < 4e200)) {
      result.stopped = TransientStop{t / begin.revolution, "the linear response passed 1e200 J, near the range of doubles"};
      break;
    }
    if (log.revolution(l, x)) {
      const Eigen::VectorXd change = z - z_whole;
      z_whole = z;
      if (resolved.add(change.norm())) resolved_change = change;
    }
  }
  const int whole = static_cast<int>(result.revolution_change.size());
  if (whole >= 1 && resolved_change.size() > 0 && revolutions_repeat(stepper.pulses(), begin.revolution, whole)) {
    // The last whole revolution's landings, after the (whole − 1)-th whole revolution's and up to the
    // whole-th, found by their flags: a time window would drop the revolution's end where an output
    // time sums to it with rounding (in a run that goes on past it).
    std::vector<Landing> last;
    double a = 0;
    int seen = 0;
    for (const Landing& l : all) {
      if (seen == whole - 1 && l.t > a) last.push_back(l);
      if (l.whole_revolution && ++seen == whole - 1) a = l.t;
      if (seen == whole) break;
    }
    resolved_change(resolved_change.size() - 1) = 0;  // the augmentation's constant, not a change (z is modal: 2·modes + 1)
    // Every revolution of the train has the last one's propagators: the resolved change is carried
    // on by them whichever revolution it came from.
    result.continued_log_change = continue_change(stepper, resolved_change, last, a);
  }
  result.final_state = x.head(2 * n);
  result.exact = stepper.statistics();
  return result;
}

}  // namespace bladestab::detail
