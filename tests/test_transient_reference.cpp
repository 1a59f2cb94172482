// The RKF45 transient against an independent integration: Boost.Odeint's Dormand–Prince 5(4) at
// tight tolerances, on the same equations written out here, stepping between the same pulse edges.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "bladestab/periodic_load.hpp"
#include "bladestab/transient.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using State = std::vector<double>;

namespace {

// Tip histories at the transient's sample times from Odeint.
std::pair<std::vector<double>, std::vector<double>> odeint_tip_history(const BladeModel& m, const Scene& s,
                                                                        const std::vector<double>& times) {
  const int n = m.layout.size();
  const double W = s.operation.speed_rad_s;
  const PulseTrain pulses = pulse_train(s);
  const Eigen::MatrixXd K = m.stiffness(W), C = m.gyroscopic(W);
  const Eigen::LLT<Eigen::MatrixXd> M(m.M);
  const auto rhs = [&](const State& x, State& dx, double t) {
    const Eigen::Map<const Eigen::VectorXd> f(x.data(), n), v(x.data() + n, n);
    const double F = pulses.force(t);
    const Eigen::VectorXd load = W * W * m.P_cf1 + F * m.tip_axial.transpose() - K * f - F * (m.G * f) - C * v;
    const Eigen::VectorXd a = M.solve(load);
    dx.resize(2 * n);
    for (int i = 0; i < n; ++i) dx[i] = v(i), dx[n + i] = a(i);
  };
  Eigen::VectorXd x0 = rotating_equilibrium(m, W);
  State x(x0.data(), x0.data() + x0.size());
  std::vector<double> edges = pulses.edges(0, times.back());
  std::vector<double> lat, ax;
  auto stepper = boost::numeric::odeint::make_dense_output(1e-12, 1e-12, boost::numeric::odeint::runge_kutta_dopri5<State>());
  double t = 0;
  std::size_t next = 0;
  const auto record = [&](const State& y) {
    const Eigen::Map<const Eigen::VectorXd> f(y.data(), n);
    lat.push_back(m.tip_lateral.dot(f));
    ax.push_back(m.tip_axial.dot(f));
  };
  edges.push_back(times.back());
  for (double edge : edges) {  // integrate piece by piece so no step crosses a pulse edge
    if (edge <= t) continue;
    std::vector<double> piece;
    while (next < times.size() && times[next] <= edge) piece.push_back(times[next++]);
    if (piece.empty() || piece.front() > t) piece.insert(piece.begin(), t);
    if (piece.back() < edge) piece.push_back(edge);
    std::size_t k = 0;
    boost::numeric::odeint::integrate_times(stepper, rhs, x, piece.begin(), piece.end(), 1e-7, [&](const State& y, double tt) {
      if (k++ == 0 && tt > 0 && !lat.empty()) return;  // the piece's start was recorded already
      if (std::find(times.begin(), times.end(), tt) != times.end()) record(y);
    });
    t = edge;
  }
  return {lat, ax};
}

}  // namespace

TEST_CASE("RKF45 at tolerance 1e-9 agrees with Odeint's Dormand-Prince to 1e-4 of the peak", "[transient][reference]") {
  for (const char* count : {"load.pulse_count=1", "load.pulse_count=0"}) {
    const Scene s = testing_support::paper_scene({"model.terms=4", count});
    const BladeModel m = assemble_model(s);
    TransientOptions o;
    o.revolutions = 2;
    o.tolerance = 1e-9;
    const TransientResult r = run_transient(m, s, o);
    std::vector<double> times;
    for (const TransientSample& p : r.samples) times.push_back(p.time_s);
    const auto [lat, ax] = odeint_tip_history(m, s, times);
    REQUIRE(lat.size() == r.samples.size());
    double peak_lat = 0, peak_ax = 0, d_lat = 0, d_ax = 0;
    for (std::size_t k = 0; k < lat.size(); ++k) {
      peak_lat = std::max(peak_lat, std::abs(lat[k]));
      peak_ax = std::max(peak_ax, std::abs(ax[k]));
      d_lat = std::max(d_lat, std::abs(lat[k] - r.samples[k].tip_lateral_m));
      d_ax = std::max(d_ax, std::abs(ax[k] - r.samples[k].tip_axial_m));
    }
    INFO(count << ": lateral difference " << d_lat / peak_lat << " of the peak, axial " << d_ax / peak_ax);
    CHECK(d_lat < 1e-4 * peak_lat);
    CHECK(d_ax < 1e-4 * peak_ax);
  }
}
