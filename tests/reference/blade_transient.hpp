#pragma once
// An independent time integration of the blade under a tip load, for comparison with
// run_transient: Boost.Odeint's Dormand–Prince 5(4) with dense output, at tight tolerances (1e-10), on the
// equation of motion written out here from the model's matrices (docs/theory.md §2, (23), (40); §5):
//
//   M f̈ + C ḟ + (K(Ω) + F(t) G) f = P_steady + F(t) p_u + R(t) p_v,
//   R = −μ |F| cos β · sign(ΩR + cos β · v̇(L))      (docs/theory.md §1: Coulomb friction μ|F|, its component
//                                                    along ê_n μ|F| cos β, against the tip's sliding
//                                                    past the casing, active only while F ≠ 0)
//
// with the exact sign (the library regularizes it with tanh(v/ε)). It steps from edge to edge of
// the load, so no step straddles a jump of F, and it integrates the work of the tip load and of
// the friction on the blade alongside, W_ax = ∫ F ḟᵀ(p_u − G f) dt and W_R = ∫ R v̇(L) dt.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <boost/numeric/odeint.hpp>
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"

namespace reference {

struct BladeLoadCase {
  double speed_rad_s = 0;
  Eigen::MatrixXd C;                    // damping + gyroscopic, Ω C_G1
  std::function<double(double)> force;  // F(t) [N], compressive < 0
  std::vector<double> edges;            // where F jumps or kinks
  double friction = 0;                  // μ
};

struct TipHistory {
  std::vector<double> lateral, axial, lateral_velocity;  // v(L), u(L), v̇(L) at the requested times
  std::vector<double> load_work, friction_work;          // W_ax, W_R since t = 0
  std::vector<Eigen::VectorXd> states;                   // [f; ḟ]
};

// The tip's history at `times` (increasing, from 0) from the state x0 = [f; ḟ] at t = 0.
inline TipHistory odeint_tip_history(const bladestab::BladeModel& m, const BladeLoadCase& c, const Eigen::VectorXd& x0,
                                     const std::vector<double>& times, double tolerance = 1e-10) {
  namespace odeint = boost::numeric::odeint;
  using State = std::vector<double>;
  const int n = m.layout.size();
  const double W = c.speed_rad_s;
  const Eigen::MatrixXd K = m.stiffness(W);
  const Eigen::VectorXd steady = m.steady_load(W), p_u = m.tip_axial.transpose(), p_v = m.tip_lateral.transpose();
  const Eigen::LLT<Eigen::MatrixXd> mass(m.M);
  const double cos_beta = std::cos(m.blade.beta_rad), rim_speed = W * m.blade.tip_radius();
  const auto friction = [&](double F, double lateral_velocity) {
    if (F == 0 || c.friction == 0) return 0.0;
    const double sliding = rim_speed + cos_beta * lateral_velocity;
    return -c.friction * std::abs(F) * cos_beta * (sliding > 0 ? 1.0 : -1.0);
  };
  double piece_end = 0;  // the load is taken from inside the current piece, never across its end
  const auto rhs = [&](const State& y, State& dy, double t) {
    const Eigen::Map<const Eigen::VectorXd> f(y.data(), n), v(y.data() + n, n);
    const double F = c.force(std::min(t, std::nextafter(piece_end, 0.0)));
    const double R = friction(F, p_v.dot(v));
    const Eigen::VectorXd axial = p_u - m.G * f;
    const Eigen::VectorXd a = mass.solve(steady + F * axial + R * p_v - K * f - c.C * v);
    dy.resize(y.size());
    Eigen::Map<Eigen::VectorXd>(dy.data(), n) = v;
    Eigen::Map<Eigen::VectorXd>(dy.data() + n, n) = a;
    dy[2 * n] = F * v.dot(axial);
    dy[2 * n + 1] = R * p_v.dot(v);
  };
  State x(2 * n + 2, 0.0);
  std::copy(x0.data(), x0.data() + 2 * n, x.begin());
  TipHistory h;
  const auto record = [&](const State& y) {
    const Eigen::Map<const Eigen::VectorXd> f(y.data(), n), v(y.data() + n, n);
    h.lateral.push_back(p_v.dot(f));
    h.axial.push_back(p_u.dot(f));
    h.lateral_velocity.push_back(p_v.dot(v));
    h.load_work.push_back(y[2 * n]);
    h.friction_work.push_back(y[2 * n + 1]);
    h.states.push_back(Eigen::Map<const Eigen::VectorXd>(y.data(), 2 * n));
  };
  // The pieces' ends: the load's edges up to the last time, and the last time. Ends and times that
  // differ by rounding only (an edge at k T_p against a sample time at j T/n) count as one.
  const double close = 1e-12 * times.back();
  std::vector<double> edges = c.edges, ends;
  edges.push_back(times.back());
  std::sort(edges.begin(), edges.end());
  for (const double e : edges) {
    if (e <= close || e > times.back() + close) continue;
    if (!ends.empty() && e - ends.back() <= close) {
      ends.back() = std::max(ends.back(), e);
    } else {
      ends.push_back(std::min(e, times.back()));
    }
  }
  ends.back() = times.back();
  auto stepper = odeint::make_dense_output(tolerance, tolerance, odeint::runge_kutta_dopri5<State>());
  std::size_t next = 0;
  if (times.front() == 0) record(x), next = 1;
  double t = 0;
  for (double end : ends) {
    piece_end = end;
    std::vector<double> piece{t};
    while (next < times.size() && times[next] <= end + close) piece.push_back(std::min(times[next++], end));
    const std::size_t recorded = piece.size() - 1;
    if (piece.back() < end) piece.push_back(end);
    std::size_t k = 0;
    odeint::integrate_times(stepper, rhs, x, piece.begin(), piece.end(), (end - t) / 100, [&](const State& y, double) {
      if (k >= 1 && k <= recorded) record(y);
      ++k;
    });
    t = end;
  }
  return h;
}

// The largest difference of two histories relative to the largest |a|.
inline double relative_history_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double peak = 0, worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    peak = std::max(peak, std::abs(a[k]));
    worst = std::max(worst, std::abs(a[k] - b[k]));
  }
  return worst / peak;
}

}  // namespace reference
