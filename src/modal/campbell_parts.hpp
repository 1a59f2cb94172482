#pragma once
// The parts of a Campbell diagram that its error estimate (campbell_estimate.cpp) shares with the
// diagram itself (campbell.cpp): the modes tracked by shape along a speed sweep, and the
// engine-order crossings and closest approaches found on them.
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/modal/campbell.hpp"
#include "bladestab/modal/speed_sweep.hpp"

namespace bladestab {

// A richer model's mode is the counterpart of a base mode if their shapes correlate at least this
// well (MAC); below it nothing is known about that point's basis error.
inline constexpr double counterpart_mac = 0.5;

// The curves followed: options.mode_count, at most the model's dofs.
int tracked_count(const BladeModel& model, const CampbellOptions& options);

// Modes solved per speed: a few more than tracked, so that modes entering from above can be followed.
int solve_count(const BladeModel& model, const CampbellOptions& options);

// Index of the mode in `modes` most like `shape` (unit columns: MAC = |aᴴ b|²), its MAC in `mac`.
int most_like(const SpeedModes& modes, const Eigen::VectorXcd& shape, double* mac = nullptr);

// The sweep's modes at `speed` with their bounds against the whole model; ReducedSweepUnavailable
// where a reduced sweep cannot bound some of them (the dense sweep then serves the estimate).
SpeedModes certified_modes(SpeedSweep& sweep, double speed);

// The sweep's modes at every speed and, per curve, which of them it follows.
struct Tracked {
  std::vector<SpeedModes> modes;       // per speed
  std::vector<std::vector<int>> pick;  // [curve][speed]
};

// The sweep at every speed of `options`, its modes followed by shape into the curves of `d`.
Tracked track(SpeedSweep& sweep, const BladeModel& model, const CampbellOptions& options, CampbellDiagram& d,
              const std::function<void(int, int)>& progress);

// Engine-order crossings, refined on the sweep's modes and then confirmed and corrected on the
// whole model. `shapes` receives, per crossing, the shape it followed.
void find_crossings(SpeedSweep& sweep, const Tracked& t, CampbellDiagram& d, std::vector<Eigen::VectorXcd>& shapes);

// Each curve's closest approach to each engine-order line (EngineOrderApproach), after the
// crossings. `shapes` receives, per approach, the shape it followed.
void find_closest_approaches(SpeedSweep& sweep, const Tracked& t, CampbellDiagram& d,
                             std::vector<Eigen::VectorXcd>& shapes);

}  // namespace bladestab
