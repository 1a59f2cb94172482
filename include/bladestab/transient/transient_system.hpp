#pragma once
// The transient's equations of motion (transient.hpp) as a first-order system ẋ = f(t, x) for any
// integrator: x = [f; ḟ; W], W the work done on the blade since the start, every matrix
// premultiplied by M⁻¹ once:
//
//   f̈ = M⁻¹(Ω² P_cf + F_s p_u − K(Ω) f − C ḟ + F_ax (p_u − G f) + F_lat p_v)
//   Ẇ = ḟᵀ(F_ax (p_u − G f) + F_lat p_v − D ḟ)
//
// with the tip loads (F_ax, F_lat) of the tip load F (tip_loads). The energy balance
// dE/dt = Ẇ, E = ½ḟᵀMḟ + ½fᵀK(Ω)f − P_steadyᵀf the rotating-frame energy ((55)–(58); the Coriolis
// forces do no work; a static tip compression is in K(Ω) and P_steady, so its potential is in E).
// A Runge–Kutta method keeps no quadratic invariant, so a step that spuriously amplifies a mode
// breaks E(t) − E(0) = W(t).
#include <optional>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/transient/casing_contact.hpp"
#include "bladestab/transient/transient.hpp"

namespace bladestab {

// The tip loads the equations apply for a tip load F: along the span (also the tension of the
// geometric stiffness) and laterally (the friction); with the follower correction (docs/theory.md
// §5) F turns with the tip slope ψ = v'(L): F cos ψ along the span, −F sin ψ added laterally.
struct TipLoads {
  double axial = 0, lateral = 0;
};

class TransientSystem {
public:
  // The scene's system at its speed: the pulse train in load.mode = "force", the casing's penalty
  // force in "clearance". InputError where the pulses have no frequency.
  TransientSystem(const BladeModel& model, const Scene& scene, const TransientOptions& options);

  int dofs() const { return n_; }
  // ẋ at t. Keeps a workspace: one evaluation at a time.
  void derivative(double t, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> dx) const;

  // The tip load F ≤ 0 at t: the pulse train's, or the casing's force.
  double tip_load(double t, const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Coulomb friction on the lateral tip, −μ|F| c · tanh(v_rel/ε), c = model.in_plane_share (cos β;
  // 1 for a two-plane blade, whose tip_lateral is already in the plane of rotation, docs/theory.md §9).
  double friction(double F, const Eigen::Ref<const Eigen::VectorXd>& x) const;
  TipLoads tip_loads(double F, const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // E, the energy the balance is about.
  double energy(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  const PulseTrain& pulses() const { return pulses_; }
  const std::optional<CasingContact>& casing() const { return casing_; }
  const Eigen::MatrixXd& stiffness() const { return K_; }  // K(Ω)

private:
  int n_;
  PulseTrain pulses_;
  std::optional<CasingContact> casing_;
  Eigen::MatrixXd M_, K_, D_, G_, MiK_, MiC_, MiG_;
  Eigen::VectorXd steady_, Mi_cf_, Mi_axial_, Mi_lateral_;
  Eigen::RowVectorXd tip_axial_, tip_lateral_, tip_slope_;
  double mu_, in_plane_share_, rim_speed_, friction_velocity_;
  bool follower_, damped_;
  mutable Eigen::VectorXd work_;  // the products of derivative(), without a temporary per evaluation
};

}  // namespace bladestab
