// Section properties along the span of a tabled blade (docs/theory.md §9), linear between stations.
#include "blade/span_sections.hpp"

#include <cmath>
#include <vector>

#include "blade/quadrature.hpp"
#include "bladestab/base/constants.hpp"

namespace bladestab {
namespace {

// A station's value of one property, linear in s between stations a and b: t = (s − s_a)/(s_b − s_a).
double between(const SectionStation& a, const SectionStation& b, double SectionStation::*field, double t) {
  return (1 - t) * a.*field + t * b.*field;
}

// ∫ ρA(ξ)(r + ξ) dξ over [x0, x1] inside one segment: the integrand is cubic (ρ and A linear), so
// two Gauss points give it exactly.
double tension_integral(const SectionStation& a, const SectionStation& b, double s_a, double s_b, double r,
                        double x0, double x1) {
  const QuadratureRule rule = gauss_legendre(2, x0, x1);
  double sum = 0;
  for (int q = 0; q < 2; ++q) {
    const double t = (rule.points(q) - s_a) / (s_b - s_a);
    sum += rule.weights(q) * between(a, b, &SectionStation::density, t) * between(a, b, &SectionStation::area, t) *
           (r + rule.points(q));
  }
  return sum;
}

}  // namespace

SpanSamples sample_span(const BladeSpec& blade, int points_per_segment) {
  const std::vector<SectionStation>& st = blade.sections;
  const double L = blade.length, r = blade.hub_radius;
  const int segments = static_cast<int>(st.size()) - 1, n = segments * points_per_segment;
  SpanSamples out;
  for (Eigen::VectorXd* v : {&out.s, &out.w, &out.area, &out.i_flap, &out.i_edge, &out.youngs_modulus,
                             &out.shear_modulus, &out.density, &out.shear_coefficient, &out.beta, &out.tension1}) {
    v->resize(n);
  }
  // The tension carried through each station from the segments outboard of it.
  std::vector<double> outboard(st.size(), 0.0);
  for (int k = segments - 1; k >= 0; --k) {
    const double a = st[k].span_fraction * L, b = st[k + 1].span_fraction * L;
    outboard[k] = outboard[k + 1] + tension_integral(st[k], st[k + 1], a, b, r, a, b);
  }
  for (int k = 0; k < segments; ++k) {
    const SectionStation &p = st[k], &q = st[k + 1];
    const double a = p.span_fraction * L, b = q.span_fraction * L;
    const QuadratureRule rule = gauss_legendre(points_per_segment, a, b);
    for (int j = 0; j < points_per_segment; ++j) {
      const int i = k * points_per_segment + j;
      const double s = rule.points(j), t = (s - a) / (b - a);
      out.s(i) = s;
      out.w(i) = rule.weights(j);
      out.area(i) = between(p, q, &SectionStation::area, t);
      out.i_flap(i) = between(p, q, &SectionStation::i_flap, t);
      out.i_edge(i) = between(p, q, &SectionStation::i_edge, t);
      out.youngs_modulus(i) = between(p, q, &SectionStation::youngs_modulus, t);
      out.shear_modulus(i) = out.youngs_modulus(i) / (2 * (1 + blade.poisson));
      out.density(i) = between(p, q, &SectionStation::density, t);
      out.shear_coefficient(i) = between(p, q, &SectionStation::shear_coefficient, t);
      out.beta(i) = (blade.stagger_deg + blade.twist_scale * between(p, q, &SectionStation::twist_deg, t)) * pi / 180;
      out.tension1(i) = outboard[k + 1] + tension_integral(p, q, a, b, r, s, b);
    }
  }
  return out;
}

}  // namespace bladestab
