#pragma once
// Campbell diagram: natural frequencies versus rotor speed, each mode followed through crossings
// and veering by the correlation of its shape from one speed to the next (mass-weighted MAC),
// and the speeds where an engine-order line f = k Ω/2π meets a mode.
//
// The modes at every speed come from a SpeedSweep (include/bladestab/speed_sweep.hpp): for an
// undamped blade one reduced basis for the whole speed range, every frequency bounded against the
// whole Ritz model; otherwise (damping, or the dense or ARPACK solver asked for) a whole solve per speed.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bladestab/base/error_budget.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

struct CampbellOptions {
  std::vector<double> speeds_rad_s;  // increasing
  std::vector<int> engine_orders;
  int mode_count = 8;
  EigenSolverKind solver = EigenSolverKind::automatic;  // automatic: the reduced sweep where it applies
  double reduction_tolerance = 1e-8;  // relative bound wanted on the reduced model's frequencies
  bool closest_approaches = false;    // also find each curve's closest approach to each line
  int threads = 0;                    // the richer models of the estimate beside the base model unless 1 (0: per core)
  std::string speeds_text{};          // the speeds as the user gave them, for messages (e.g. "0:600:61")
  // campbell_with_error_estimate: the work its rounds may take, counted as their whole-model
  // eigensolves (whole_eigensolve_flops); a round that would pass it is not started.
  double work_flops = std::numeric_limits<double>::infinity();
};

struct CampbellCurve {
  int mode = 0;                           // 1-based, by frequency at the first speed
  ModeFamily family = ModeFamily::bending; // at the first speed
  // At each speed, by the point's own kinetic-energy shares (dominant_family): where a flap and an
  // edge mode veer, the curve followed by shape changes family.
  std::vector<ModeFamily> families;
  std::vector<double> frequency_hz;       // one per speed
  std::vector<double> damping_ratio;
  std::vector<double> correlation;        // MAC with the previous speed's shape (1 at the first)
  std::vector<double> reduction_bound;    // relative bound on |f − f_Ritz model| / f (0 when solved whole)
  std::vector<double> rounding;           // relative rounding of f (frequency_rounding)
};

struct EngineOrderCrossing {
  int engine_order = 0;
  int mode = 0;
  double speed_rad_s = 0;
  double frequency_hz = 0;
  // The whole Ritz model's f − kΩ/2π at the reported speed, relative to f: what is left of the
  // root after the refinement (the crossing is refined on the sweep's modes, then confirmed and
  // corrected by whole-model solves).
  double residual = 0;
  // Relative error of the crossing speed per relative error of the frequency there:
  // 1/|1 − (Ω/f) df/dΩ| = (k/2π) / |d(f − kΩ/2π)/dΩ|.
  double amplification = 1;
};

// How near a curve comes to an engine-order line inside the diagram's speeds: the least relative
// distance min over Ω of |f(Ω) − kΩ/2π| / f(Ω), 0 where they cross. Located on the continuous
// curve (the mode followed by its shape between the speeds): a crossing where there is one, else
// the least of the speeds refined by golden-section search between its neighbours; the distance
// is the whole Ritz model's there.
struct EngineOrderApproach {
  int engine_order = 0;
  int mode = 0;
  double speed_rad_s = 0;
  double frequency_hz = 0;
  double distance = 0;  // |f − kΩ/2π| / f
};

struct CampbellDiagram {
  std::vector<double> speeds_rad_s;
  std::vector<int> engine_orders;
  std::vector<CampbellCurve> curves;
  std::vector<EngineOrderCrossing> crossings;  // sorted by speed
  std::vector<EngineOrderApproach> approaches;  // per engine order and curve, when asked for
  EigenSolverKind solver = EigenSolverKind::dense;
  bool reduced = false;                     // the reduced sweep served the diagram
  int basis_vectors = 0;                    // its size (the dofs when solved whole)
  std::vector<double> sample_speeds_rad_s;  // where its basis was taken
};

// `progress(done, total)` is called after each speed. The speeds are the caller's to keep within
// the model's static limits (speeds_within_limits); campbell_with_error_estimate does.
CampbellDiagram campbell_diagram(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                                 const std::function<void(int, int)>& progress = {});

// A Campbell diagram with the whole error of every point and crossing against the continuum model.
struct CampbellWithErrors {
  BladeModel model;                  // the model the curves belong to (its terms met the tolerance)
  CampbellDiagram diagram;           // at the speeds within the blade's static limits
  // The speeds asked for against the static limits (static_limits.hpp): the diagram holds those
  // in [first, end); `before` and `after` are the limits it meets, `where` in rad/s.
  PathWithinLimits static_limits;
  double tolerance = 0;
  std::vector<int> reference_terms;  // the richer models of the basis estimate
  // [curve][speed], relative on the frequency: basis (the change against the richer models, as
  // `modes` forms it, plus their reduction bounds), reduction (the point's bound), method.
  std::vector<std::vector<ErrorBudget>> budget;
  // Per crossing (same order), relative on its speed and frequency: the frequency's budget at the
  // crossing times the amplification; the reduction part is what the whole-model check left.
  std::vector<ErrorBudget> crossing_budget;
  // Per approach (same order), absolute on its distance: the frequency's budget there times
  // kΩ/(2πf), the distance's sensitivity to a relative error of f.
  std::vector<ErrorBudget> approach_budget;
  double work_flops = 0;  // the whole-model eigensolves of every round, counted as CampbellOptions::work_flops

  // Each part the largest over the points where the mode oscillates and over the crossings: the
  // tolerance holds there. A point whose mode does not oscillate (overdamped: 0 Hz) has no
  // frequency to hold to it; its budget is 1 where the richer model's counterpart oscillates or is missing.
  ErrorBudget worst() const;
  int points_not_oscillating() const;
  ErrorBudget worst_at(std::size_t speed) const;   // each part the largest over the curves there
};

// The diagram of `scene` with its errors. Only the speeds within the blade's static limits (at the
// scene's static tip compression; the scene's own speed plays no part) are solved: the diagram
// starts after a limit below them and stops before one above (speeds_within_limits, on the
// model the curves belong to), and says where they lie; ParameterError "speeds" when every speed is past one.
// The terms start at the scene's and are raised (Legendre + 2, sine × 2) until every curve's
// whole estimate is within `tolerance` at every speed; the reduced sweep's part is held to
// tolerance/20. InputError when the tolerance cannot be met (terms_for_tolerance) or is out of
// range. Crossings carry their estimate but do not steer the
// terms (near a tangency their amplification is unbounded). WorkLimitError, naming the terms it
// would take and the estimate reached, when the next round would pass options.work_flops.
CampbellWithErrors campbell_with_error_estimate(const Scene& scene, const CampbellOptions& options, double tolerance,
                                                const std::function<void(int, int)>& progress = {});

}  // namespace bladestab
