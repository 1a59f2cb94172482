#pragma once
// When a ladder of step counts N₀, 2N₀, 4N₀, … of a sixth-order method (the Magnus propagator,
// docs/theory.md §4) has converged, and how large the error of its last level is.
//
// Level N gives a result; Δ_N is its distance to level N/2's and r = Δ_{N/2}/Δ_N:
//  - 16 ≤ r ≤ 256: the method is in its asymptotic range (a doubling divides a sixth-order error
//    by ~64); the error of level N is then at most Δ_N/15, the bound for a convergence of fourth
//    order or better from here on;
//  - 4 ≤ r < 16, or Δ_{N/2} within the tolerance as well, or N at or past the count `safe` from
//    which the method is known to converge (for Magnus: h‖A‖ ≤ 2): the error is taken as Δ_N;
//  - otherwise the level is not trusted, however small Δ_N: with r > 256 level N/2 was
//    pre-asymptotic and may have landed near the answer by chance (measured on the paper blade:
//    Δ_N 15× below the true error at F̄ = 12, N = 256), and two levels alone show no contraction.
// Knows nothing of what is integrated: the caller computes the levels and their distances.
#include <limits>
#include <optional>
#include <string>

namespace bladestab {

class StepDoubling {
 public:
  // Levels first, 2·first, … up to `last`; `safe` as above. A work bound keeps only the levels whose
  // steps together (2L − first up to level L) take at most `max_work` at `step_work` a step, and
  // none where not even the first two, the fewest that can converge, fit. last() is the last level
  // kept (0: none). std::invalid_argument unless first ≥ 1.
  StepDoubling(int first, int last, int safe, double step_work = 0,
               double max_work = std::numeric_limits<double>::infinity());

  int first() const { return first_; }
  int last() const { return last_; }
  int safe() const { return safe_; }
  // The number of levels from `first` to `last`.
  int levels() const;

  // Judges level `steps` whose result lies `distance` from the level before (the first level of a
  // ladder has none: call start()). Returns the error bound, at least `floor` (what the result's
  // own rounding allows), when it is within `allowed`.
  std::optional<double> judge(int steps, double distance, double allowed, double floor = 0);
  // Forgets the distances seen, as at the ladder's first level (also after a level that failed,
  // e.g. overflowed, so that its neighbours are never compared).
  void start();
  // Level `steps` overflowed: forgets the distances (start()). True when the level before (steps/2)
  // overflowed too and was at or past `safe`, where a step is short enough: the result itself grows
  // past the double range, and no level will settle.
  bool overflowed(int steps);
  // The failure of a ladder that ended unconverged: "<what> within <last> <unit>", thrown as
  // WorkLimitError where the work bound cut levels off (the message says so), else as NumericalError.
  [[noreturn]] void give_up(const std::string& what, const std::string& unit) const;

 private:
  int first_, last_ = 0, safe_, most_;  // most_: the `last` asked for
  bool work_limited_ = false;           // the work bound cut levels off
  std::optional<double> previous_distance_;
  int last_overflow_ = 0;  // the steps of the last level that overflowed (0: none)
};

}  // namespace bladestab
