#pragma once
// Stability maps (docs/theory.md §4 "Charts"): regions of dynamic instability in the (θ, F̄_max) plane at
// the scene's speed (Ince–Strutt) or in the (Ω, F̄_max) plane with θ = k Ω (an engine order).
// The ±1 boundaries are traced as curves from the boundary eigenproblems — along F̄ in the θ
// plane (all θ at once), along Ω in the speed plane (all F̄ at once), on a reduced model checked
// against the whole Ritz model, a richer basis and more harmonics — and Floquet max|ρ| shades
// the regions, which also reveals combination resonances. The shading starts on the given grid
// and splits, like a quadtree, every cell whose corners disagree about stability or that holds a
// traced boundary point, until the cells reach the requested resolution.
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/stability/combination_resonance.hpp"
#include "bladestab/base/error_budget.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

enum class MapPlane { theta_fmax, speed_fmax };

struct MapOptions {
  MapPlane plane = MapPlane::theta_fmax;
  std::vector<double> grid_x, grid_fbar;  // shading grid: θ or Ω [rad/s], F̄
  std::vector<double> trace;              // curve parameter: F̄ values (θ plane) or Ω values (speed plane)
  int engine_order = 1;                   // speed plane: θ = k Ω
  int approximation = 4;                  // harmonics per multiplier sign in the boundary equations (at least)
  int max_order = 4;                      // boundary curves drawn from orders n ≤ max_order (θ ≈ 2ω/n); traced to 2·max_order
  double tolerance = 1e-3;                // on max|ρ| of the shading and on the curves (CurveFidelity)
  int resolution_x = 400, resolution_y = 200;  // effective cells of the refined shading (at least)
  int threads = 0;  // worker threads (0: one per core)
  // The work of the map, in dense eigensolver flops (boundary_level_flops): the curves' model is not
  // raised to a level whose check and trace lines would pass half of it (CurveFidelity::
  // work_limited). Each shading point's Floquet ladder may take work_flops / (4 · grid points)
  // (FloquetOptions::max_flops); a point that has not converged within it is left undecided
  // (StabilityMap::undecided). Deterministic, unlike a clock.
  double work_flops = std::numeric_limits<double>::infinity();
};

// One evaluated shading point.
struct MapSample {
  double x = 0, fbar = 0, max_abs_multiplier = 0;
};

// A leaf of the refinement on the fine lattice: cells [i, i + width) × [j, j + height), the
// largest max|ρ| of its corners (NaN where a corner has no periodic load).
struct MapCell {
  int i = 0, j = 0, width = 1, height = 1;
  double max_abs_multiplier = 0;
};

// A drawn boundary curve: a part of order ≤ max_order continued, through its changes of name,
// to where it meets another curve or leaves the plot (stability_map.cpp, drawn_curves). Named by
// its lowest-load point's dominant mode and order (θ ≈ 2ω_mode/order there).
struct BoundaryCurve {
  int multiplier = -1, mode = 0, order = 0;
  std::vector<double> x, fbar;  // θ or Ω, F̄
};

// The model the boundary curves were traced on and their error, measured on a few trace lines
// as distances along the line over the window's span (θ_max − θ_min in the θ plane, F̄_max of
// the window in the speed plane); a missing or extra boundary counts as the whole span.
struct CurveFidelity {
  ReductionSpec reduction;        // automatic (with its vectors per load level) or none
  int approximation = 0;          // harmonics per multiplier sign
  std::vector<double> checked_at; // the trace values (F̄ or Ω) of the lines checked
  ErrorBudget budget;
  bool tolerance_met = false;     // budget.total() ≤ the map's tolerance
  bool work_limited = false;      // not raised further: the next level's check passes MapOptions::work_flops
  bool drawn = true;              // false for a pulse's own series: no curves (stability_map.cpp)
};

// The shading's reduced model and its check on points of the grid against twice the vectors.
struct ShadingCheck {
  double x = 0, fbar = 0, relative_error = 0;
};
struct ShadingFidelity {
  int reduction_vectors = 0;          // automatic reduction, vectors per load level; 0: the whole Ritz model
  std::vector<ShadingCheck> checked;  // the grid points checked and each one's reduction part
  double reduction_error = 0;         // the largest, relative to max(1, max|ρ|)
  bool tolerance_met = false;
  // The basis checked on the same grid points against the richer basis (reference_terms; the sine
  // basis also against the same terms in the Legendre basis): the largest part, relative, and the
  // points it was measured on.
  double basis_error = 0;
  std::vector<ShadingCheck> basis_checked;
};

// The scene's own point on the map: its max|ρ| (on the shading's model, at the map's tolerance)
// and the nearest boundary drawn along F̄ at its θ or Ω.
struct MapPoint {
  double x = 0, fbar = 0, max_abs_multiplier = 0;  // NaN where undecided
  std::string undecided;  // why its Floquet ladder stopped short of its tolerance (its work, as a shading point's)
  struct Nearest {
    double fbar = 0;
    int multiplier = 0, mode = 0, order = 0;
  };
  std::optional<Nearest> nearest_boundary;
};

// A combination resonance found in the shading (combination_resonance.hpp): the samples whose
// unstable multiplier is complex, each named by the modes it couples at its own mean load, and
// grouped into islands (samples of one combination within a grid cell of each other); one entry
// per island of at least 3 samples, at its sample of largest max|ρ|, where it is labelled (an
// island need not touch the F̄ = 0 axis, as the principal tongues do).
struct CombinationRegion {
  Combination combination;
  double x = 0, fbar = 0, max_abs_multiplier = 0;  // the sample of largest max|ρ|
  int samples = 0;                                 // the island's samples
};

struct StabilityMap {
  MapPlane plane = MapPlane::theta_fmax;
  std::vector<double> grid_x, grid_fbar;
  Eigen::MatrixXd max_abs_multiplier;  // rows: F̄, columns: x; NaN where the point has no periodic load or is undecided
  int cells_x = 0, cells_y = 0;        // the fine lattice: the grid's cells split 2^k times
  std::vector<MapSample> samples;      // every evaluated point, the grid's included
  std::vector<MapCell> cells;          // the refinement's leaves, covering the window
  double max_error_estimate = 0;
  // The shading points whose Floquet ladder did not converge within their work (MapOptions::
  // work_flops; max|ρ| NaN): shaded as a verdict of their own. `undecided_reason`: the first one's.
  std::vector<MapSample> undecided;
  std::string undecided_reason;
  std::vector<BoundaryCurve> curves;
  std::vector<CombinationRegion> combinations;  // by x, then F̄
  CurveFidelity curve_fidelity;
  ShadingFidelity shading_fidelity;
  std::optional<MapPoint> scene_point;  // where the window holds the scene's (θ or Ω, F̄)
};

// `progress(done, total)` counts shading points and traced parameter values.
StabilityMap stability_map(const Scene& scene, const MapOptions& options,
                           const std::function<void(int, int)>& progress = {});

}  // namespace bladestab
