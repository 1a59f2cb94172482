#pragma once
// A transient held to a tolerance on its whole error (docs/guide/transient.md, "A tolerance on the
// whole error"): the run and its estimate (transient_error.hpp) on the scene's terms; while a
// reported quantity's whole error is above tolerance × |value| (the growth: × max(1, |growth|)) and
// its basis part is the larger part, the terms are raised to the richer model's and both runs
// repeated. Raising stops, with the answer of the last round and the reason, where
//  - two raises in a row did not halve the basis part (raising no longer pays; one may not: the
//    shipped blade's lateral peak over 2 revolutions falls from 0.080 to 0.071 from 6 to 10 terms,
//    then to 0.0021 at 15);
//  - the next round may not start (the builder throws: a work limit, a model the scene cannot
//    build; or it has no richer model), or it fails its own checks (NumericalError), or its
//    estimate fails: the round before stands;
//  - the part above the tolerance is not the basis (the time stepping, or an unbounded part).
// The first estimate predicts nothing about the next: the response to a 0.2 ms tip pulse moves by
// 8 % from 16 to 24 terms of the scene as shipped and by 0.014 % from 24 to 32, so no rule of
// algebraic convergence (basis_can_reach) is asked before the first raise.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/transient/transient.hpp"
#include "bladestab/transient/transient_error.hpp"

namespace bladestab {

// A round: the run's model and options, and the richer models of its estimate (assemble_richer_models;
// none: why not).
struct TransientRoundModels {
  BladeModel model;
  std::vector<BladeModel> richer;
  std::string richer_unavailable;
  TransientOptions options;
};

// Builds the models of a round on `scene` (its model.terms raised); throws where its run may not
// start (InputError, e.g. a work limit).
using TransientRoundBuilder = std::function<TransientRoundModels(const Scene& scene)>;

// One round: the run of `m.model` with `m.options` and its estimate against `m.richer`
// (run_transient_with_error), or without one where there are no richer models (error_unavailable:
// m.richer_unavailable).
EstimatedTransient run_transient_round(const TransientRoundModels& m, const Scene& scene,
                                       const std::function<void(int, int)>& richer_progress = {});

struct TransientAtTolerance {
  EstimatedTransient run;  // the last round's
  BladeModel model;        // the model it ran
  bool tolerance_met = true;
  std::string tolerance_unmet;  // why not, one line
  bool work_limited = false;    // the rounds ended at the work limit (WorkLimitError)
};

// The rounds above on `scene` toward `tolerance` (0 < tolerance < 1). The first round's builder
// throws through; a later one's ends the rounds with its message as the reason.
TransientAtTolerance run_transient_to_tolerance(const Scene& scene, double tolerance, const TransientRoundBuilder& build,
                                                const std::function<void(int, int)>& richer_progress = {});

}  // namespace bladestab
