#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/transient/exact_stepping.hpp"
#include "bladestab/transient/transient_system.hpp"
#include "transient_parts.hpp"

namespace bladestab::detail {
namespace {

// A time the exact stepping lands on, and what happens there.
struct Landing {
  double t = 0;
  bool output = false, whole_revolution = false, check = false;
  bool edge = false;  // a pulse edge or kink: its time is kept exactly when landings merge
};

// Every output time, whole revolution, pulse edge and kink of [0, t_end], and the check time, in
// order; landings closer than 1e-9 of a pulse period (or of a revolution, if that is shorter) are
// one (an output time that falls on a pulse edge up to rounding must not leave a sliver of an
// interval).
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

// After a stop: the change of the state over the last whole revolution, z(T_K) − z(T_{K−1}),
// carried on through `count` more revolutions by that revolution's own propagators (`revolution`:
// its landings), and its energy norm after each (½|y|² is the energy in these coordinates). Only
// the homogeneous part acts on a change (its last entry is 0), so this continues the revolution
// changes of the linear equations as the run would have without the small-deflection limit.
std::vector<double> continued_changes(ExactStepper& stepper, Eigen::VectorXd change, const std::vector<Landing>& revolution,
                                      double start, int count) {
  std::vector<double> norms;
  double ignored_work = 0, scale = change.norm() / std::sqrt(2.0);
  change /= scale;
  // Each revolution from a unit change, its norm times the norm before: no overflow until the
  // product passes 1e300, where the continuation ends.
  for (int k = 0; k < count && scale < 1e300; ++k) {
    double t = start;
    for (const Landing& l : revolution) {
      stepper.step(t, l.t, change, ignored_work);
      t = l.t;
    }
    const double norm = change.norm();
    change /= norm;
    scale *= norm;
    norms.push_back(scale);
  }
  return norms;
}

}  // namespace

TransientResult run_fast_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o,
                                   double check_time, Eigen::VectorXd& check_state) {
  const int n = model.layout.size();
  const TransientSystem system(model, scene, o);
  ExactStepper stepper(model, scene, o.contact_tolerance, o.reduction);
  TransientResult result;
  result.method = TransientMethod::fast;
  RunStart begin = run_start(model, scene, system, o, result);
  const Recorder record = begin.recorder(model, system, o, result);
  Eigen::VectorXd x = begin.x, z = stepper.modal(x.head(2 * n)), last_whole = x, z_whole = z, z_before = z;
  double work = 0, t = 0;
  record(0, x);
  const bool friction = scene.load.friction != 0;
  const int total_revs = static_cast<int>(std::ceil(o.revolutions));
  const std::vector<Landing> all = landings(stepper, begin, o, check_time);
  std::vector<double> times{0};
  for (const Landing& l : all) times.push_back(l.t);
  stepper.prepare(times, o.threads);
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
    if (contact && friction) check_sliding(stepper, z, t, o);
    if (l.check) check_state = x.head(2 * n);
    if (l.output) {
      if ((result.stopped = record(t, x))) break;
    }
    // Without the small-deflection stop an unstable response would overflow: stop where its
    // vibration energy ½|y|² passes 1e200 J (the growth is carried on from there).
    if (!(z.head(2 * stepper.modes()).squaredNorm() < 4e200)) {
      result.stopped = TransientStop{t / begin.revolution, "the linear response passed 1e200 J, near the range of doubles"};
      break;
    }
    if (l.whole_revolution) {
      result.revolution_change.push_back(energy_norm(system.stiffness(), model.M, x - last_whole));
      last_whole = x;
      z_before = z_whole, z_whole = z;
      if (o.progress) o.progress(static_cast<int>(result.revolution_change.size()), total_revs);
    }
  }
  const int whole = static_cast<int>(result.revolution_change.size());
  if ((result.stopped || o.continue_growth) && whole >= 1) {
    std::vector<Landing> last;
    const double a = (whole - 1) * begin.revolution, b = whole * begin.revolution;
    std::copy_if(all.begin(), all.end(), std::back_inserter(last), [&](const Landing& l) { return l.t > a && l.t <= b; });
    Eigen::VectorXd change = z_whole - z_before;
    change(change.size() - 1) = 0;  // the augmentation's constant, not a change (z is modal: 2·modes + 1)
    result.continued_change = continued_changes(stepper, change, last, a, growth_continuation);
  }
  result.final_state = x.head(2 * n);
  result.exact = stepper.statistics();
  return result;
}

}  // namespace bladestab::detail
