#include "bladestab/stability/boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <lapacke.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/ltp/floquet.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {
using cplx = std::complex<double>;

constexpr double check_monodromy_tolerance = 1e-10;  // on Φ(T) of the multiplier check, relative
// The check keeps the modes below check_reach·order·θ/2π: the monodromy's steps grow like the
// fastest kept frequency times the period (≈ 2π·check_reach·order radians a period); at 20 the
// paper blade's boundary at θ = 300 rad/s lost its Coriolis-coupled axial mode (1280 Hz) and moved 2 %.
constexpr double check_reach = 200;

double value_of(const Boundary& b, bool in_load) { return in_load ? b.peak_force_n : b.theta_rad_s; }

double relative_change(const Boundary& a, const Boundary& b, bool in_load) {
  return std::abs(value_of(a, in_load) / value_of(b, in_load) - 1);
}

// Pairs each boundary of `base` without a counterpart with the nearest unpaired boundary of its
// multiplier sign and mode in `other` where each is the other's nearest unpaired one, whatever their
// orders. The order is the dominant harmonic of the eigenvector, and where two harmonics weigh
// the same it flips from one model to the next: on Mathieu's blade at F̄ = 1 (the stiffness
// touches zero once a period) the +1 sign's constant and second harmonics tie, and the boundary
// at θ = 107.573 rad/s is named order 2 at k = 6, 12, 24 and order 0 at k = 8, 10, 16, 20, its
// value the same to 1e-10.
void pair_nearest(const std::vector<Boundary>& base, const std::vector<Boundary>& other, bool in_load,
                  std::vector<int>& counterpart) {
  std::vector<bool> taken(other.size(), false);
  for (int j : counterpart) {
    if (j >= 0) taken[j] = true;
  }
  const auto kin = [](const Boundary& a, const Boundary& b) { return a.multiplier == b.multiplier && a.mode == b.mode; };
  for (std::size_t i = 0; i < base.size(); ++i) {
    if (counterpart[i] >= 0) continue;
    int j = -1;  // the nearest unpaired boundary of other
    for (std::size_t c = 0; c < other.size(); ++c) {
      if (taken[c] || !kin(base[i], other[c])) continue;
      if (j < 0 || relative_change(base[i], other[c], in_load) < relative_change(base[i], other[j], in_load)) {
        j = static_cast<int>(c);
      }
    }
    if (j < 0) continue;
    bool mutual = true;  // and no unpaired boundary of base nearer to it
    for (std::size_t c = 0; c < base.size() && mutual; ++c) {
      mutual = c == i || counterpart[c] >= 0 || !kin(base[c], other[j]) ||
               relative_change(base[c], other[j], in_load) >= relative_change(base[i], other[j], in_load);
    }
    if (mutual) counterpart[i] = j, taken[j] = true;
  }
}

// For each boundary of `base`, the index of its counterpart in `other`, or −1. Within each
// multiplier, mode and order both are taken in order of value and the shorter run is laid along the
// longer at the offset of least total relative distance: the two edges of a region keep their
// order even when a model change moves them by more than the region is wide (nearest-value
// matching pairs both edges of the paper blade's order-3 region with one edge under a cut-off).
// Those left over are paired across a change of name (pair_nearest).
std::vector<int> match(const std::vector<Boundary>& base, const std::vector<Boundary>& other, bool in_load) {
  std::vector<int> counterpart(base.size(), -1);
  const auto same_kind = [](const Boundary& a, const Boundary& b) {
    return a.multiplier == b.multiplier && a.mode == b.mode && a.order == b.order;
  };
  std::vector<bool> done(base.size(), false);
  for (std::size_t first = 0; first < base.size(); ++first) {
    if (done[first]) continue;
    std::vector<std::size_t> x, y;  // indices of this kind, by value
    for (std::size_t i = 0; i < base.size(); ++i) {
      if (same_kind(base[i], base[first])) x.push_back(i), done[i] = true;
    }
    for (std::size_t j = 0; j < other.size(); ++j) {
      if (same_kind(other[j], base[first])) y.push_back(j);
    }
    const auto by_value = [&](const std::vector<Boundary>& v) {
      return [&v, in_load](std::size_t p, std::size_t q) { return value_of(v[p], in_load) < value_of(v[q], in_load); };
    };
    std::sort(x.begin(), x.end(), by_value(base));
    std::sort(y.begin(), y.end(), by_value(other));
    // Pair x[i] with y[i + shift] (shift ≥ 0) or x[i − shift] with y[i] (shift < 0).
    const int lo = -static_cast<int>(x.size() > y.size() ? x.size() - y.size() : 0);
    const int hi = static_cast<int>(y.size() > x.size() ? y.size() - x.size() : 0);
    double best = std::numeric_limits<double>::infinity();
    int best_shift = 0;
    for (int shift = lo; shift <= hi; ++shift) {
      double total = 0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const long j = static_cast<long>(i) + shift;
        if (j >= 0 && j < static_cast<long>(y.size())) total += relative_change(base[x[i]], other[y[j]], in_load);
      }
      if (total < best) best = total, best_shift = shift;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      const long j = static_cast<long>(i) + best_shift;
      if (j >= 0 && j < static_cast<long>(y.size())) counterpart[x[i]] = static_cast<int>(y[j]);
    }
  }
  pair_nearest(base, other, in_load, counterpart);
  return counterpart;
}

// The boundaries of one model of the scene, cached per approximation k. The two multiplier
// signs are independent eigenproblems of equal size: with two threads the +1 sign's runs beside the −1's.
// `solved(k)` is called after each new k.
class BoundarySolver {
public:
  BoundarySolver(PeriodicSystem system, double peak, std::optional<double> theta, int threads,
                 std::function<void(int)> solved)
      : system_(std::move(system)), peak_(peak), theta_(theta), threads_(threads), solved_(std::move(solved)) {}
  const std::vector<Boundary>& at(int k) {
    auto it = cache_.find(k);
    if (it == cache_.end()) {
      const auto of_sign = [this, k](int multiplier) {
        return theta_ ? boundary_loads(system_, peak_, *theta_, k, multiplier)
                      : boundary_frequencies(system_, peak_, k, multiplier);
      };
      std::vector<std::vector<Boundary>> sides =
          run_indexed(2, threads_, [&](std::size_t side) { return of_sign(side == 0 ? -1 : 1); });
      std::vector<Boundary>& both = sides[0];
      both.insert(both.end(), sides[1].begin(), sides[1].end());
      std::sort(both.begin(), both.end(), [this](const Boundary& a, const Boundary& b) {
        return value_of(a, theta_.has_value()) < value_of(b, theta_.has_value());
      });
      it = cache_.emplace(k, std::move(both)).first;
      if (solved_) solved_(k);
    }
    return it->second;
  }
  bool has(int k) const { return cache_.count(k) > 0; }
  const PeriodicSystem& system() const { return system_; }
  double peak() const { return peak_; }

private:
  PeriodicSystem system_;
  double peak_;
  std::optional<double> theta_;
  int threads_;
  std::function<void(int)> solved_;
  std::map<int, std::vector<Boundary>> cache_;
};

// The method part from the change δ between k and k + 2 harmonics: the tail of a convergence at
// least geometric with ratio 1/2 per step is at most 2δ (measured on the paper blade: ratios
// 1e-4 to 3e-5 per step at θ = 300; δ alone came out 0.99997 of the change to k = 12), plus the
// eigensolver's rounding.
double harmonics_error(double change) { return 2 * change + eigensolver_rounding; }

// Estimated and unconverged boundaries alike, in order of θ or F_max.
template <class Entry>
void sort_by_value(std::vector<Entry>& all, bool in_load) {
  std::sort(all.begin(), all.end(), [in_load](const Entry& a, const Entry& b) {
    return value_of(a.boundary, in_load) < value_of(b.boundary, in_load);
  });
}

// The counterparts of `base` at more harmonics: the nearest of the same multiplier sign and mode
// (pair_nearest), not by order. The harmonics do not change the model, a boundary that converges
// moves less than its neighbours are apart, and new boundaries of high order appear between the
// old ones with every k, which would misalign the runs `match` lays side by side. Where two
// different boundaries are taken for one, the change reported is still the distance from the one
// at k to a boundary at k + 2.
std::vector<int> nearest_counterparts(const std::vector<Boundary>& base, const std::vector<Boundary>& other,
                                      bool in_load) {
  std::vector<int> counterpart(base.size(), -1);
  pair_nearest(base, other, in_load, counterpart);
  return counterpart;
}

// A boundary of the window at k compared with k + 2: its relative change, none where k + 2 has no
// counterpart.
struct Compared {
  Boundary boundary;
  int approximation = 0;
  std::optional<double> change;
  bool check_failed = false;  // its multiplier check (check_lowest) failed
};

// The boundaries of the window (of order ≤ max_order) at k, each compared with k + 2, and those
// that appear only at k + 2, compared with k + 4 (dropped if they have no counterpart there:
// a root of one truncation only); without k + 4 (`with_next` false: the work limit does not afford
// it), those are kept without a counterpart, so not converged.
std::vector<Compared> compare_at(BoundarySolver& solver, int k, bool in_load, const std::pair<double, double>& window,
                                 int max_order, bool with_next) {
  const auto inside = [&](const Boundary& b) {
    return b.order <= max_order && value_of(b, in_load) >= window.first && value_of(b, in_load) <= window.second;
  };
  std::vector<Boundary> lo;
  for (const Boundary& b : solver.at(k)) {
    if (inside(b)) lo.push_back(b);
  }
  // Counterparts are sought in the whole of k + 2 and k + 4: a boundary may step out of the window.
  const std::vector<Boundary>& mid = solver.at(k + 2);
  std::vector<Compared> out;
  const std::vector<int> to_mid = nearest_counterparts(lo, mid, in_load);
  std::vector<bool> seen(mid.size(), false);
  for (std::size_t i = 0; i < lo.size(); ++i) {
    out.push_back({lo[i], k, std::nullopt});
    if (to_mid[i] < 0) continue;
    seen[to_mid[i]] = true;
    out.back().change = relative_change(lo[i], mid[to_mid[i]], in_load);
  }
  std::vector<Boundary> fresh;
  for (std::size_t j = 0; j < mid.size(); ++j) {
    if (!seen[j] && inside(mid[j])) fresh.push_back(mid[j]);
  }
  if (!with_next) {
    for (const Boundary& b : fresh) out.push_back({b, k + 2, std::nullopt});
    return out;
  }
  if (fresh.empty()) return out;
  const std::vector<Boundary>& hi = solver.at(k + 4);
  const std::vector<int> to_hi = nearest_counterparts(fresh, hi, in_load);
  for (std::size_t j = 0; j < fresh.size(); ++j) {
    if (to_hi[j] >= 0) out.push_back({fresh[j], k + 2, relative_change(fresh[j], hi[to_hi[j]], in_load)});
  }
  return out;
}

// The method part of a compared boundary; 1 (nothing is known) where it has no counterpart.
double method_part(const Compared& c) { return c.change ? harmonics_error(*c.change) : 1.0; }

// The compared boundaries whose method part meets the tolerance (and whose check, if any, passed)
// as the result's boundaries, the others as its unconverged ones.
void split_by_tolerance(const std::vector<Compared>& compared, double tolerance, bool in_load, BoundaryAnalysis& result) {
  result.boundaries.clear();
  result.unconverged.clear();
  for (const Compared& c : compared) {
    if (method_part(c) <= tolerance && !c.check_failed) {
      result.boundaries.push_back({c.boundary, c.approximation, {}});
      result.boundaries.back().budget.method = method_part(c);
    } else {
      result.unconverged.push_back({c.boundary, c.approximation, c.change, c.check_failed});
    }
  }
  sort_by_value(result.boundaries, in_load);
  sort_by_value(result.unconverged, in_load);
}

// The check: the multiplier at the lowest-order converged boundaries (one or two) from a monodromy
// (multiplier_gap) on a system whose fastest mode Magnus steps take cheaply over a period, cut off
// at check_reach·order·θ/2π (or the request's cut-off, if lower). `checker(cutoff_hz)` is the
// boundaries' solver on the model cut off there. Marks the boundaries whose check failed or was
// not made (its monodromy took more than `check_work_left`, which it is charged).
std::vector<BoundaryCheck> check_lowest(std::vector<Compared>& compared, double tolerance, double request_cutoff_hz,
                                        double& check_work_left, bool in_load,
                                        const std::function<BoundarySolver(double)>& checker) {
  int lowest = std::numeric_limits<int>::max();
  for (const Compared& c : compared) {
    if (method_part(c) <= tolerance) lowest = std::min(lowest, c.boundary.order);
  }
  std::vector<BoundaryCheck> checks;
  for (Compared& c : compared) {
    if (c.boundary.order != lowest || method_part(c) > tolerance || checks.size() == 2) continue;
    const double reach_hz = check_reach * std::max(1, lowest) * c.boundary.theta_rad_s / two_pi;
    BoundaryCheck check;
    check.cutoff_hz = request_cutoff_hz > 0 ? std::min(request_cutoff_hz, reach_hz) : reach_hz;
    // Multipliers split like the square root of the distance from the boundary (test_map:
    // 2e-4 in ρ for 1e-8 in F̄); the check's boundary carries the same harmonics' error.
    check.allowed = std::max(1e-3, 10 * std::sqrt(method_part(c)));
    check.boundary = c.boundary;
    check.made = false;
    if (check_work_left > 0) {
      BoundarySolver solver = checker(check.cutoff_hz);
      const PeriodicSystem& system = solver.system();
      if (system.kept_modes == system.all_modes) check.cutoff_hz = 0;
      const std::vector<Boundary>& there = solver.at(c.approximation);
      // Its model (static limits, modes: a few dense solves of the whole Ritz model) and boundaries.
      check_work_left -= 3 * 26 * std::pow(system.all_modes, 3) +
                         boundary_level_flops(c.approximation, system.kept_modes, !in_load);
      const int j = match({c.boundary}, there, in_load)[0];  // the same boundary in the check's model
      MultiplierGap gap{std::numeric_limits<double>::infinity(), 0};
      if (j >= 0) {
        check.boundary = there[j];
        gap = multiplier_gap(system, solver.peak(), check.boundary, check_monodromy_tolerance, check_work_left);
      }
      check_work_left -= gap.work;
      check.made = gap.gap.has_value();
      check.gap = gap.gap.value_or(0);
    }
    c.check_failed = !check.made || !(check.gap <= check.allowed);
    checks.push_back(check);
  }
  return checks;
}

}  // namespace

ErrorBudget BoundaryAnalysis::total() const {
  ErrorBudget t;
  for (const EstimatedBoundary& b : boundaries) t.raise_to(b.budget);
  return t;
}

namespace {

// One part of each reported boundary's budget: `factor` times its change against its counterpart
// in `other`, at the approximation it comes from; a boundary without one gets 1, and `missing`
// names the part as unbounded.
void compare_part(BoundaryAnalysis& result, BoundarySolver& other, bool in_load, double factor,
                  double ErrorBudget::*part, const char* missing) {
  for (int k : {result.approximation, result.approximation + 2}) {
    std::vector<Boundary> at_k;  // the reported boundaries that come from k, matched together
    for (const EstimatedBoundary& e : result.boundaries) {
      if (e.approximation == k) at_k.push_back(e.boundary);
    }
    if (at_k.empty()) continue;
    const std::vector<Boundary>& there = other.at(k);
    const std::vector<int> to = match(at_k, there, in_load);
    std::size_t next = 0;
    for (EstimatedBoundary& e : result.boundaries) {
      if (e.approximation != k) continue;
      const int j = to[next++];
      e.budget.*part = j < 0 ? 1.0 : factor * relative_change(e.boundary, there[j], in_load);
      if (j < 0) e.budget.unbounded.push_back(missing);
    }
  }
}

}  // namespace

namespace {

// The window of θ (or F_max): the request's, else θ/2 to 2θ of the scene's θ (0 to 2 F_max).
std::pair<double, double> window_of(const BoundaryRequest& r, double peak, double theta) {
  if (r.window) return *r.window;
  return r.theta_rad_s ? std::make_pair(0.0, 2 * peak) : std::make_pair(theta / 2, 2 * theta);
}

// Whether the reduction's vectors are the program's to choose (and raise): the automatic reduction
// without model.reduction_vectors, and no --cutoff-hz.
bool vectors_left_to_program(const Scene& scene, const BoundaryRequest& r) {
  const ReductionSpec& asked = scene.model.reduction;
  return r.cutoff_hz == 0 && asked.kind == ReductionKind::automatic && asked.vectors == 0;
}

// k raised from `first` in steps of 2 on one model until every boundary of the window of order
// ≤ max_order moves by at most the tolerance at k + 2 and the multiplier check passes, or k + 2
// would need more than max_approximation harmonics, or more work than `affordable(k + 2)` allows
// (then result.work_limited): the result's approximation, boundaries (with their method part),
// unconverged ones and checks. `at_level(k)` is told each k tried; the checks' Magnus work is
// taken from `check_work_left`.
void converge_in_harmonics(BoundarySolver& solver, const BoundaryRequest& r, int first, double& check_work_left,
                           const std::function<BoundarySolver(double)>& checker,
                           const std::function<void(int)>& at_level, const std::function<bool(int)>& affordable,
                           BoundaryAnalysis& result) {
  const bool in_load = r.theta_rad_s.has_value();
  for (int k = first;; k += 2) {
    at_level(k);
    const bool within_harmonics = k + 6 <= r.max_approximation;  // k + 2 would need k + 6 harmonics
    const bool last = !within_harmonics || !affordable(k + 2);
    std::vector<Compared> compared = compare_at(solver, k, in_load, result.window, r.max_order, affordable(k));
    double worst = 0;
    for (const Compared& c : compared) worst = std::max(worst, method_part(c));
    if (worst > r.tolerance && !last) continue;
    result.approximation = k;
    result.checks = check_lowest(compared, r.tolerance, r.cutoff_hz, check_work_left, in_load, checker);
    // A check not made (its monodromy did not settle within its share of the work) would not be
    // made at a higher k either: its boundary is listed as unconverged, and k is not raised for it.
    const bool passed = std::all_of(result.checks.begin(), result.checks.end(),
                                    [](const BoundaryCheck& c) { return !c.made || c.gap <= c.allowed; });
    if (!passed && !last) continue;
    split_by_tolerance(compared, r.tolerance, in_load, result);
    result.work_limited = within_harmonics && !result.unconverged.empty();
    return;
  }
}

// The reduction part from the whole model at a low k (the reduction's error hardly depends on k,
// the whole model's eigenproblems grow like its dofs·k): each reported boundary matched to the
// reduced model at `k_low`, that one to the whole model there, the part raised to twice their
// change (its change with k is not known).
// A boundary without counterparts keeps its part from the other comparison.
void compare_whole_at(BoundaryAnalysis& result, BoundarySolver& reduced, BoundarySolver& whole, int k_low,
                      bool in_load) {
  std::vector<Boundary> reported;
  for (const EstimatedBoundary& e : result.boundaries) reported.push_back(e.boundary);
  const std::vector<Boundary>& here = reduced.at(k_low);
  const std::vector<int> to_here = match(reported, here, in_load);
  const std::vector<Boundary>& there = whole.at(k_low);
  const std::vector<int> to_whole = match(here, there, in_load);
  for (std::size_t i = 0; i < reported.size(); ++i) {
    const int j = to_here[i];
    if (j < 0 || to_whole[j] < 0) continue;
    double& part = result.boundaries[i].budget.reduction;
    part = std::max(part, 2 * relative_change(here[j], there[to_whole[j]], in_load));
  }
}

}  // namespace

int richer_basis_dofs(const ModelSpec& spec, int dofs, int all_dofs) {
  return dofs < all_dofs ? dofs : dofs * reference_terms(spec.basis, spec.terms) / spec.terms;
}

ReductionSpec boundary_reduction(const BladeModel& model, const Scene& scene, const BoundaryRequest& r) {
  if (r.cutoff_hz > 0) return {ReductionKind::modal, 0, r.cutoff_hz};
  if (!vectors_left_to_program(scene, r)) return scene.model.reduction;
  const double peak = scene.load.fmax_over_fcr * model.blade.critical_load();
  const double theta = r.theta_rad_s ? *r.theta_rad_s : pulse_train(scene).angular_frequency();
  const double theta_max = r.theta_rad_s ? theta : window_of(r, peak, theta).second;
  return automatic_or_whole(tongue_vectors(model, scene, theta_max, r.max_order), model.layout.size());
}

namespace {

// One run of boundaries_with_error_estimate: the scene's model and load, the solvers of the models
// compared, and the progress over their harmonic levels.
class BoundaryRun {
public:
  BoundaryRun(const Scene& scene, const BoundaryRequest& request)
      : r_(request), in_load_(request.theta_rad_s.has_value()), scene_(at_request(scene, request)),
        model_(assemble_model(scene_)), peak_(scene_.load.fmax_over_fcr * model_.blade.critical_load()),
        load_(load_series(scene_)) {}

  BoundaryAnalysis run() {
    BoundaryAnalysis result;
    result.window = window_of(r_, peak_, load_.angular_frequency);
    result.reduction = boundary_reduction(model_, scene_, r_);
    BoundarySolver solver = solver_for(model_, load_, result.reduction);
    ladder_ = &solver;
    const bool automatic = result.reduction.kind == ReductionKind::automatic;
    const bool cut = result.reduction.kind == ReductionKind::modal && solver.system().kept_modes < solver.system().all_modes;
    comparisons_left_ = 1 + automatic + cut + !load_.cosine_approximation;
    converge(solver, r_.first_approximation, result);
    if (automatic) raise_reduction(solver, result);
    if (cut) {
      BoundarySolver full = solver_for(model_, load_, {ReductionKind::none, 0, 0});
      compare(result, full, 1, &ErrorBudget::reduction, "reduction: no counterpart with all modes");
    }
    result.reduced_size = solver.system().kept_modes;
    result.full_size = solver.system().all_modes;
    ModelSpec richer = scene_.model;
    richer.terms = reference_terms(richer.basis, richer.terms);
    BoundarySolver richer_solver = solver_for(assemble_model(scene_, richer), load_, result.reduction);
    compare(result, richer_solver, basis_tail_factor(basis_convergence(scene_.blade, richer.basis, scene_.model.terms)), &ErrorBudget::basis,
            "basis: no counterpart with a richer basis");
    if (!load_.cosine_approximation) {
      const LoadSeries longer_series = load_series(scene_, load_.relative_tail / 10, 10 * (load_.harmonics() + 1));
      BoundarySolver longer = solver_for(model_, longer_series, result.reduction);
      compare(result, longer, 1, &ErrorBudget::load, "load: no counterpart with a longer series");
    }
    if (r_.progress) r_.progress(done_, done_);
    return result;
  }

private:
  // The pulses come at the θ asked for: a pulse series (not the cosine approximation) depends on
  // it through the duty t_c/T; for boundaries in F_max only the load's shape matters.
  static Scene at_request(Scene scene, const BoundaryRequest& r) {
    if (!r.theta_rad_s) return scene;
    if (scene.load.fmax_over_fcr == 0) scene.load.fmax_over_fcr = 1;
    scene.load.pulse_frequency_hz = *r.theta_rad_s / two_pi;
    return scene;
  }

  // Progress: one step per harmonic level of a model. What remains if the current k converges, at
  // most: its levels k, k + 2, k + 4 not yet solved (k + 4 only where a boundary first appears at
  // k + 2) and one level of each comparison model still to come.
  void report() const {
    int pending = std::max(0, comparisons_left_);
    for (int k : {level_, level_ + 2, level_ + 4}) pending += ladder_ == nullptr || !ladder_->has(k);
    if (r_.progress) r_.progress(done_, done_ + pending);
  }

  BoundarySolver solver_for(const BladeModel& m, const LoadSeries& series, const ReductionSpec& reduction,
                            bool counted = true) {
    PeriodicSystem system = periodic_system(m, scene_, series, reduction);
    const int dofs = system.kept_modes;
    std::function<void(int)> solved = [this, dofs, counted](int k) {
      spent_ += boundary_level_flops(k, dofs, !in_load_);
      if (counted) ++done_, report();
    };
    return BoundarySolver(std::move(system), peak_, r_.theta_rad_s, r_.threads, std::move(solved));
  }

  // Whether the work spent, one more level (k + 4) of `dofs` and the comparisons at k (two levels
  // each of the richer basis, the reduction's next step and the longer load series; the whole
  // model at k ≤ 4) fit in half of request.work_flops: the multiplier checks take up to a quarter
  // (check_work_left_) and the regions' Floquet verdicts about another (instability_regions.cpp).
  bool affordable(int k, int dofs, const ReductionSpec& reduction) const {
    const int all = model_.layout.size();
    const auto levels = [&](int n) {
      return boundary_level_flops(k, n, !in_load_) + boundary_level_flops(k + 2, n, !in_load_);
    };
    const int richer = richer_basis_dofs(scene_.model, dofs, all);
    double work = spent_ + boundary_level_flops(k + 4, dofs, !in_load_) + levels(richer);
    if (reduction.kind == ReductionKind::automatic) {
      work += levels(std::min(2 * dofs, all)) + boundary_level_flops(std::min(k, whole_model_approximation), all, !in_load_);
    }
    if (reduction.kind == ReductionKind::modal && dofs < all) work += levels(all);
    if (!load_.cosine_approximation) work += levels(dofs);
    return work <= r_.work_flops / 2;
  }

  void converge(BoundarySolver& solver, int first, BoundaryAnalysis& result) {
    const auto checker = [this](double cutoff_hz) {
      return solver_for(model_, load_, {ReductionKind::modal, 0, cutoff_hz}, false);
    };
    const int dofs = solver.system().kept_modes;
    const ReductionSpec reduction = result.reduction;
    converge_in_harmonics(
        solver, r_, first, check_work_left_, checker, [this](int k) { level_ = k; },
        [this, dofs, reduction](int k) { return affordable(k, dofs, reduction); }, result);
  }

  void compare(BoundaryAnalysis& result, BoundarySolver& other, double factor, double ErrorBudget::*part,
               const char* missing) {
    compare_part(result, other, in_load_, factor, part, missing);
    --comparisons_left_;
  }

  // The automatic reduction's part: twice the change against twice the vectors, or the change
  // against the whole model where that is next, and twice the change against the whole model at a
  // low k. Vectors the program chose (not the scene, not --cutoff-hz) are doubled, and k converged
  // again from where it was, while the part is above half the tolerance.
  void raise_reduction(BoundarySolver& solver, BoundaryAnalysis& result) {
    const bool chosen = vectors_left_to_program(scene_, r_);
    BoundarySolver whole = solver_for(model_, load_, {ReductionKind::none, 0, 0});
    for (;;) {
      // Twice the vectors, or the whole model once they would be as many.
      const ReductionSpec next = automatic_or_whole(2 * result.reduction.vectors, model_.layout.size());
      const bool next_whole = next.kind == ReductionKind::none;
      std::optional<BoundarySolver> twice;
      if (!next_whole) twice.emplace(solver_for(model_, load_, next));
      BoundarySolver& other = next_whole ? whole : *twice;
      compare(result, other, next_whole ? 1 : 2, &ErrorBudget::reduction,
              "reduction: no counterpart with twice the vectors");
      if (!next_whole) {
        compare_whole_at(result, solver, whole, std::min(result.approximation, whole_model_approximation), in_load_);
      }
      if (result.total().reduction <= r_.tolerance / 2 || !chosen) return;
      const int dofs = other.system().kept_modes;
      if (!affordable(result.approximation, dofs, next)) {
        result.work_limited = true;
        return;
      }
      result.reduction = next;
      solver = std::move(other);
      ++comparisons_left_;
      converge(solver, result.approximation, result);
      if (next_whole) return;
    }
  }

  const BoundaryRequest& r_;
  bool in_load_;
  Scene scene_;
  BladeModel model_;
  double peak_;
  LoadSeries load_;
  int done_ = 0, level_ = 0, comparisons_left_ = 0;
  double spent_ = 0;  // boundary_level_flops of the levels solved
  // What the multiplier checks of the whole run may still take: a quarter of the request's work.
  double check_work_left_ = r_.work_flops / 4;
  const BoundarySolver* ladder_ = nullptr;
};

}  // namespace

BoundaryAnalysis boundaries_with_error_estimate(const Scene& scene, const BoundaryRequest& r) {
  if (r.first_approximation < 1 || r.first_approximation + 4 > r.max_approximation) {
    throw std::invalid_argument(fmt::format("boundaries: the first approximation {} must be in [1, {}] (the maximum "
                                            "{} less the two levels it is compared with)", r.first_approximation,
                                            r.max_approximation - 4, r.max_approximation));
  }
  // The boundary equations balance harmonics of a series; the true train has none to balance (its
  // mean load alone would set the edges: the unloaded blade's tongue tips, a zero width).
  if (scene.load.approximation == LoadApproximation::exact) {
    throw InputError(fmt::format("{}: load.approximation = \"exact\": the boundary equations need the load as a "
                                 "series; use \"fourier\" (its truncation is in the error budget) or \"cosine\", or "
                                 "`stability` and `map` for the true pulse train", scene.source));
  }
  return BoundaryRun(scene, r).run();
}

}  // namespace bladestab
