#pragma once
// The displacement-controlled rub (docs/theory.md §5, Appendix C): the casing is a rigid wall at the running
// clearance δ above the tip's steady rotating position, distorted inward once per pulse period by
// the intrusion depth d with the pulse profile's shape over the contact time. The tip is pushed
// back by a penalty force while its radial deflection passes the wall:
//
//   g(t, f) = u(L) − ½∫v'² ds − u_eq(L) − (δ − d s(t)),     F = −k max(0, g)     (docs/theory.md §5, (C.1)–(C.3))
//
// with s(t) ∈ [0, 1] the distortion's shape and u_eq(L) the steady stretch. Why a penalty and not
// a constraint: an exact unilateral constraint on one point of a Ritz continuum turns every touch
// into an impact that needs a restitution law the model does not have, and chatters; the penalty
// keeps a smooth ODE between touches, derives from the potential ½k g₊² (so a still wall conserves
// energy), and converges to the constraint as k grows. Its force acts on f through ∇g = p_u − G f:
// axially on the tip and through the geometric stiffness, exactly as a prescribed tip load does.
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct CasingContact {
  double stiffness_n_m = 0;   // k
  double clearance_m = 0;     // δ
  double intrusion_m = 0;     // d
  double running_tip_m = 0;   // u_eq(L)
  PulseTrain shape;           // s(t): the pulse train with peak 1
  Eigen::RowVectorXd tip_axial;
  Eigen::MatrixXd G;

  // The casing's radial position above the tip's running position: δ − d s(t).
  double wall(double t) const { return clearance_m + intrusion_m * shape.force(t); }  // force(t) = −s(t)
  // g(t, f): how far the tip has passed the wall (> 0 in contact).
  double overlap(double t, const Eigen::VectorXd& f) const {
    return tip_axial.dot(f) - 0.5 * f.dot(G * f) - running_tip_m - wall(t);
  }
  // ġ with the wall's own speed from a central difference of s(t) (used only to find the deepest
  // overlap, where ġ = 0).
  double overlap_rate(double t, const Eigen::VectorXd& f, const Eigen::VectorXd& f_dot) const;
  // The contact force on the tip along the blade axis, ≤ 0.
  double force(double t, const Eigen::VectorXd& f) const { return -stiffness_n_m * std::max(0.0, overlap(t, f)); }
  // The penalty's potential ½k g₊².
  double energy(double t, const Eigen::VectorXd& f) const {
    const double g = std::max(0.0, overlap(t, f));
    return 0.5 * stiffness_n_m * g * g;
  }
};

// The scene's casing at its speed (load.mode = "clearance"). Default k: 100 times the blade's
// static axial stiffness at the tip, 1/(p_uᵀ K(Ω)⁻¹ p_u), so the wall yields 1 % of what the blade does.
CasingContact casing_contact(const BladeModel& model, const Scene& scene);

}  // namespace bladestab
