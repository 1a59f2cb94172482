#pragma once
// One-dimensional searches on a continuous function of the rotor speed (or any scalar): the root
// of a bracketed sign change and the least value on an interval. Shared by the Campbell
// diagram's crossings and the requirements' worst points.
#include <functional>

namespace bladestab {

// Root of g in [a, b] (a < b), g(a) = ga and g(b) = gb of opposite signs, by Boost.Math's TOMS 748,
// to 1e-12 of max(1, |b|) in the argument: the middle of its last bracket.
double bracketed_root(const std::function<double(double)>& g, double a, double ga, double b, double gb);

// The argument of the least value of f on [a, b] by golden-section search, to `tolerance` in the
// argument (f unimodal there; otherwise a local minimum). The ends are candidates too. (Boost's
// brent_find_minima stops at √ε of the argument, 1.5e-8 relative, above the 1e-10 the Campbell
// diagram's closest approaches ask for.)
double golden_minimum(const std::function<double(double)>& f, double a, double b, double tolerance);

}  // namespace bladestab
