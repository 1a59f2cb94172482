#pragma once
// Dynamic stability of a scene at its operating point, with the whole error against the
// continuum model (issue "every answer right or refused"):
//
//  1. the LTP system on the automatic reduction of the scene's Ritz model (reduction.hpp); the true
//     pulse train on the whole Ritz model where its contacts are short against its stiffest period
//     (it is integrated only through them, and its narrow tongues need the high modes);
//  2. Floquet multipliers by the requested method, with its own checks (floquet.hpp);
//  3. the error budget on max|ρ|, each part from a second computation that differs in that part only
//     (each on its own thread, started with the answer: none depends on it):
//       basis      the same at the richer Ritz basis of basis_error.hpp (sine: ×2, its
//                  algebraic convergence makes the difference understate the error up to 2×);
//       reduction  the reduced model against one with twice the vectors (×2: projections do not
//                  converge monotonically), or, for a modal cut-off, against the automatic reduction;
//       load       the series against the true pulse train ("fourier"); 0 where the scene's load is
//                  the series itself (the cosine approximation (42)) or the true train ("exact");
//       method     step or harmonic convergence of the whole multiplier set;
//  4. fidelity raised where the budget exceeds the tolerance (terms, vectors, steps), as far as the
//     scene leaves it free and more terms can reach it (basis_can_reach, basis_error.hpp); what
//     was chosen is reported, and a tolerance not met says why.
#include <functional>
#include <limits>
#include <string>

#include "bladestab/base/error_budget.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct StabilityRequest {
  FloquetMethod method = FloquetMethod::automatic;
  int harmonics = 0;        // Hill methods' q; 0 = raised to the tolerance
  double tolerance = 1e-6;  // on max|ρ|, relative above 1
  int threads = 0;          // the budget's variants beside the answer: at most this many at once (0: one per core)
  // progress(done, total): the answer's refinement levels (FloquetOptions::progress) and then each
  // budget variant as it is taken, over every fidelity round; `total` overstates; (n, n) at the end.
  std::function<void(int, int)> progress = {};
  // The work of one fidelity round, in eigensolver flops (magnus_step_work): the answer's and each
  // variant's monodromy ladder may take a quarter of it (FloquetOptions::max_flops); a ladder that
  // would pass its share throws WorkLimitError. The systems built over all rounds (the answer's and
  // the variants', periodic_system_flops) may take another quarter: the first round's throw
  // WorkLimitError past it, a later round is not started (StabilityAnswer::work_limited).
  // Deterministic, unlike a clock.
  double work_flops = std::numeric_limits<double>::infinity();
  // Stop raising the fidelity once the estimate decides the verdict: max|ρ| above 1 by more than the
  // total estimate, or below 1 + 1e-9 with it (the `stable` floor). For callers that need only
  // stable or not (instability_regions' middles); the answer then says the tolerance is not met.
  bool verdict_only = false;
};

struct StabilityAnswer {
  FloquetResult floquet;
  ErrorBudget budget;           // absolute, on max|ρ|
  bool stable = true;           // max|ρ| ≤ 1 + the total estimate
  bool tolerance_met = true;    // false where a fidelity fixed by the scene keeps the total above it
  std::string tolerance_unmet;  // why not, in one line ("tolerance 1e-06: not met with 10 terms per field …")
  bool work_limited = false;    // … because the next round's systems would pass the work (StabilityRequest::work_flops)
  ModelSpec model;              // the Ritz model used (terms raised to the tolerance)
  int reference_terms = 0;      // the richer basis of the basis part
  ReductionSpec reduction;      // as used (vectors chosen)
  int reduced_size = 0, full_size = 0;
  LoadSeries load;              // the series the system was built with
  double theta_rad_s = 0;
};

StabilityAnswer analyse_stability(const Scene& scene, const StabilityRequest& request);

// Whether an answer's estimate decides its verdict: max|ρ| above 1 by more than the estimate, or
// below 1 + 1e-9 with it (StabilityRequest::verdict_only; `stable` is max|ρ| ≤ 1 + the estimate).
bool verdict_decided(const StabilityAnswer& answer);

}  // namespace bladestab
