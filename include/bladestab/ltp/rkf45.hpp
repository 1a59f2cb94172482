#pragma once
// Runge–Kutta–Fehlberg 4(5) (docs/theory.md §5; Fehlberg's six-stage pair, nodes 0, 1/4, 3/8, 12/13, 1, 1/2)
// for ẋ = f(t, x). Knows nothing of blades: the system is a function, as in Boost.Odeint, so a
// higher-order pair or an implicit method can stand beside it.
//  - adaptive: the step is chosen so the embedded error estimate stays below rtol·|x| + atol
//    (the fifth-order solution is propagated, the fourth-order one only measures the error);
//  - fixed: a constant step (the paper's (54)), shortened only to land on a breakpoint.
// Steps land exactly on every breakpoint (pulse edges: F and F' jump there). Output between
// steps is dense: cubic Hermite interpolation from the values and slopes at both ends.
#include <complex>
#include <functional>
#include <vector>

#include <Eigen/Dense>

namespace bladestab {

using OdeFunction = std::function<void(double t, const Eigen::VectorXd& x, Eigen::VectorXd& dxdt)>;
// Called at each output time with the interpolated state.
using OdeObserver = std::function<void(double t, const Eigen::VectorXd& x)>;

// A function of the state whose zeros the steps land on, and what to do there (direction +1 where
// it rises through zero, −1 where it falls). A jump through zero at a breakpoint counts as a zero.
struct OdeEvent {
  std::function<double(double t, const Eigen::VectorXd& x)> value;
  std::function<void(double t, const Eigen::VectorXd& x, int direction)> on_zero;  // may be empty
};

struct StepControl {
  bool adaptive = true;
  double rtol = 1e-8, atol = 1e-14;
  double fixed_step = 0;   // fixed mode
  double first_step = 0;   // adaptive: 0 = choose from the initial slope
  double max_step = 0;     // adaptive: 0 = unlimited
};

struct StepStatistics {
  long accepted = 0, rejected = 0, evaluations = 0;
  long event_landings = 0;
  double smallest_step = 0, largest_step = 0;
};

// Integrates x from t0 to t1. `breakpoints` (any order, outside (t0, t1) ignored) are landed on;
// `outputs` (increasing) are reported to `observer` by dense output; `events` are landed on. Returns
// the statistics; x holds x(t1). Throws std::runtime_error if the step size underflows.
StepStatistics rkf45_integrate(const OdeFunction& f, Eigen::VectorXd& x, double t0, double t1,
                               const StepControl& control, std::vector<double> breakpoints,
                               const std::vector<double>& outputs, const OdeObserver& observer,
                               const std::vector<OdeEvent>& events = {});

// The stability function of the propagated (fifth-order) formula: one step of ẋ = λx multiplies x
// by R(hλ) = 1 + hλ bᵀ(I − hλA)⁻¹1. On the imaginary axis |R(iy)| exceeds 1 for 0 < y < 2.3
// (1 + 1.7e-4 at y = π/4): an undamped mode stepped with a fixed h grows by |R(iωh)| per step.
std::complex<double> rkf45_stability_function(std::complex<double> h_lambda);

}  // namespace bladestab
