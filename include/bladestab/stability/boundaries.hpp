#pragma once
// The boundaries of the blade's regions of dynamic instability with their whole error against the
// continuum model of the scene (docs/theory.md §4): the boundary equations (ltp/boundary_equations.hpp)
// on the scene's periodic system, converged in the harmonics, checked by the multipliers.
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "bladestab/base/error_budget.hpp"
#include "bladestab/ltp/boundary_equations.hpp"
#include "bladestab/stability/periodic_system.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

// Boundaries with an estimate of their whole error against the continuum model of the scene.
struct BoundaryRequest {
  std::optional<double> theta_rad_s;  // set: boundary F_max at this θ; unset: boundary θ at the scene's F_max
  double cutoff_hz = 0;               // keep only the modes below (0: the scene's model.reduction)
  // The window of θ [rad/s] (or of F_max [N] with theta_rad_s) whose boundaries are reported and
  // converged; unset: θ/2 to 2θ of the scene's θ (0 to 2 F_max of the scene). The set of
  // boundaries is infinite (orders n → ∞ accumulate at θ → 0, thin high-order tongues at every
  // F_max) and new ones appear with every k, so only a window can converge.
  std::optional<std::pair<double, double>> window;
  // Orders n (θ ≈ 2ω/n) reported and converged: the thin tongues of high order converge slowly in
  // k (measured on the paper blade: mode 2, order 13 still moves 4e-3 from k = 8 to 10) and new
  // ones appear with every k.
  int max_order = 4;
  double tolerance = 1e-6;            // on the harmonics' part, relative on θ or F_max
  int first_approximation = 2;        // k to start from
  int max_approximation = 40;
  // The work the run may take, in dense eigensolver flops (boundary_level_flops): k, and the
  // automatic reduction's vectors, are raised only while the next step and the comparisons after
  // it fit (else BoundaryAnalysis::work_limited). The multiplier checks' monodromies together, and
  // the regions' Floquet verdicts together (instability_regions.hpp), may take a quarter of it each
  // (in magnus_step_work). Deterministic, unlike a clock.
  double work_flops = std::numeric_limits<double>::infinity();
  int threads = 1;                    // the two multiplier signs' eigenproblems side by side (0: one per core)
  // progress(done, total) after each harmonic level of each model: `total` is what the answer needs
  // if the current k converges (an upper bound), so it grows when k is raised; (done, done) at the end.
  std::function<void(int, int)> progress = {};
};

struct EstimatedBoundary {
  Boundary boundary;
  int approximation = 0;  // k its value comes from
  ErrorBudget budget;     // relative on θ (boundaries in θ) or on F_max (in F_max)
};

struct BoundaryCheck {
  Boundary boundary;      // the boundary checked, in the check's model
  double cutoff_hz = 0;   // the check's modal cut-off (0: all modes)
  double gap = 0;         // multiplier_gap there (where made)
  // False where the check's monodromy did not settle within max_magnus_steps or what is left of
  // the checks' quarter of BoundaryRequest::work_flops: the boundary is then listed as unconverged.
  bool made = true;
  double allowed = 0;     // the largest gap accepted
};

// A boundary of the window whose harmonics' part did not meet the tolerance by the largest k, or
// whose multiplier check failed there: where it was at the highest k it was compared at, and how
// far it got.
struct UnconvergedBoundary {
  Boundary boundary;             // its value at `approximation`
  int approximation = 0;         // k of that value, compared with k + 2
  std::optional<double> change;  // relative change from k to k + 2; none: no counterpart at k + 2
  bool check_failed = false;     // converged in k, but its multiplier check (in `checks`) failed
};

struct BoundaryAnalysis {
  ReductionSpec reduction;  // the model's reduction the boundaries come from
  int reduced_size = 0, full_size = 0;  // its dofs, and the Ritz model's
  int approximation = 0;  // the chosen k: boundaries of k (and, those that appear only there, of k + 2)
  std::pair<double, double> window;  // the window used
  std::vector<EstimatedBoundary> boundaries;  // converged to the tolerance; sorted by θ or F_max
  std::vector<UnconvergedBoundary> unconverged;  // not converged by max_approximation; sorted likewise
  std::vector<BoundaryCheck> checks;
  // k (or the reduction) was not raised further because request.work_flops would not allow it:
  // the unconverged boundaries (or a reduction part above the tolerance) are what that left.
  bool work_limited = false;
  ErrorBudget total() const;  // each part the largest over the (converged) boundaries
};

// The dense eigensolver work of harmonic level k of the boundary equations on `dofs` dofs: both
// multiplier signs (2k and 2k + 1 harmonics), each a real eigenproblem of harmonics·dofs unknowns,
// doubled by the linearization in θ (in_theta), counted as 3 N³ + 800 N² flops at
// cli::dense_flops_per_second: 1.5–3× the measured time of LAPACK's dgeev with eigenvectors on the
// boundary equations (one core, 28 Nov 2026: 0.9 ms at N = 72, 8.4 ms at 216, 0.16 s at 754, 0.88 s
// at 1440; its ~26 N³ flops at 1.1e10 to 8.9e10 per second).
double boundary_level_flops(int k, int dofs, bool in_theta);

// The memory of the larger eigenproblem of that level (2k + 1 harmonics): ~64 N² bytes for N
// unknowns (the pencil's matrices, their linearization, dgeev's copy, its eigenvectors real and
// complex; measured 1.65 GB at N = 5340, the whole model of 178 terms at k = 2 in θ).
double boundary_level_bytes(int k, int dofs, bool in_theta);

// The automatic reduction is also compared with the whole model at this k (or the answer's, if
// lower): a few whole-model levels cost about as much as all the reduced ones.
inline constexpr int whole_model_approximation = 4;

// Dofs of the richer-basis model the basis part is measured against, for a model of `dofs` of its
// `all_dofs`: a reduced model keeps its size (the same vectors, or the same cut-off), the whole
// Ritz model grows with the terms (reference_terms).
int richer_basis_dofs(const ModelSpec& spec, int dofs, int all_dofs);

// The reduction the boundaries start from: modes below request.cutoff_hz if set, else the scene's
// model.reduction; where that leaves the vectors to the program, the automatic reduction with
// tongue_vectors for the window's highest θ (or the request's θ) and max_order.
ReductionSpec boundary_reduction(const BladeModel& model, const Scene& scene, const BoundaryRequest& request);

// Raises k from request.first_approximation in steps of 2 until every boundary found at k in the
// window, of order ≤ max_order, moves by at most request.tolerance (relative) at k + 2 — boundaries
// are matched by multiplier sign, mode, order and nearest value (across a change of order where the
// dominant harmonic flips); one that first appears at k + 2 is reported from k + 2 with its change
// at k + 4. Where some do not converge by max_approximation (k + 4 ≤ it), those that did are the
// answer at the last k and the others are listed in `unconverged`: a tongue that pinches (high
// orders at low θ, or a load whose stiffness touches zero) does not sink the rest. (The method
// part is twice the change, so "converged" means 2·change + rounding ≤ tolerance.)
// The error budget of each boundary (docs/theory.md §2–§4):
//   basis      change against the richer Ritz basis reference_terms(basis, N), times
//              basis_tail_factor (basis_convergence: sine basis, section tables)
//   reduction  with a cut-off: the change against all modes kept; with the automatic reduction:
//              twice the change against twice the vectors (the change against the whole model
//              where that is next), the vectors doubled (and k converged again from where it was)
//              while this part is above half the tolerance, unless the scene sets them
//   load       change against a series with a 10 times smaller tail (load.approximation =
//              "fourier"); 0 for the cosine approximation (42), which is the scene's load
//   method     twice the change from k to k + 2 harmonics (or k + 2 to k + 4), plus the
//              eigensolver's rounding
// Then the multiplier at the (one or two) lowest-order converged boundaries is checked by
// multiplier_gap on a system cut off at 200·order·θ/2π (few Magnus steps a period); a failed check
// raises k, and at the last k the boundary whose check failed is listed as unconverged, never
// reported as a number.
// std::invalid_argument unless 1 ≤ first_approximation ≤ max_approximation − 4.
BoundaryAnalysis boundaries_with_error_estimate(const Scene& scene, const BoundaryRequest& request);

}  // namespace bladestab
