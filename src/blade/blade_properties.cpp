#include "bladestab/blade/blade_properties.hpp"

#include <cmath>

#include "bladestab/base/constants.hpp"
#include "blade/two_plane_model.hpp"

namespace bladestab {

BladeProperties::BladeProperties(const BladeSpec& s)
    : L(s.length), r(s.hub_radius), A(s.area), I(s.inertia), E(s.youngs_modulus),
      shear_modulus(s.youngs_modulus / (2 * (1 + s.poisson))), rho(s.density), nu(s.poisson),
      kappa(s.shear_coefficient), beta_rad(s.stagger_deg * pi / 180), critical_load_n(0) {
  if (s.two_planes()) {
    const SectionStation& root = s.sections.front();
    E = root.youngs_modulus;
    shear_modulus = root.youngs_modulus / (2 * (1 + s.poisson));
    rho = root.density;
    kappa = root.shear_coefficient;
    critical_load_n = tabled_buckling_load(s);
  } else {
    critical_load_n = pi * pi * E * I / (4 * L * L);
  }
}

double BladeProperties::slenderness() const { return std::sqrt(I / (A * L * L)); }
double BladeProperties::lambda_from_omega(double w) const { return w * L * L * std::sqrt(rho * A / (E * I)); }
double BladeProperties::nondimensional_speed(double W) const {
  return W * std::sqrt(rho * tip_radius() * tip_radius() / E);
}
double BladeProperties::revolutions(double t, double W) const { return t * W / (2 * pi); }

}  // namespace bladestab
