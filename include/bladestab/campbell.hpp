#pragma once
// Campbell diagram: natural frequencies versus rotor speed, each mode followed through crossings
// and veering by the correlation of its shape from one speed to the next (mass-weighted MAC),
// and the speeds where an engine-order line f = k Ω/2π meets a mode.
#include <functional>
#include <vector>

#include "bladestab/modes.hpp"
#include "bladestab/scene.hpp"

namespace bladestab {

struct CampbellOptions {
  std::vector<double> speeds_rad_s;  // increasing
  std::vector<int> engine_orders;
  int mode_count = 8;
  EigenSolverKind solver = EigenSolverKind::automatic;
};

struct CampbellCurve {
  int mode = 0;                           // 1-based, by frequency at the first speed
  ModeFamily family = ModeFamily::bending; // at the first speed
  std::vector<double> frequency_hz;       // one per speed
  std::vector<double> damping_ratio;
  std::vector<double> correlation;        // MAC with the previous speed's shape (1 at the first)
};

struct EngineOrderCrossing {
  int engine_order = 0;
  int mode = 0;
  double speed_rad_s = 0;
  double frequency_hz = 0;
};

struct CampbellDiagram {
  std::vector<double> speeds_rad_s;
  std::vector<int> engine_orders;
  std::vector<CampbellCurve> curves;
  std::vector<EngineOrderCrossing> crossings;  // sorted by speed
  EigenSolverKind solver = EigenSolverKind::dense;
};

// `progress(done, total)` is called after each speed.
CampbellDiagram campbell_diagram(const BladeModel& model, const DampingSpec& damping, const CampbellOptions& options,
                                 const std::function<void(int, int)>& progress = {});

}  // namespace bladestab
