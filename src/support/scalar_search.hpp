#pragma once
// One-dimensional searches on a continuous function of the rotor speed (or any scalar): the root
// of a bracketed sign change and the least value on an interval. Shared by the Campbell
// diagram's crossings and the requirements' worst points.
#include <functional>

namespace bladestab {

// Root of g in [a, b], g(a) = ga and g(b) = gb of opposite signs, by the Illinois variant of
// regula falsi, to 1e-12 of max(1, |b|) in the argument.
double illinois_root(const std::function<double(double)>& g, double a, double ga, double b, double gb);

// The argument of the least value of f on [a, b] by golden-section search, to `tolerance` in the
// argument (f unimodal there; otherwise a local minimum). The ends are candidates too.
double golden_minimum(const std::function<double(double)>& f, double a, double b, double tolerance);

}  // namespace bladestab
