#include "bladestab/transient/casing_contact.hpp"

#include "bladestab/transient/transient.hpp"

namespace bladestab {

double CasingContact::overlap_rate(double t, const Eigen::VectorXd& f, const Eigen::VectorXd& f_dot) const {
  // ġ = (p_u − G f)ᵀ ḟ − ẇ(t), ẇ = d · dF/dt of the unit-peak train.
  return (tip_axial - (G * f).transpose()).dot(f_dot) - intrusion_m * shape.force_rate(t);
}

CasingContact casing_contact(const BladeModel& model, const Scene& scene) {
  const double speed = scene.operation.speed_rad_s;
  const Eigen::MatrixXd K = model.stiffness(speed);
  CasingContact c;
  c.clearance_m = scene.load.clearance;
  c.intrusion_m = scene.load.intrusion;
  c.running_tip_m = model.tip_axial.dot(rotating_equilibrium(model, speed).head(model.layout.size()));
  c.shape = pulse_train(scene);
  c.shape.peak_n = 1;
  c.tip_axial = model.tip_axial;
  c.G = model.G;
  const Eigen::VectorXd p_u = model.tip_axial.transpose();
  const double tip_stiffness = 1 / p_u.dot(K.ldlt().solve(p_u));  // static axial stiffness at the tip
  c.stiffness_n_m = scene.load.contact_stiffness.value_or(100 * tip_stiffness);
  return c;
}

}  // namespace bladestab
