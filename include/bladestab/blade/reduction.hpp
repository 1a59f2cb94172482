#pragma once
// Reduced models of the blade under a periodic tip load (docs/theory.md §6, "model only what a scene
// needs"). The motion is sought in the span of a few vectors V with Vᵀ M V = I, so the reduced
// system is  q̈ + Vᵀ C V q̇ + Vᵀ (K(Ω) + F(t) G) V q = 0.
//
//   automatic: the `vectors` lowest modes of K(Ω) + F G at both ends of the load's range, F = 0
//              and F = F_min (the most compressive), plus the static gyroscopic corrections
//              K(Ω)⁻¹ C φ of the unloaded ones. The loaded modes span what the load does to the
//              stiffness (docs/theory.md §6 table); the corrections carry the Coriolis coupling to the axial
//              modes that otherwise leaves a 1e-5 plateau on this blade. A Ritz model with no
//              more than 3·vectors dofs is kept whole.
//   modal:     the unloaded modes below `cutoff_hz` (a modal truncation; all of them for 0).
//   none:      the full Ritz model (the modal form of every mode).
// Nearly dependent vectors are dropped (their M-Gram eigenvalue is below 1e-10 of unit columns).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"

namespace bladestab {

// The reduced second-order system; its mass matrix is the identity.
struct ReducedSystem {
  Eigen::MatrixXd basis;  // V, dofs × size, Vᵀ M V = I
  Eigen::MatrixXd K;      // Vᵀ K(Ω) V, the unloaded stiffness at speed
  Eigen::MatrixXd C;      // Vᵀ (C_D + Ω C_G1) V
  Eigen::MatrixXd G;      // Vᵀ G V, per newton of tip tension
  int full_size = 0;      // dofs of the Ritz model
  bool undamped = false;  // C_D = 0: C is gyroscopic only, the blade's motion Hamiltonian
  // The sizes of the basis's consecutive column blocks: the bending fields', then the axial
  // field's, where the blade is undamped and couples the two by the gyroscopic matrix alone (each
  // column lies in one, so K, G and the modes are block diagonal, exactly); else empty: one block.
  std::vector<int> blocks;
  int size() const { return static_cast<int>(basis.cols()); }
};

// The modes of a reduced system (M = I): ω² ascending and the eigenvectors Q of K in the reduced
// coordinates, solved block by block (ReducedSystem::blocks), so that an axial mode has no bending
// component, to the last bit; `converged` false where K is not finite.
struct ReducedModes {
  Eigen::VectorXd omega2;
  Eigen::MatrixXd shapes;
  bool converged = false;
};
ReducedModes reduced_modes(const ReducedSystem& reduced);

// Modes per load level of the automatic reduction when the spec leaves it to the program.
constexpr int default_reduction_vectors = 3;

// Whether the automatic reduction with `vectors` modes per load level keeps a model of `dofs` whole:
// its 3·vectors basis vectors (the modes at two load levels and their gyroscopic corrections)
// would be as many as the model's dofs.
constexpr bool reduction_keeps_whole(int vectors, int dofs) { return 3 * vectors >= dofs; }

// The automatic reduction with `vectors` modes per load level, or the whole model (none) where
// that would keep it whole.
inline ReductionSpec automatic_or_whole(int vectors, int dofs) {
  return reduction_keeps_whole(vectors, dofs) ? ReductionSpec{ReductionKind::none, 0, 0}
                                              : ReductionSpec{ReductionKind::automatic, vectors, 0};
}

// `min_force_n` is the most compressive tip force of the period (≤ 0), used by `automatic`.
ReducedSystem reduce(const BladeModel& model, double speed_rad_s, const Eigen::MatrixXd& damping,
                     double min_force_n, const ReductionSpec& spec);

}  // namespace bladestab
