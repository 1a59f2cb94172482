#pragma once
// Sixth-order Magnus propagator for a linear system ẋ = A(t) x (Blanes, Casas & Ros 2000,
// three Gauss–Legendre points per step). The constant part of A is exponentiated exactly, so
// stiff but slowly modulated systems need few steps. Knows nothing of blades: φ is a function.
#include <functional>

#include <Eigen/Dense>

namespace bladestab {

// X(t1) with X(t0) = I, in `steps` equal steps, for A(t) = A₀ + φ(t) B (the blade: a constant part
// and the tip load's). Every commutator of the expansion is then a fixed combination of nine nested
// commutators of A₀ and B, formed once, so a step costs one exponential and one product.
Eigen::MatrixXd magnus_propagator(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& B,
                                  const std::function<double(double)>& phi, double t0, double t1, int steps);

}  // namespace bladestab
