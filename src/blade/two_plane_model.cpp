// The Ritz matrices of a tabled, pretwisted blade bending in two planes (docs/theory.md §9), in the
// rotating frame's fixed axes: y tangential (in the plane of rotation), z along the spin axis.
// The section's inertia tensor I₁ n nᵀ + I₂ c cᵀ with n = (cos β, −sin β), c = (sin β, cos β):
//
//   I_zz = I₁ cos²β + I₂ sin²β,  I_yy = I₁ sin²β + I₂ cos²β,  I_yz = (I₂ − I₁) sin β cos β
//
// stiffens the curvatures (y'', z'') (Euler–Bernoulli) or the section rotations' gradients
// (Timoshenko, with shear κGA in each plane and rotary inertia ρ times the same tensor).
#include "blade/two_plane_model.hpp"

#include <algorithm>
#include <cmath>

#include "blade/basis.hpp"
#include "blade/gram.hpp"
#include "blade/span_sections.hpp"

namespace bladestab {
namespace {

// The inertia tensor's entries at the span's points (docs/theory.md §9).
struct SectionTensor {
  Eigen::VectorXd zz, yy, yz;
};

SectionTensor section_tensor(const SpanSamples& p) {
  const Eigen::ArrayXd c = p.beta.array().cos(), s = p.beta.array().sin();
  const Eigen::ArrayXd I1 = p.i_flap.array(), I2 = p.i_edge.array();
  return {(I1 * c * c + I2 * s * s).matrix(), (I1 * s * s + I2 * c * c).matrix(), ((I2 - I1) * s * c).matrix()};
}

// A symmetric 2×2 block form [[a, b], [b, c]] of N×N blocks ∫ coefficient · f_i g_j.
Eigen::MatrixXd tensor_form(const Eigen::VectorXd& w, const SectionTensor& t, double factor, const Eigen::VectorXd& along,
                            const Eigen::MatrixXd& f) {
  const int N = static_cast<int>(f.cols());
  Eigen::MatrixXd out(2 * N, 2 * N);
  const Eigen::VectorXd wa = factor * w.cwiseProduct(along);
  out.topLeftCorner(N, N) = gram(wa.cwiseProduct(t.zz), f, f);
  out.topRightCorner(N, N) = gram(wa.cwiseProduct(t.yz), f, f);
  out.bottomLeftCorner(N, N) = out.topRightCorner(N, N).transpose();
  out.bottomRightCorner(N, N) = gram(wa.cwiseProduct(t.yy), f, f);
  return out;
}

// The same N×N block on the diagonal of both planes.
Eigen::MatrixXd both_planes(const Eigen::MatrixXd& block) {
  const Eigen::Index N = block.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(2 * N, 2 * N);
  out.topLeftCorner(N, N) = block;
  out.bottomRightCorner(N, N) = block;
  return out;
}

int points_per_segment(const ModelSpec& spec) {
  // The basis products of quadrature_points_needed times a linear or quadratic property and the
  // trigonometric factors of β(s): a margin of eight points takes them to rounding.
  return quadrature_points_needed(spec.basis, spec.terms) + 8;
}

FieldRole lateral_role(const ModelSpec& spec) {
  return spec.theory == BeamTheory::timoshenko ? FieldRole::lateral : FieldRole::lateral_clamped;
}

}  // namespace

// Mass-weighted projections of the deflection (y, z) on the local flap normal n and chord c: the
// kinetic-energy forms of the flap and edge families (they add up to the lateral mass).
void add_two_plane_families(BladeModel& model, const BladeSpec& blade) {
  const ModelSpec& spec = model.spec;
  const SpanSamples p = sample_span(blade, points_per_segment(spec));
  const BasisSamples V = sample_basis(spec.basis, lateral_role(spec), spec.terms, blade.length, p.s);
  const DofLayout& l = model.layout;
  const Eigen::VectorXd rhoA = p.density.cwiseProduct(p.area);
  const Eigen::ArrayXd c = p.beta.array().cos(), s = p.beta.array().sin();
  // n·d = cos β y − sin β z, c·d = sin β y + cos β z.
  const SectionTensor flap{(c * c).matrix(), (s * s).matrix(), (-s * c).matrix()};
  const SectionTensor edge{(s * s).matrix(), (c * c).matrix(), (s * c).matrix()};
  if (l.theta_count > 0) {
    model.families.push_back({ModeFamily::rotation, "rotation", l.theta_offset(), l.theta_count,
                              model.M.block(l.theta_offset(), l.theta_offset(), l.theta_count, l.theta_count)});
  }
  model.families.push_back({ModeFamily::flap, "flap", l.lateral_offset(), l.lateral_count,
                            tensor_form(p.w, flap, 1, rhoA, V.value)});
  model.families.push_back({ModeFamily::edge, "edge", l.lateral_offset(), l.lateral_count,
                            tensor_form(p.w, edge, 1, rhoA, V.value)});
  if (l.axial_count > 0) {
    model.families.push_back({ModeFamily::axial, "axial", l.axial_offset(), l.axial_count,
                              model.M.block(l.axial_offset(), l.axial_offset(), l.axial_count, l.axial_count)});
  }
}

namespace {

// Section rotations (θ_y of the y-bending, θ_z of the z-bending): rotary inertia ρ·tensor, bending
// E·tensor on their gradients, shear κGA (θ − lateral slope)² per plane, and the centrifugal
// softening −ρ·tensor Ω² of §1–2's rotation field, rotated as the tensor.
void add_rotations(BladeModel& model, const SpanSamples& p, const SectionTensor& t, const BasisSamples& V,
                   const ModelSpec& spec) {
  const int N = spec.terms, th = model.layout.theta_offset(), lv = model.layout.lateral_offset();
  const BasisSamples U = sample_basis(spec.basis, FieldRole::rotation, N, model.blade.L, p.s);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(p.s.size());
  const Eigen::VectorXd kGA = p.shear_coefficient.cwiseProduct(p.shear_modulus).cwiseProduct(p.area);
  const Eigen::MatrixXd rotary = tensor_form(p.w, t, 1, p.density, U.value);
  model.M.block(th, th, 2 * N, 2 * N) = rotary;
  model.K_C1.block(th, th, 2 * N, 2 * N) = -rotary;
  model.K_S.block(th, th, 2 * N, 2 * N) = tensor_form(p.w, t, 1, p.youngs_modulus, U.slope) +
                                          both_planes(gram(p.w.cwiseProduct(kGA), U.value, U.value));
  const Eigen::MatrixXd coupling = both_planes(-gram(p.w.cwiseProduct(kGA), U.value, V.slope));
  model.K_S.block(th, lv, 2 * N, 2 * N) = coupling;
  model.K_S.block(lv, th, 2 * N, 2 * N) = coupling.transpose();
  model.K_S.block(lv, lv, 2 * N, 2 * N) = both_planes(gram(p.w.cwiseProduct(kGA), V.slope, V.slope));
}

// The axial field u: mass, stiffness, spin softening, steady centrifugal load, Coriolis coupling with
// the in-plane deflection y (C_yu = 2ρA ∫Y_i W_j per Ω, C_uy = −C_yuᵀ; docs/theory.md §9).
void add_axial(BladeModel& model, const SpanSamples& p, const BasisSamples& V, const ModelSpec& spec) {
  const int N = spec.terms, y = model.layout.lateral_offset(), ax = model.layout.axial_offset();
  const Eigen::VectorXd rhoA = p.density.cwiseProduct(p.area);
  const BasisSamples W = sample_basis(spec.basis, FieldRole::axial, N, model.blade.L, p.s);
  const BasisSamples W_tip = sample_basis(spec.basis, FieldRole::axial, N, model.blade.L,
                                          Eigen::VectorXd::Constant(1, model.blade.L));
  model.M.block(ax, ax, N, N) = gram(p.w.cwiseProduct(rhoA), W.value, W.value);
  model.K_S.block(ax, ax, N, N) = gram(p.w.cwiseProduct(p.youngs_modulus.cwiseProduct(p.area)), W.slope, W.slope);
  model.K_C1.block(ax, ax, N, N) = -model.M.block(ax, ax, N, N);
  model.P_cf1.segment(ax, N) =
      W.value.transpose() * p.w.cwiseProduct(rhoA).cwiseProduct((model.blade.r + p.s.array()).matrix());
  model.tip_axial.segment(ax, N) = W_tip.value.row(0);
  if (spec.coriolis) {
    const Eigen::MatrixXd C_yu = gram(p.w.cwiseProduct(2 * rhoA), V.value, W.value);
    model.C_G1.block(y, ax, N, N) = C_yu;
    model.C_G1.block(ax, y, N, N) = -C_yu.transpose();
  }
}

// G = ∫(Y_i' Y_j' + Z_i' Z_j') and the Euler–Bernoulli bending stiffness E·tensor on (y'', z'').
Eigen::MatrixXd geometric(const SpanSamples& p, const BasisSamples& V) { return both_planes(gram(p.w, V.slope, V.slope)); }
Eigen::MatrixXd bending_eb(const SpanSamples& p, const BasisSamples& V) {
  return tensor_form(p.w, section_tensor(p), 1, p.youngs_modulus, V.curvature);
}

}  // namespace

void assemble_two_planes(BladeModel& model, const BladeSpec& blade, const ModelSpec& spec) {
  const SpanSamples p = sample_span(blade, points_per_segment(spec));
  const int N = spec.terms, lv = model.layout.lateral_offset();
  const BasisSamples V = sample_basis(spec.basis, lateral_role(spec), N, blade.length, p.s);
  const BasisSamples V_tip =
      sample_basis(spec.basis, lateral_role(spec), N, blade.length, Eigen::VectorXd::Constant(1, blade.length));
  const Eigen::VectorXd rhoA = p.density.cwiseProduct(p.area);
  const Eigen::MatrixXd lateral_mass = gram(p.w.cwiseProduct(rhoA), V.value, V.value);
  // Translations: ρA (ẏ² + ż²); tension stiffening ∫T_cf (y'² + z'²); spin softening −ρAΩ² y².
  model.M.block(lv, lv, 2 * N, 2 * N) = both_planes(lateral_mass);
  model.K_C1.block(lv, lv, 2 * N, 2 * N) = both_planes(gram(p.w.cwiseProduct(p.tension1), V.slope, V.slope));
  model.K_C1.block(lv, lv, N, N) -= lateral_mass;
  model.G.block(lv, lv, 2 * N, 2 * N) = geometric(p, V);
  model.tip_lateral.segment(lv, N) = V_tip.value.row(0);
  model.tip_slope.segment(lv, N) = V_tip.slope.row(0);
  model.in_plane_share = 1;
  if (spec.theory == BeamTheory::timoshenko) {
    add_rotations(model, p, section_tensor(p), V, spec);
  } else {
    model.K_S.block(lv, lv, 2 * N, 2 * N) = bending_eb(p, V);
  }
  if (spec.axial) add_axial(model, p, V, spec);
}

double tabled_buckling_load(const BladeSpec& blade) {
  const ModelSpec spec{BasisKind::legendre, 24, BeamTheory::euler_bernoulli, false, false, {}};
  const SpanSamples p = sample_span(blade, points_per_segment(spec));
  const BasisSamples V = sample_basis(spec.basis, FieldRole::lateral_clamped, spec.terms, blade.length, p.s);
  // G x = μ K_E x (K_E positive definite): the least buckling load is 1/μ_max.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      symmetrized(geometric(p, V)), symmetrized(bending_eb(p, V)), Eigen::EigenvaluesOnly);
  return 1 / solver.eigenvalues().maxCoeff();
}

}  // namespace bladestab
