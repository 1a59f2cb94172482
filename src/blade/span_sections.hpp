#pragma once
// A tabled blade's section properties sampled along the span (docs/theory.md §9): Gauss–Legendre
// points per segment between stations, where every property is linear, so that the integrals of
// the model are exact to rounding however the properties bend at the stations.
#include <Eigen/Dense>

#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct SpanSamples {
  Eigen::VectorXd s, w;             // points [m] and weights over [0, L]
  Eigen::VectorXd area, i_flap, i_edge, youngs_modulus, shear_modulus, density, shear_coefficient;
  Eigen::VectorXd beta;             // β(s) = stagger + twist_scale · twist(s) [rad]
  Eigen::VectorXd tension1;         // T_cf(s)/Ω² = ∫_s^L ρA (r + ξ) dξ
};

// `points_per_segment` Gauss points on each segment between the table's stations.
SpanSamples sample_span(const BladeSpec& blade, int points_per_segment);

}  // namespace bladestab
