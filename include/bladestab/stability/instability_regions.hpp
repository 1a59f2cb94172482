#pragma once
// The regions of dynamic instability along one line of the load plane — θ at the scene's F̄_max,
// or F̄_max at a given θ — as intervals between boundaries (docs/theory.md §4), for CI scripts that ask
// "is this operating range clear?".
//
// Between two consecutive boundaries of one multiplier sign (±1) lies either a region of that
// sign or a gap; the window's ends close the first and last intervals. Which one is decided by
// the Floquet multipliers at the interval's middle (a check that shares nothing with the boundary
// equations): unstable there, with the dominant multiplier real and of the boundaries' sign, it is a
// region. Signs, not kinds (mode, order), are paired: at high loads the label of a boundary,
// the dominant harmonic of its eigenvector, can differ between a region's two edges (measured on
// the paper blade at F̄ = 5: the order-3 region from 177.7 to 209.9 rad/s has its lower edge
// labelled order 1). A region is labelled by its edges, the higher order where they differ. Regions of
// different kinds may overlap; combination resonances have no ±1 boundaries and are not listed
// (the map's shading shows them). The boundaries that did not converge divide the line too, so no
// interval spans one; a region that ends at one says so. Two neighbouring intervals of one sign both
// unstable are one region: the boundary between them is another multiplier of that sign crossing
// inside it (on the paper blade at F̄ = 5, the −1 boundary at 514.29 rad/s inside the principal
// region, the upper edge of a mode-2 tongue of order 5), listed as `inner`. An interval whose check
// fails is listed as undecided, so one hard middle does not sink the verdicts that were reached.
#include <string>
#include <vector>

#include "bladestab/stability/boundaries.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct InstabilityRegion {
  double lower = 0, upper = 0;  // θ [rad/s], or F_max [N] along F̄; a window end where open
  bool lower_open = false, upper_open = false;  // ends at the window, not at a boundary
  // Ends at a boundary that did not converge (BoundaryAnalysis::unconverged): its value at the
  // highest k reached, not an estimate.
  bool lower_unconverged = false, upper_unconverged = false;
  int multiplier = -1, mode = 0, order = 0;  // mode and order 0 where both ends are the window's
  // The check: max|ρ| at the middle, > 1 + its error, and that error (absolute; the check raises the
  // fidelity only until the estimate decides the verdict, StabilityRequest::verdict_only).
  double middle_max_abs_multiplier = 0, middle_error_estimate = 0;
  // Set where the check failed (its analysis's one-line NumericalError, e.g. its share of
  // BoundaryRequest::work_flops spent): the interval may be a region or a gap, and is listed.
  std::string undecided;
  // Boundaries of the region's sign inside it, between intervals both checked unstable; the middle
  // reported is the interval's whose max|ρ| is largest.
  std::vector<double> inner;
};

// `analysis` from boundaries_with_error_estimate(scene, request); each middle is checked by
// analyse_stability at `tolerance`, or as far as decides it.
std::vector<InstabilityRegion> instability_regions(const Scene& scene, const BoundaryRequest& request,
                                                   const BoundaryAnalysis& analysis, double tolerance = 1e-4);

}  // namespace bladestab
