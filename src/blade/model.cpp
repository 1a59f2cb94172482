// Assembly of the Ritz matrices of docs/theory.md §2. Every entry is one weighted Gram product
// ∫ c(s) a_i(s) b_j(s) ds of sampled shape functions, evaluated by Gauss–Legendre quadrature
// that is exact for the Legendre basis and accurate to rounding for the sine basis.
#include "bladestab/blade/model.hpp"

#include <cmath>

#include <fmt/format.h>

#include "blade/basis.hpp"
#include "blade/gram.hpp"
#include "blade/two_plane_model.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "blade/quadrature.hpp"
#include "bladestab/blade/static_limits.hpp"

namespace bladestab {

DofLayout dof_layout(const ModelSpec& spec, bool two_planes) {
  DofLayout layout;
  layout.planes = two_planes ? 2 : 1;
  layout.theta_count = spec.theory == BeamTheory::timoshenko ? layout.planes * spec.terms : 0;
  layout.lateral_count = layout.planes * spec.terms;
  layout.axial_count = spec.axial ? spec.terms : 0;
  return layout;
}

std::vector<std::pair<int, int>> DofLayout::fields() const {
  std::vector<std::pair<int, int>> out;
  for (int p = 0; p < planes; ++p) out.emplace_back(theta_offset() + p * theta_count / planes, theta_count / planes);
  for (int p = 0; p < planes; ++p) {
    out.emplace_back(lateral_offset() + p * lateral_count / planes, lateral_count / planes);
  }
  out.emplace_back(axial_offset(), axial_count);
  return out;
}

namespace {

// Every matrix finite and the mass positive definite, or a NumericalError that names what the
// scene gave: within the scene's limits (scene_limits.hpp) this does not happen, and if it does the
// message says which numbers to look at rather than which factorization failed later.
void check_model(const BladeModel& model, const BladeSpec& blade) {
  const bool finite = model.M.allFinite() && model.K_S.allFinite() && model.K_C1.allFinite() &&
                      model.C_G1.allFinite() && model.G.allFinite() && model.P_cf1.allFinite();
  const bool positive_mass = finite && Eigen::LLT<Eigen::MatrixXd>(model.M).info() == Eigen::Success;
  if (positive_mass) return;
  throw NumericalError(fmt::format(
      "the Ritz model's {} (blade.length = {:g}, blade.area = {:g}, I = {:g} m^4 from blade.slenderness or "
      "blade.inertia, blade.youngs_modulus = {:g}, blade.density = {:g}, model.basis = \"{}\", model.terms = {}); "
      "fewer model.terms or the legendre basis condition it better",
      finite ? "mass matrix is not positive definite" : "matrices are not finite", blade.length, blade.area,
      blade.inertia, blade.youngs_modulus, blade.density, to_string(model.spec.basis), model.spec.terms));
}

// Where the fields are sampled and summed: the blade, the basis size N, the quadrature points s
// and weights w, and the first dof of each field.
struct FieldQuadrature {
  const BladeProperties& b;
  BasisKind basis;
  int N;
  const Eigen::VectorXd &s, &w;
  int th, lv, ax;
};

// The rotation field θ of the Timoshenko beam: rotary inertia, bending and shear stiffness (coupled
// to v through the shear), centrifugal softening of θ.
void add_rotation_field(BladeModel& model, const FieldQuadrature& q, const BasisSamples& V) {
  const BladeProperties& b = q.b;
  const int N = q.N, th = q.th, lv = q.lv;
  const Eigen::VectorXd &s = q.s, &w = q.w;
  const double kGA = b.kappa * b.shear_modulus * b.A;
  const BasisSamples U = sample_basis(q.basis, FieldRole::rotation, N, b.L, s);
  model.M.block(th, th, N, N) = gram(w * (b.rho * b.I), U.value, U.value);
  model.K_S.block(th, th, N, N) = gram(w * (b.E * b.I), U.slope, U.slope) + gram(w * kGA, U.value, U.value);
  model.K_S.block(th, lv, N, N) = -gram(w * kGA, U.value, V.slope);
  model.K_S.block(lv, th, N, N) = model.K_S.block(th, lv, N, N).transpose();
  model.K_S.block(lv, lv, N, N) = gram(w * kGA, V.slope, V.slope);
  model.K_C1.block(th, th, N, N) = -gram(w * (b.rho * b.I), U.value, U.value);
}

// The axial field u: mass, stiffness, centrifugal softening and load, the tip's axial motion; with
// the Coriolis coupling to v.
void add_axial_field(BladeModel& model, const FieldQuadrature& q, const BasisSamples& V, const Eigen::VectorXd& tip,
                     bool coriolis) {
  const BladeProperties& b = q.b;
  const int N = q.N, lv = q.lv, ax = q.ax;
  const Eigen::VectorXd &s = q.s, &w = q.w;
  const double cos_beta = std::cos(b.beta_rad);
  const BasisSamples W = sample_basis(q.basis, FieldRole::axial, N, b.L, s);
  const BasisSamples W_tip = sample_basis(q.basis, FieldRole::axial, N, b.L, tip);
  model.M.block(ax, ax, N, N) = gram(w * (b.rho * b.A), W.value, W.value);
  model.K_S.block(ax, ax, N, N) = gram(w * (b.E * b.A), W.slope, W.slope);
  model.K_C1.block(ax, ax, N, N) = -gram(w * (b.rho * b.A), W.value, W.value);
  // Steady centrifugal load ρAΩ²(r + s) per unit length on u.
  model.P_cf1.segment(ax, N) = W.value.transpose() * (w * (b.rho * b.A)).cwiseProduct((b.r + s.array()).matrix());
  model.tip_axial.segment(ax, N) = W_tip.value.row(0);
  if (coriolis) {
    // Coriolis force −2ρAΩ cos β u̇ on v and +2ρAΩ cos β v̇ on u (docs/theory.md §1), moved to the left
    // side of (23): C_vu = 2ρA cos β ∫V_i W_j per Ω, C_uv = −C_vuᵀ.
    const Eigen::MatrixXd C_vu = gram(w * (2 * b.rho * b.A * cos_beta), V.value, W.value);
    model.C_G1.block(lv, ax, N, N) = C_vu;
    model.C_G1.block(ax, lv, N, N) = -C_vu.transpose();
  }
}

// The uniform blade of docs/theory.md §1–2, bending in one plane.
void assemble_one_plane(BladeModel& model, const ModelSpec& spec) {
  const BladeProperties& b = model.blade;
  const bool timoshenko = spec.theory == BeamTheory::timoshenko;
  const int N = spec.terms;
  const DofLayout& layout = model.layout;
  const int th = layout.theta_offset(), lv = layout.lateral_offset(), ax = layout.axial_offset();

  const QuadratureRule rule = gauss_legendre(quadrature_points_needed(spec.basis, N), 0, b.L);
  const Eigen::VectorXd& s = rule.points;
  const Eigen::VectorXd w = rule.weights;
  // T_cf(s)/Ω² = ρA [r(L − s) + (L² − s²)/2]   (docs/theory.md §1)
  const Eigen::VectorXd tension1 =
      b.rho * b.A * (b.r * (b.L - s.array()) + 0.5 * (b.L * b.L - s.array().square())).matrix();

  const Eigen::VectorXd tip = Eigen::VectorXd::Constant(1, b.L);
  const BasisSamples V = sample_basis(spec.basis, timoshenko ? FieldRole::lateral : FieldRole::lateral_clamped,
                                      N, b.L, s);
  const BasisSamples V_tip = sample_basis(spec.basis, timoshenko ? FieldRole::lateral : FieldRole::lateral_clamped,
                                          N, b.L, tip);
  const double cos_beta = std::cos(b.beta_rad);

  // Lateral field v.
  model.M.block(lv, lv, N, N) = gram(w * (b.rho * b.A), V.value, V.value);
  model.K_C1.block(lv, lv, N, N) = gram(w.cwiseProduct(tension1), V.slope, V.slope)       // ∫T_cf V_i'V_j'
                                   - gram(w * (b.rho * b.A * cos_beta * cos_beta), V.value, V.value);
  model.G.block(lv, lv, N, N) = gram(w, V.slope, V.slope);
  model.tip_lateral.segment(lv, N) = V_tip.value.row(0);
  model.tip_slope.segment(lv, N) = V_tip.slope.row(0);
  model.in_plane_share = cos_beta;

  const FieldQuadrature q{b, spec.basis, N, s, w, th, lv, ax};
  if (timoshenko) {
    add_rotation_field(model, q, V);
  } else {
    // Euler–Bernoulli: θ = v', shear-rigid, no rotary inertia: U = ½∫EI v''².
    model.K_S.block(lv, lv, N, N) = gram(w * (b.E * b.I), V.curvature, V.curvature);
  }

  if (spec.axial) add_axial_field(model, q, V, tip, spec.coriolis);
}

// The kinetic-energy families of the one-plane blade: its fields' blocks of M.
void add_one_plane_families(BladeModel& model) {
  const DofLayout& l = model.layout;
  const ModeFamily kinds[3] = {ModeFamily::rotation, ModeFamily::bending, ModeFamily::axial};
  const char* names[3] = {"rotation", "lateral", "axial"};
  const int offsets[3] = {l.theta_offset(), l.lateral_offset(), l.axial_offset()};
  const int counts[3] = {l.theta_count, l.lateral_count, l.axial_count};
  for (int f = 0; f < 3; ++f) {
    model.families.push_back({kinds[f], names[f], offsets[f], counts[f],
                              model.M.block(offsets[f], offsets[f], counts[f], counts[f])});
  }
}

BladeModel assemble_blade(const BladeSpec& blade_spec, const ModelSpec& spec) {
  BladeModel model{BladeProperties(blade_spec), spec, dof_layout(spec, blade_spec.two_planes()), 0, {}, {}, {}, {}, {}, {}, {}, {}, {}, 1, {}};
  const int n = model.layout.size();
  model.M = Eigen::MatrixXd::Zero(n, n);
  model.K_S = Eigen::MatrixXd::Zero(n, n);
  model.K_C1 = Eigen::MatrixXd::Zero(n, n);
  model.C_G1 = Eigen::MatrixXd::Zero(n, n);
  model.G = Eigen::MatrixXd::Zero(n, n);
  model.P_cf1 = Eigen::VectorXd::Zero(n);
  model.tip_lateral = Eigen::RowVectorXd::Zero(n);
  model.tip_axial = Eigen::RowVectorXd::Zero(n);
  model.tip_slope = Eigen::RowVectorXd::Zero(n);
  if (blade_spec.two_planes()) {
    assemble_two_planes(model, blade_spec, spec);
  } else {
    assemble_one_plane(model, spec);
  }

  // Quadrature sums are symmetric only to rounding; make M, K and G symmetric exactly.
  model.M = symmetrized(model.M);
  model.K_S = symmetrized(model.K_S);
  model.K_C1 = symmetrized(model.K_C1);
  model.G = symmetrized(model.G);
  if (blade_spec.two_planes()) {
    add_two_plane_families(model, blade_spec);
  } else {
    add_one_plane_families(model);
  }
  check_model(model, blade_spec);
  return model;
}

}  // namespace

BladeModel assemble_model(const Scene& scene) { return assemble_model(scene, scene.model); }

BladeModel assemble_model(const Scene& scene, const ModelSpec& spec) {
  BladeModel model = assemble_model_at_any_speed(scene, spec);
  if (std::optional<InputError> past = static_limit_error(model, scene.operation.speed_rad_s)) throw *past;
  return model;
}

BladeModel assemble_model_at_any_speed(const Scene& scene, const ModelSpec& spec) {
  BladeModel model = assemble_blade(scene.blade, spec);
  // A static tip compression F_a = c F_cr is a constant tip tension −F_a: its geometric stiffness
  // −F_a G joins the speed-free stiffness (docs/theory.md (23), (40) with F(t) = −F_a), its axial push the
  // steady load (steady_load()).
  model.static_tip_force_n = -scene.operation.tip_compression_over_fcr * model.blade.critical_load();
  if (model.static_tip_force_n != 0) model.K_S += model.static_tip_force_n * model.G;
  return model;
}

}  // namespace bladestab
