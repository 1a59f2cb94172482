#pragma once
// The whole error of a transient's reported quantities against the continuum model of its scene
// (base/error_budget.hpp): the tip peaks, the largest vibration energy and the growth per
// revolution, each with
//
//   basis      the same run on a richer Ritz model (reference_terms, modal/basis_error.hpp), over
//              the same time (a stopped run: to its stop), the difference times the algebraic tail
//              (basis_tail) at the slowest trusted rate, or for the sine basis at the rate a third
//              model measures: a response to a concentrated tip load converges algebraically (the
//              axial tip peak, half-sine train: ratio 0.22 of the errors from 12 to 18 terms, where
//              1.1 × the difference fell 15 % short); plus the richer runs' own errors
//   reduction  0: the transient runs the whole Ritz model
//   load       0: the transient runs the scene's true pulse train
//   method     the time stepping: the fast method's contact propagators (their step-doubling bound
//              for each piece of the first contact, or the self-check's measured difference, the
//              larger) relative to the quantity; RKF45's tolerance; for the growth its fit's estimate
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bladestab/base/error_budget.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/transient/transient.hpp"

namespace bladestab {

struct TransientQuantity {
  std::string name;  // as in the JSON summary: peak_tip_lateral_m, …
  double value = 0;
  ErrorBudget budget;
};

// The measures of a run the estimate is about: |v(L)| and |u(L) − u_eq(L)| at their peaks, the
// largest vibration energy E(t) − E_eq, the mean of u(L) over the samples, the peak of |u(L)| (the
// table's axial "peak"), and the growth where the run reports one.
std::vector<TransientQuantity> transient_quantities(const TransientResult& result);

struct TransientErrorEstimate {
  std::vector<int> reference_terms;  // the richer models' (assemble_richer_models)
  std::vector<TransientQuantity> quantities;
};

// The richer models the estimate runs, assembled: the scene's at reference_terms (modal/basis_error.hpp), and
// for the sine basis also at reference_terms of that (2N and 4N, where 4N is within the limit of
// terms), whose difference measures the rate of convergence in basis_tail, as `modes` and
// `stability` measure it: the sine basis at 10 terms of the scene as shipped moves the lateral peak
// over 20 revolutions by 1.2 % to 20 terms and by 2.6 % more to 40, where 20 terms alone, at the
// slowest trusted rate, would state 1.4× too little.
std::vector<BladeModel> assemble_richer_models(const Scene& scene);

// The run `result` of `scene` with `options`, against the same on the richer models.
TransientErrorEstimate estimate_transient_error(const Scene& scene, const TransientOptions& options,
                                                const TransientResult& result);

// A run with its estimate, or why there is none.
struct EstimatedTransient {
  TransientResult result;
  std::optional<TransientErrorEstimate> error;
  std::string error_unavailable;  // a richer model's run failed: its one line
  bool work_limited = false;      // that run stopped at the work limit (WorkLimitError)
};

// The run of `model` and its estimate against `richer` (assemble_richer_models): the
// richer runs start beside the run (WorkPool, options.threads) over the same revolutions, so the
// estimate costs little wall time on two cores; a run that stops early is compared over its own
// window, and the richer models then run again to that stop. A failure of a richer run (a work
// limit, a check of its own) leaves the run without an estimate and says why. `richer_progress`
// (optional) hears the richer runs' contact pieces and revolutions, from their own threads; what
// it throws stops the run.
EstimatedTransient run_transient_with_error(const BladeModel& model, const std::vector<BladeModel>& richer,
                                            const Scene& scene,
                                            const TransientOptions& options,
                                            const std::function<void(int, int)>& richer_progress = {});

}  // namespace bladestab
