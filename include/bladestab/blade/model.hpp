#pragma once
// The Ritz model of a rotating blade (docs/theory.md §2): mass, stiffness split into its speed-free and
// centrifugal parts, gyroscopic and geometric matrices, load vectors. The Ω-dependence is kept
// as coefficients so a speed sweep assembles once:
//
//   M f̈ + (C_D + Ω C_G1) ḟ + (K_S + Ω² K_C1 + F(t) G) f = Ω² P_cf1 + F(t) p_tip + friction  (23), (40)
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/blade_properties.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

// Where each field's generalized coordinates sit in f = [X; Y; Z] (θ, v, u). A field that the
// model drops (θ for Euler–Bernoulli, u without axial motion) has count 0. A blade bending in two
// planes (docs/theory.md §9) has two rotation and two lateral fields, one per plane (y, then z),
// each of count/planes coordinates: f = [θ_y; θ_z; y; z; u].
struct DofLayout {
  int theta_count = 0, lateral_count = 0, axial_count = 0;
  int planes = 1;
  int theta_offset() const { return 0; }
  int lateral_offset() const { return theta_count; }
  int axial_offset() const { return theta_count + lateral_count; }
  int size() const { return theta_count + lateral_count + axial_count; }
  // Each field's coordinates (offset, count): the rotation and lateral fields plane by plane, then
  // the axial one. The bases are hierarchical within each.
  std::vector<std::pair<int, int>> fields() const;
};

// The layout of a model of this spec, known before (and without) assembling it; `two_planes` for a
// blade with a section table (BladeSpec::two_planes).
DofLayout dof_layout(const ModelSpec& spec, bool two_planes = false);

// What a mode is, by where its kinetic energy lies (docs/theory.md §9): bending of the one-plane
// blade; flap (normal to the local chord) or edge (along it) of a two-plane blade; axial; rotation
// of the sections.
enum class ModeFamily { bending, axial, rotation, flap, edge };
constexpr int mode_family_count = 5;

// A family's share of a vector's kinetic energy is qᵀ mass q over the coordinates
// [offset, offset + count): the families' forms add up to qᵀ M q.
struct FieldFamily {
  ModeFamily family = ModeFamily::bending;
  const char* share_name = "";  // as outputs name the share: "rotation", "lateral", "flap", …
  int offset = 0, count = 0;
  Eigen::MatrixXd mass;
};

struct BladeModel {
  BladeProperties blade;
  ModelSpec spec;
  DofLayout layout;
  // The scene's static tip force F_s [N], tension positive: a static compression F_a (scene key
  // operation.tip_compression_over_fcr) is F_s = −F_a. It is part of K_S and of steady_load().
  double static_tip_force_n = 0;

  Eigen::MatrixXd M;     // mass, symmetric positive definite
  Eigen::MatrixXd K_S;   // speed-free stiffness, symmetric: the elastic one plus F_s G
  Eigen::MatrixXd K_C1;  // centrifugal stiffness per Ω² (tension stiffening and spin softening), symmetric
  Eigen::MatrixXd C_G1;  // gyroscopic (Coriolis) matrix per Ω, skew-symmetric; zero without coriolis
  Eigen::MatrixXd G;     // geometric stiffness per newton of tip tension: ∫V_i' V_j'
  Eigen::VectorXd P_cf1; // steady centrifugal load per Ω²: ρA ∫(r + s) W_i
  // The tip's lateral deflection, along which the tip friction acts: v(L) = tip_lateral · f (one
  // plane, along the flap normal), or y(L) in the plane of rotation (two planes, docs/theory.md §9).
  Eigen::RowVectorXd tip_lateral;
  Eigen::RowVectorXd tip_axial;    // u(L) = tip_axial · f
  Eigen::RowVectorXd tip_slope;    // the slope of the deflected axis at the tip along tip_lateral
  // The in-plane component of a unit tip_lateral deflection: cos β (one plane), 1 (two planes).
  double in_plane_share = 1;
  // The kinetic-energy families of modes (modes.hpp): rotation, lateral (or flap and edge), axial.
  std::vector<FieldFamily> families;

  // K_S + Ω² K_C1 + F G: F is a tip tension on top of the static one (a pulse).
  Eigen::MatrixXd stiffness(double speed_rad_s, double tip_force_n = 0) const {
    return K_S + speed_rad_s * speed_rad_s * K_C1 + tip_force_n * G;
  }
  // The strain stiffness alone (bending, shear, axial; (55), (56)), without the static tip force:
  // what stiffness-proportional damping and the strain energy are made of.
  Eigen::MatrixXd elastic_stiffness() const { return K_S - static_tip_force_n * G; }
  // The load that does not vary in time: Ω² P_cf1 plus the static tip force on the axial tip (docs/theory.md §2, P_u).
  Eigen::VectorXd steady_load(double speed_rad_s) const {
    return speed_rad_s * speed_rad_s * P_cf1 + static_tip_force_n * tip_axial.transpose();
  }
  Eigen::MatrixXd gyroscopic(double speed_rad_s) const { return speed_rad_s * C_G1; }
};

// The Ritz model of a scene: its blade, its model spec (or `spec`, e.g. a richer basis for an
// error estimate) and its operation's static tip compression F_a, which the model carries in K_S
// (as −F_a G) and in its steady load. Every analysis builds its model here, so every command
// honours the compression. An InputError when the scene's operating point (its speed and F_a) is
// past the blade's static limits (static_limit_error in static_limits.hpp); a NumericalError
// naming the scene's keys when the matrices come out non-finite or the mass is not positive
// definite (the model would have no modes).
BladeModel assemble_model(const Scene& scene);
BladeModel assemble_model(const Scene& scene, const ModelSpec& spec);

// The same model without the check of the scene's speed: for the analyses over a range of speeds
// (a Campbell diagram), which keep to the speeds within the limits themselves (speeds_within_limits).
BladeModel assemble_model_at_any_speed(const Scene& scene, const ModelSpec& spec);

}  // namespace bladestab
