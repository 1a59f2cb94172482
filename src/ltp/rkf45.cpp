#include "bladestab/ltp/rkf45.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/tools/roots.hpp>
#include <fmt/format.h>

namespace bladestab {
namespace {

// Fehlberg's coefficients.
constexpr double c2 = 1.0 / 4, c3 = 3.0 / 8, c4 = 12.0 / 13, c6 = 1.0 / 2;
constexpr double a21 = 1.0 / 4;
constexpr double a31 = 3.0 / 32, a32 = 9.0 / 32;
constexpr double a41 = 1932.0 / 2197, a42 = -7200.0 / 2197, a43 = 7296.0 / 2197;
constexpr double a51 = 439.0 / 216, a52 = -8.0, a53 = 3680.0 / 513, a54 = -845.0 / 4104;
constexpr double a61 = -8.0 / 27, a62 = 2.0, a63 = -3544.0 / 2565, a64 = 1859.0 / 4104, a65 = -11.0 / 40;
constexpr double b1 = 16.0 / 135, b3 = 6656.0 / 12825, b4 = 28561.0 / 56430, b5 = -9.0 / 50, b6 = 2.0 / 55;  // 5th order
constexpr double d1 = 25.0 / 216, d3 = 1408.0 / 2565, d4 = 2197.0 / 4104, d5 = -1.0 / 5;                  // 4th order

struct Step {
  Eigen::VectorXd x, error;
};

// The slopes k2…k6 and the stage argument of a step, kept from step to step: a step allocates nothing.
struct Stages {
  Eigen::VectorXd k2, k3, k4, k5, k6, argument;
};

// One Fehlberg step from (t, x) with slope k1 = f(t, x), into s.
void fehlberg_step(const OdeFunction& f, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& k1, double h,
                   Stages& k, Step& s, StepStatistics& stats) {
  k.argument = x + h * a21 * k1;
  f(t + c2 * h, k.argument, k.k2);
  k.argument = x + h * (a31 * k1 + a32 * k.k2);
  f(t + c3 * h, k.argument, k.k3);
  k.argument = x + h * (a41 * k1 + a42 * k.k2 + a43 * k.k3);
  f(t + c4 * h, k.argument, k.k4);
  k.argument = x + h * (a51 * k1 + a52 * k.k2 + a53 * k.k3 + a54 * k.k4);
  f(t + h, k.argument, k.k5);
  k.argument = x + h * (a61 * k1 + a62 * k.k2 + a63 * k.k3 + a64 * k.k4 + a65 * k.k5);
  f(t + c6 * h, k.argument, k.k6);
  stats.evaluations += 5;
  s.x = x + h * (b1 * k1 + b3 * k.k3 + b4 * k.k4 + b5 * k.k5 + b6 * k.k6);
  s.error = h * ((b1 - d1) * k1 + (b3 - d3) * k.k3 + (b4 - d4) * k.k4 + (b5 - d5) * k.k5 + b6 * k.k6);
}

// Cubic Hermite interpolation on [t0, t0 + h].
Eigen::VectorXd hermite(double t0, double h, const Eigen::VectorXd& x0, const Eigen::VectorXd& f0,
                        const Eigen::VectorXd& x1, const Eigen::VectorXd& f1, double t) {
  const double s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * f0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * h * f1;
}

// The earliest zero of an event function inside (t0, t0 + h] on the dense output: {index, time,
// direction}, index −1 if none. `start` and `end` are the values at both ends of the step (at the end
// the left-hand limit: the piece of the system the step integrated). A zero of event `landed` within
// 1e-6 of the step from t0 is the one the previous step landed on, seen again through rounding.
struct EventZero {
  int index = -1;
  double t = 0;
  int direction = 0;
};

EventZero first_event(const std::vector<OdeEvent>& events, int landed, const std::vector<double>& start,
                      const std::vector<double>& end, double t0, double h, const Eigen::VectorXd& x0,
                      const Eigen::VectorXd& f0, const Eigen::VectorXd& x1, const Eigen::VectorXd& f1) {
  EventZero first{-1, t0 + h, 0};
  for (std::size_t i = 0; i < events.size(); ++i) {
    const double a = start[i], b = end[i];
    if (!(a * b < 0)) continue;
    const auto g = [&](double t) { return events[i].value(t, hermite(t0, h, x0, f0, x1, f1, t)); };
    std::uintmax_t iterations = 100;
    const auto bracket = boost::math::tools::toms748_solve(
        g, t0, t0 + h, a, b, [h](double lo, double hi) { return hi - lo <= 1e-13 * h; }, iterations);
    const double t = bracket.second;  // the side past the crossing
    const double skip = static_cast<int>(i) == landed ? 1e-6 * h : 0;
    if (t - t0 > skip && t < first.t) first = {static_cast<int>(i), t, b > 0 ? 1 : -1};
  }
  return first;
}

}  // namespace

std::complex<double> rkf45_stability_function(std::complex<double> z) {
  // Stage values for x' = λx, x(0) = 1: k_i = λ(1 + h Σ_j a_ij k_j), solved in stage order.
  using C = std::complex<double>;
  const C g1 = 1.0;
  const C g2 = 1.0 + z * a21 * g1;
  const C g3 = 1.0 + z * (a31 * g1 + a32 * g2);
  const C g4 = 1.0 + z * (a41 * g1 + a42 * g2 + a43 * g3);
  const C g5 = 1.0 + z * (a51 * g1 + a52 * g2 + a53 * g3 + a54 * g4);
  const C g6 = 1.0 + z * (a61 * g1 + a62 * g2 + a63 * g3 + a64 * g4 + a65 * g5);
  return 1.0 + z * (b1 * g1 + b3 * g3 + b4 * g4 + b5 * g5 + b6 * g6);
}

namespace {

// The breakpoints in (t0, t1], sorted, ending with t1.
std::vector<double> breakpoints_within(std::vector<double> breakpoints, double t0, double t1) {
  breakpoints.push_back(t1);
  std::sort(breakpoints.begin(), breakpoints.end());
  breakpoints.erase(std::remove_if(breakpoints.begin(), breakpoints.end(),
                                   [&](double b) { return b <= t0 || b > t1; }),
                    breakpoints.end());
  return breakpoints;
}

// The first step: the fixed one, the one given, or from the initial slope k1 a step over which x
// changes by about rtol·|x| + atol.
double first_step(const StepControl& control, const Eigen::VectorXd& x, const Eigen::VectorXd& k1, double span) {
  double h = control.adaptive ? control.first_step : control.fixed_step;
  if (control.adaptive && h <= 0) {
    const Eigen::ArrayXd scale = control.atol + control.rtol * x.array().abs();
    const double slope = (k1.array() / scale).abs().maxCoeff();
    h = slope > 0 ? std::pow(1 / slope, 1.0 / 5) * 1e-2 : span * 1e-3;
    h = std::min(h, span);
  }
  return h;
}

// The adaptive control of a step `step` from (t, x) to s: whether it is accepted (its embedded
// error within atol + rtol·|x|), and the next step h either way.
bool step_accepted(const StepControl& control, const Eigen::VectorXd& x, const Step& s, double step, double t,
                   double span, double& h, StepStatistics& stats) {
  const double err =
      (s.error.array().abs() / (control.atol + control.rtol * x.array().abs().max(s.x.array().abs()))).maxCoeff();
  const double factor = err > 0 ? std::clamp(0.9 * std::pow(err, -0.2), 0.2, 5.0) : 5.0;
  if (err <= 1) {
    h = step * factor;
    return true;
  }
  ++stats.rejected;  // also for a NaN error
  h = step * std::min(factor, 0.9);
  if (h < 1e-14 * std::max(std::abs(t), span)) {
    throw std::runtime_error(fmt::format("RKF45 step size underflow at t = {:.9g} s", t));
  }
  return false;
}

}  // namespace

StepStatistics rkf45_integrate(const OdeFunction& f, Eigen::VectorXd& x, double t0, double t1,
                               const StepControl& control, std::vector<double> breakpoints,
                               const std::vector<double>& outputs, const OdeObserver& observer,
                               const std::vector<OdeEvent>& events) {
  StepStatistics stats;
  breakpoints = breakpoints_within(std::move(breakpoints), t0, t1);
  auto next_break = breakpoints.begin();
  auto next_output = std::lower_bound(outputs.begin(), outputs.end(), t0);

  Eigen::VectorXd k1;
  f(t0, x, k1);
  stats.evaluations = 1;
  std::vector<double> event_start(events.size()), event_end(events.size());
  const auto evaluate_events = [&](double t, const Eigen::VectorXd& y, std::vector<double>& values) {
    for (std::size_t i = 0; i < events.size(); ++i) values[i] = events[i].value(t, y);
  };
  evaluate_events(t0, x, event_start);
  int landed_event = -1;
  while (next_output != outputs.end() && *next_output <= t0) observer(*next_output++, x);

  const double span = t1 - t0;
  double h = first_step(control, x, k1, span);
  double t = t0;
  stats.smallest_step = span;
  Stages stages;
  Step s;
  Eigen::VectorXd k_new;
  while (t < t1) {
    const double to_break = *next_break - t;
    bool lands = false;
    double step = h;
    if (control.adaptive && control.max_step > 0) step = std::min(step, control.max_step);
    if (step >= to_break * (1 - 1e-12)) step = to_break, lands = true;
    fehlberg_step(f, t, x, k1, step, stages, s, stats);
    if (control.adaptive && !step_accepted(control, x, s, step, t, span, h, stats)) continue;
    double t_new = lands ? *next_break : t + step;
    f(t_new, s.x, k_new);
    ++stats.evaluations;
    evaluate_events(std::nextafter(t_new, t), s.x, event_end);
    const EventZero event = first_event(events, landed_event, event_start, event_end, t, t_new - t, x, k1, s.x, k_new);
    if (event.index >= 0) {  // redo the step to end on the event (shorter, so within tolerance too)
      step = event.t - t;
      fehlberg_step(f, t, x, k1, step, stages, s, stats);
      t_new = event.t;
      lands = false;
      f(t_new, s.x, k_new);
      ++stats.evaluations;
      ++stats.event_landings;
    }
    while (next_output != outputs.end() && *next_output <= t_new) {
      observer(*next_output, hermite(t, t_new - t, x, k1, s.x, k_new, *next_output));
      ++next_output;
    }
    ++stats.accepted;
    stats.smallest_step = std::min(stats.smallest_step, step);
    stats.largest_step = std::max(stats.largest_step, step);
    t = t_new;
    x.swap(s.x);
    k1.swap(k_new);
    evaluate_events(t, x, event_start);
    landed_event = event.index;
    if (event.index >= 0 && events[event.index].on_zero) events[event.index].on_zero(t, x, event.direction);
    for (std::size_t i = 0; lands && event.index < 0 && i < events.size(); ++i) {  // a jump at a breakpoint
      if (event_end[i] * event_start[i] < 0 && events[i].on_zero) events[i].on_zero(t, x, event_start[i] > 0 ? 1 : -1);
    }
    if (lands) {
      ++next_break;
      // After a landing the adaptive step resumes from its own estimate; the fixed one as set.
      if (!control.adaptive) h = control.fixed_step;
    }
  }
  return stats;
}

}  // namespace bladestab
