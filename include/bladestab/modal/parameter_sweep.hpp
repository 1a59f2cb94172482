#pragma once
// Natural frequencies against any numeric scene key (`bladestab sweep`), e.g. the slenderness d̄
// (Sinha's Figs. 7, 8) or a static tip compression F_a / F_cr (Fig. 9).
//
// For each value the scene is read again with "key=value" applied after `overrides` (the
// scene's own override machinery, so every key is validated as in a scene file), its model
// assembled (assemble_model: a static tip compression included) and its modes solved at the
// scene's speed with their error estimates, as `modes` does (modes_with_error_estimate). The
// lowest `mode_count` modes of the first value are followed from value to value by their shapes
// (mass-weighted MAC, mode_tracking.hpp) while the number of dofs stays the same, and by
// frequency order where it changes (model.terms, model.axial, model.theory).
#include <functional>
#include <string>
#include <vector>

#include "bladestab/blade/model.hpp"
#include "bladestab/blade/static_limits.hpp"
#include "bladestab/modal/modes.hpp"

namespace bladestab {

struct ParameterSweepOptions {
  std::string key;          // "section.key": a scene key that takes a number
  std::string values_text;  // the values as the user gave them (e.g. "a:b:n"), for messages
  std::vector<double> values;
  int mode_count = 8;
  EigenSolverKind solver = EigenSolverKind::automatic;
  int threads = 0;  // values solved at once (0: one per core)
};

// How the modes at a value were matched to the previous value's.
enum class ModeMatch { first, shape, order };
const char* to_string(ModeMatch);

struct SweptMode {
  int index = 0;                          // 1-based, by frequency at the first value
  ModeFamily family = ModeFamily::bending;  // at the first value
  std::vector<ModeFamily> families;       // at each value (veering can change it)
  std::vector<double> frequency_hz;       // one per value
  std::vector<double> lambda;             // Λ = ω L² sqrt(ρA/(EI)) with that value's blade
  std::vector<double> damping_ratio;
  std::vector<double> correlation;        // MAC with the previous value's shape: 1 at the first
                                          // value, NaN where matched by order
  std::vector<double> error_estimate;     // whole relative estimate (basis + method), as `modes`
};

struct ParameterSweep {
  BladeModel model;                     // the first value's model
  std::string key;
  std::vector<double> values;           // those solved: the run within the blade's static limits
  // The values asked for against the static limits (static_limits.hpp): `values` are those in
  // [first, end); `before` and `after` the limits the sweep meets, `where` in the key's units.
  PathWithinLimits static_limits;
  bool ascending = true;                // the values asked for ascend
  std::vector<double> speeds_rad_s;     // the scene's speed at each value
  std::vector<int> dofs;                // the model's dofs at each value
  std::vector<int> reference_terms;     // of the richer model of the error estimate, per value
  std::vector<ModeMatch> matched_by;    // per value
  EigenSolverKind solver = EigenSolverKind::dense;  // the one used at the first value
  std::vector<SweptMode> modes;

  double max_error_estimate() const;    // over every point
  double min_correlation() const;       // over the points matched by shape (1 if none)
};

// The sweep of the scene given as TOML text (`source` names it in messages). The values are
// solved from the first one within the blade's static limits (at each value's operating point) up
// to the next one past them; where the sweep meets a limit is found by root search on the key
// (path_within_limits). ParameterError, one line, on `key` for a key the scene does not have, does
// not use or that takes no number; on `values` for a value the key does not allow (the scene's
// message) or when every value is past the static limits; on `count` when a value's model has
// fewer modes.
// `progress(done, total)` after each value.
ParameterSweep parameter_sweep(const std::string& scene_text, const std::string& source,
                               const std::vector<std::string>& overrides, const ParameterSweepOptions& options,
                               const std::function<void(int, int)>& progress = {});

// The TOML text of a swept value: an integer where the value is one (so integer keys such as
// model.terms take it), else the shortest text that reads back as the same double.
std::string scene_value_text(double value);

}  // namespace bladestab
