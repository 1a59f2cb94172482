#pragma once
// Error estimates for computed modes ("model only what a scene needs"): each mode is compared
// with the same mode (same family, same rank within it) of a richer model, and the number of
// terms can be raised until every requested mode meets a tolerance.
#include <optional>
#include <vector>

#include "bladestab/modes.hpp"
#include "bladestab/scene.hpp"

namespace bladestab {

struct ConvergedModes {
  BladeModel model;                   // the model the modes belong to
  ModalSolution solution;
  int reference_terms = 0;            // terms of the richer model used for the estimate
  std::vector<double> relative_error; // |f_N − f_ref| / f_ref per mode
  double max_relative_error() const;
};

// Terms of the richer model used to estimate the error of an N-term model: Legendre (exponential
// convergence) N + max(4, N/2); sine (algebraic convergence) 2N.
int reference_terms(BasisKind basis, int terms);

// Modes of `scene` at its speed with their error estimates. With a tolerance, the number of terms
// starts at the scene's and grows until every one of the `count` lowest modes meets it (an
// InputError if 200 terms do not suffice).
ConvergedModes modes_with_error_estimate(const Scene& scene, int count, EigenSolverKind solver,
                                         std::optional<double> tolerance = std::nullopt);

}  // namespace bladestab
