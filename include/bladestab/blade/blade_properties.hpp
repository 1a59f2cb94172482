#pragma once
// Physical constants of a blade and the non-dimensional groups of docs/theory.md §3.
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct BladeProperties {
  double L, r, A, I, E;     // SI: span, hub radius, area, second moment, Young's modulus
  double shear_modulus;     // E / (2(1 + ν)); the model's G is the geometric stiffness
  double rho, nu, kappa;    // density, Poisson's ratio, shear coefficient κ
  double beta_rad;                          // stagger angle β
  double critical_load_n;                   // F_cr [N]

  // A blade with a section table (docs/theory.md §9) takes A, I, E, ρ, κ from its root station.
  explicit BladeProperties(const BladeSpec& spec);

  double tip_radius() const { return r + L; }                    // R = r + L
  double slenderness() const;                                    // d̄ = sqrt(I / (A L²))
  // F_cr: π² E I / (4 L²) for a uniform blade; for a blade with a section table its own
  // Euler–Bernoulli buckling load at rest under tip compression (docs/theory.md §9).
  double critical_load() const { return critical_load_n; }
  double lambda_from_omega(double omega_rad_s) const;            // Λ = ω L² sqrt(ρA/(EI))
  double nondimensional_speed(double speed_rad_s) const;         // Ω̄ = Ω sqrt(ρ R² / E)
  double revolutions(double time_s, double speed_rad_s) const;   // t̄ = t Ω / 2π
};

}  // namespace bladestab
