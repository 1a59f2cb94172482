#pragma once
// Ritz shape functions of one field, sampled where the assembly needs them (docs/theory.md §2).
#include <Eigen/Dense>

#include "bladestab/scene/scene.hpp"

namespace bladestab {

// What a field's shape functions must satisfy at the clamped root s = 0.
enum class FieldRole {
  rotation,        // θ: θ(0) = 0                         paper: U_n = sin(λ_n s)
  lateral,         // v: v(0) = 0 (paper basis also v'(0) = 0)   paper: V_n = (1 − cos λ_n s)/λ_n
  lateral_clamped, // v of Euler–Bernoulli: v(0) = v'(0) = 0
  axial,           // u: u(0) = 0                         paper: W_n = sin(λ_n s)/λ_n
};

// Shape functions 1..terms at points s_q: value, first and second derivative (points × terms).
struct BasisSamples {
  Eigen::MatrixXd value, slope, curvature;
};

// Paper basis (18a–c), λ_n = (2n − 1)π/(2L); or integrated Legendre polynomials
// φ_k(s) = ∫₀ˢ P_{k−1}(2ξ/L − 1) dξ (and ψ_k = ∫₀ˢ φ_k for lateral_clamped).
BasisSamples sample_basis(BasisKind kind, FieldRole role, int terms, double length,
                          const Eigen::VectorXd& points);

// Quadrature points that integrate every product the model forms to machine precision
// (exactly, for the polynomial basis).
int quadrature_points_needed(BasisKind kind, int terms);

}  // namespace bladestab
