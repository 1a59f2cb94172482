#include "bladestab/campbell.hpp"

#include <algorithm>
#include <cmath>

#include "bladestab/damping.hpp"

namespace bladestab {
namespace {

constexpr double two_pi = 6.28318530717958647692;

// Modes at one speed, a few more than tracked so that modes entering from above can be followed.
ModalSolution modes_at(const BladeModel& model, const DampingSpec& damping, double speed, int count,
                       EigenSolverKind solver) {
  return solve_modes(model, system_at(model, speed, damping_matrix(model, damping, speed)), speed, count, solver);
}

// Greedy assignment by largest MAC: result[i] = index in `candidates` for tracked shape i.
std::vector<int> match_by_shape(const std::vector<Eigen::VectorXcd>& tracked, const std::vector<Mode>& candidates,
                                const Eigen::MatrixXd& M, std::vector<double>& mac_out) {
  const int nt = static_cast<int>(tracked.size()), nc = static_cast<int>(candidates.size());
  Eigen::MatrixXd mac(nt, nc);
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < nc; ++j) mac(i, j) = modal_assurance(tracked[i], candidates[j].shape, M);
  std::vector<int> result(nt, -1);
  mac_out.assign(nt, 0);
  Eigen::MatrixXd open = mac;
  for (int step = 0; step < std::min(nt, nc); ++step) {
    Eigen::Index i = 0, j = 0;
    open.maxCoeff(&i, &j);
    result[i] = static_cast<int>(j);
    mac_out[i] = mac(i, j);
    open.row(i).setConstant(-1);
    open.col(j).setConstant(-1);
  }
  return result;
}

// Frequency of the mode most like `shape` at speed Ω.
double tracked_frequency(const BladeModel& model, const DampingSpec& damping, double speed, int count,
                         EigenSolverKind solver, const Eigen::VectorXcd& shape) {
  const ModalSolution sol = modes_at(model, damping, speed, count, solver);
  double best = -1, f = 0;
  for (const Mode& m : sol.modes) {
    const double mac = modal_assurance(shape, m.shape, model.M);
    if (mac > best) best = mac, f = m.frequency_hz;
  }
  return f;
}

// Root of g(Ω) = f(Ω) − kΩ/2π in [a, b] by the Illinois variant of regula falsi.
double refine_crossing(const std::function<double(double)>& g, double a, double ga, double b, double gb) {
  int side = 0;
  for (int iter = 0; iter < 60 && std::abs(b - a) > 1e-12 * std::max(1.0, std::abs(b)); ++iter) {
    const double c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if (gc == 0) return c;
    if ((gc > 0) == (gb > 0)) {
      b = c, gb = gc;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = c, ga = gc;
      if (side == 1) gb *= 0.5;
      side = 1;
    }
  }
  return std::abs(ga) < std::abs(gb) ? a : b;
}

}  // namespace

CampbellDiagram campbell_diagram(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                                 const std::function<void(int, int)>& progress) {
  const int n = model.layout.size();
  const int tracked_count = std::min(options.mode_count, n);
  const int solve_count = std::min(n, tracked_count + std::max(4, tracked_count / 2));
  const auto& speeds = options.speeds_rad_s;
  const int ns = static_cast<int>(speeds.size());

  CampbellDiagram diagram;
  diagram.speeds_rad_s = speeds;
  diagram.engine_orders = options.engine_orders;
  diagram.curves.resize(tracked_count);

  // Shapes of each tracked mode at every speed, for refining engine-order crossings.
  std::vector<std::vector<Eigen::VectorXcd>> shapes(tracked_count, std::vector<Eigen::VectorXcd>(ns));
  for (int s = 0; s < ns; ++s) {
    const ModalSolution sol = modes_at(model, damping, speeds[s], solve_count, options.solver);
    diagram.solver = sol.solver;
    std::vector<int> pick(tracked_count);
    std::vector<double> mac(tracked_count, 1.0);
    if (s == 0) {
      for (int i = 0; i < tracked_count; ++i) {
        pick[i] = i;
        diagram.curves[i].mode = i + 1;
        diagram.curves[i].family = sol.modes[i].family;
      }
    } else {
      std::vector<Eigen::VectorXcd> previous(tracked_count);
      for (int i = 0; i < tracked_count; ++i) previous[i] = shapes[i][s - 1];
      pick = match_by_shape(previous, sol.modes, model.M, mac);
    }
    for (int i = 0; i < tracked_count; ++i) {
      const Mode& m = sol.modes[pick[i]];
      diagram.curves[i].frequency_hz.push_back(m.frequency_hz);
      diagram.curves[i].damping_ratio.push_back(m.damping_ratio);
      diagram.curves[i].correlation.push_back(mac[i]);
      shapes[i][s] = m.shape;
    }
    if (progress) progress(s + 1, ns);
  }

  for (int k : options.engine_orders) {
    for (int i = 0; i < tracked_count; ++i) {
      const CampbellCurve& curve = diagram.curves[i];
      for (int s = 0; s + 1 < ns; ++s) {
        const double g0 = curve.frequency_hz[s] - k * speeds[s] / two_pi;
        const double g1 = curve.frequency_hz[s + 1] - k * speeds[s + 1] / two_pi;
        if (!((g0 > 0 && g1 <= 0) || (g0 < 0 && g1 >= 0))) continue;
        const Eigen::VectorXcd& shape = shapes[i][s];
        const auto g = [&](double speed) {
          return tracked_frequency(model, damping, speed, solve_count, options.solver, shape) - k * speed / two_pi;
        };
        const double speed = g1 == 0 ? speeds[s + 1] : refine_crossing(g, speeds[s], g0, speeds[s + 1], g1);
        diagram.crossings.push_back({k, curve.mode, speed, k * speed / two_pi});
      }
    }
  }
  std::sort(diagram.crossings.begin(), diagram.crossings.end(),
            [](const auto& a, const auto& b) { return a.speed_rad_s < b.speed_rad_s; });
  return diagram;
}

}  // namespace bladestab
