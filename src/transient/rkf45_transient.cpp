#include "transient_parts.hpp"

#include <cmath>
#include <optional>

#include "bladestab/base/constants.hpp"
#include "bladestab/transient/casing_contact.hpp"
#include "bladestab/transient/transient_system.hpp"

namespace bladestab::detail {
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

void add_statistics(StepStatistics& total, const StepStatistics& s, bool first) {
  total.accepted += s.accepted;
  total.rejected += s.rejected;
  total.evaluations += s.evaluations;
  total.event_landings += s.event_landings;
  total.smallest_step = first ? s.smallest_step : std::min(total.smallest_step, s.smallest_step);
  total.largest_step = std::max(total.largest_step, s.largest_step);
}

// The Recorder's stop, thrown out of the integrator's observer.
struct StopRun {
  TransientStop stop;
  Eigen::VectorXd state;
  double time_s;
};

}  // namespace

TransientResult run_rkf45_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o) {
  const int n = model.layout.size();
  const TransientSystem system(model, scene, o);
  const OdeFunction rhs = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    dx.resize(2 * n + 1);
    system.derivative(t, x, dx);
  };
  TransientResult result;
  RunStart begin = run_start(model, scene, system, o, result);
  Eigen::VectorXd& x = begin.x;
  std::optional<ContactEvents> contact;
  if (system.casing()) contact.emplace(*system.casing(), x.head(2 * n));
  const std::vector<OdeEvent> events = contact ? contact->events(n) : std::vector<OdeEvent>{};
  result.fixed = transient_step(model, scene, o, begin.t_end);
  const StepControl control = step_control(o, result.fixed);
  const Recorder record = begin.recorder(model, system, o, result);
  const OdeObserver observe = [&record](double t, const Eigen::VectorXd& s) {
    if (std::optional<TransientStop> stop = record(t, s)) throw StopRun{*stop, s, t};
  };
  const int total_revs = static_cast<int>(std::ceil(o.revolutions));
  Eigen::VectorXd last_whole = x;
  double t_last = begin.t_end;
  // One revolution at a time, so long runs can report progress.
  for (int r = 0; r < total_revs && !result.stopped; ++r) {
    const double a = r * begin.revolution, b = std::min(begin.t_end, (r + 1) * begin.revolution);
    try {
      const StepStatistics s = rkf45_integrate(rhs, x, a, b, control, system.pulses().edges(a, b),
                                               output_times(r, a, b, begin.revolution, o.samples_per_revolution),
                                               observe, events);
      add_statistics(result.steps, s, r == 0);
    } catch (const StopRun& stop) {
      result.stopped = stop.stop;
      x = stop.state;
      t_last = stop.time_s;
      break;
    }
    if (b == (r + 1) * begin.revolution) {
      result.revolution_change.push_back(energy_norm(system.stiffness(), model.M, x - last_whole));
      last_whole = x;
    }
    if (o.progress) o.progress(r + 1, total_revs);
  }
  result.final_state = x.head(2 * n);
  if (contact) result.contact = contact->finished(t_last, x, n);
  return result;
}

}  // namespace bladestab::detail
