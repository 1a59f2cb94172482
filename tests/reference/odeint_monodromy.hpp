#pragma once
// The state-transition matrix Φ(t1) of ẏ = (A₀ + φ(t) B) y, Φ(0) = I (docs/theory.md §4, the periodic system
// in the library's scaled modal form), by Boost.Odeint's controlled Runge–Kutta–Fehlberg 7(8)
// stepper: all columns at once, piece by piece between `breakpoints` (where φ jumps or kinks), the
// load read from inside the current piece. Independent of the library's Magnus and RKF45
// propagators; it shares only A₀ and B.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <boost/numeric/odeint.hpp>
#include <Eigen/Dense>

namespace reference {

inline Eigen::MatrixXd odeint_propagator(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B,
                                         const std::function<double(double)>& phi, std::vector<double> breakpoints,
                                         double t1, double tolerance) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  const Eigen::Index n = A0.rows();
  State x(n * n, 0.0);
  for (Eigen::Index i = 0; i < n; ++i) x[i * n + i] = 1;
  breakpoints.push_back(t1);
  std::sort(breakpoints.begin(), breakpoints.end());
  double from = 0;
  for (double to : breakpoints) {
    to = std::min(to, t1);
    if (to <= from) continue;
    const double inside_end = std::nextafter(to, from);
    const auto rhs = [&](const State& y, State& dy, double t) {
      dy.resize(y.size());
      Eigen::Map<Eigen::MatrixXd>(dy.data(), n, n) =
          (A0 + phi(std::min(t, inside_end)) * B) * Eigen::Map<const Eigen::MatrixXd>(y.data(), n, n);
    };
    odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_fehlberg78<State>>(tolerance, tolerance),
                               rhs, x, from, to, (to - from) / 100);
    from = to;
  }
  return Eigen::Map<Eigen::MatrixXd>(x.data(), n, n);
}

}  // namespace reference
