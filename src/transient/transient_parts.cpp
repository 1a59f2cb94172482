#include "transient_parts.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/transient/transient_checks.hpp"

namespace bladestab::detail {

Recorder::Recorder(const BladeModel& model, const TransientSystem& system, double speed, double revolution,
                   double initial_energy, double max_lateral_m, double static_tip_axial_m,
                   std::vector<TransientSample>& samples)
    : model_(model), system_(system), K_E_(model.elastic_stiffness()), speed_(speed), revolution_(revolution),
      initial_energy_(initial_energy), max_lateral_m_(max_lateral_m), static_axial_m_(static_tip_axial_m),
      samples_(samples) {}

std::optional<TransientStop> Recorder::operator()(double t, const Eigen::VectorXd& s) const {
  const int n = system_.dofs();
  const Eigen::VectorXd f = s.head(n), v = s.segment(n, n);
  const std::optional<CasingContact>& casing = system_.casing();
  const double F = system_.tip_load(t, s), E = system_.energy(s), W = s(2 * n);
  const TipLoads applied = system_.tip_loads(F, s);
  const double revolutions = speed_ > 0 ? t * speed_ / two_pi : t / revolution_;
  const TransientSample& sample = samples_.emplace_back(TransientSample{
      t, revolutions, model_.tip_lateral.dot(f), model_.tip_axial.dot(f), model_.tip_lateral.dot(v),
      model_.tip_axial.dot(v), F, system_.friction(F, s), casing ? casing->overlap(t, f) : 0, 0.5 * f.dot(K_E_ * f),
      0.5 * v.dot(model_.M * v), E + (casing ? casing->energy(t, f) : 0), W, E - initial_energy_ - W, applied.axial,
      applied.lateral});
  const double L = model_.blade.L;
  if (std::isinf(max_lateral_m_)) return std::nullopt;
  // Written as !(x ≤ limit) so that NaN stops the run too.
  if (!(std::abs(sample.tip_lateral_m) <= max_lateral_m_)) {
    return TransientStop{revolutions, fmt::format("the lateral tip deflection reached {:.4g} m = {:.4g} L, beyond the "
                                                  "small-deflection range of {:g} L",
                                                  sample.tip_lateral_m, sample.tip_lateral_m / L, max_lateral_m_ / L)};
  }
  const double axial_change = sample.tip_axial_m - static_axial_m_;
  if (!(std::abs(axial_change) <= TransientChecks::max_axial_strain * L)) {
    return TransientStop{revolutions, fmt::format("the axial tip deflection changed by {:.4g} m, a mean strain of "
                                                  "{:.4g}, beyond the elastic range of {:g}",
                                                  axial_change, axial_change / L, TransientChecks::max_axial_strain)};
  }
  return std::nullopt;
}

std::vector<double> output_times(int r, double a, double b, double revolution, int per_rev) {
  std::vector<double> outputs;
  for (int k = (r == 0 ? 0 : 1); k <= per_rev && a + k * revolution / per_rev <= b * (1 + 1e-12); ++k) {
    outputs.push_back(k == per_rev ? b : a + k * revolution / per_rev);
  }
  return outputs;
}

double energy_norm(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Eigen::VectorXd& d) {
  const Eigen::Index n = K.rows();
  return std::sqrt(0.5 * d.head(n).dot(K * d.head(n)) + 0.5 * d.segment(n, n).dot(M * d.segment(n, n)));
}

RunStart run_start(const BladeModel& model, const Scene& scene, const TransientSystem& system,
                   const TransientOptions& o, TransientResult& result) {
  const double speed = scene.operation.speed_rad_s;
  const int n = model.layout.size();
  RunStart begin;
  begin.speed = speed;
  begin.revolution = speed > 0 ? two_pi / speed : system.pulses().period_s * scene.load.pulses_per_rev;
  begin.t_end = o.revolutions * begin.revolution;
  const Eigen::VectorXd equilibrium = rotating_equilibrium(model, speed);
  const Eigen::VectorXd start = o.initial_state ? *o.initial_state : equilibrium;
  if (start.size() != 2 * n) throw std::invalid_argument("initial state has the wrong size");
  begin.x.resize(2 * n + 1);
  begin.x << start, 0.0;
  result.static_tip_axial_m = model.tip_axial.dot(equilibrium.head(n));
  begin.initial_energy = system.energy(begin.x);
  result.initial_vibration_energy_j = begin.initial_energy - system.energy(equilibrium);
  return begin;
}

Recorder RunStart::recorder(const BladeModel& model, const TransientSystem& system, const TransientOptions& o,
                            TransientResult& result) const {
  return Recorder(model, system, speed, revolution, initial_energy,
                  o.max_lateral_over_length * model.blade.L, result.static_tip_axial_m, result.samples);
}

}  // namespace bladestab::detail
