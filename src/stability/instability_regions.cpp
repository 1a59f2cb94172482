#include "bladestab/stability/instability_regions.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include <fmt/format.h>

#include "bladestab/blade/blade_properties.hpp"
#include "bladestab/base/constants.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/stability/stability_analysis.hpp"
#include "support/work_pool.hpp"

namespace bladestab {
namespace {

struct Verdict {
  bool unstable = false;
  double max_abs = 0, error = 0;  // max|ρ| and its whole estimate (decided)
  std::string undecided;  // why there is no verdict: the analysis's one-line failure
};

// Unstable at a point for a multiplier sign: the dominant multiplier real, beyond +1 or −1 as the
// sign (a complex one is a combination resonance; the other sign's is that sign's region). Where
// such a multiplier lies above 1 by less than its estimate (the middle of a thin tongue: 1.0000031
// at F̄ = 0.5, θ = 209.727 rad/s, against an estimate of 6.7e-6 at 1e-4), the tolerance is
// tightened a hundredfold at a time, to 1e-10, until the estimate decides; one it never decides
// leaves the point undecided, as does an analysis that fails (NumericalError, e.g. its work share
// spent).
Verdict verdict_at(const Scene& at, int multiplier, StabilityRequest request) {
  try {
    StabilityAnswer a = analyse_stability(at, request);
    const auto real_of_sign = [&] {
      const std::complex<double> rho = a.floquet.multipliers(0);
      return std::abs(rho.imag()) <= 1e-6 * std::abs(rho) && rho.real() * multiplier > 0;
    };
    while (!verdict_decided(a) && real_of_sign() && a.floquet.max_abs_multiplier > 1 && request.tolerance > 1e-10) {
      request.tolerance = std::max(1e-10, request.tolerance / 100);
      a = analyse_stability(at, request);
    }
    const double max_abs = a.floquet.max_abs_multiplier, error = a.budget.total();
    if (!verdict_decided(a) && real_of_sign() && max_abs > 1) {
      return {false, max_abs, error, fmt::format("max|ρ| = {:.10g} ± {:.2g} stays above 1 by less than its estimate "
                                                 "at the tolerance 1e-10", max_abs, error)};
    }
    return {!a.stable && real_of_sign(), max_abs, error, {}};
  } catch (const NumericalError& e) {
    return {false, 0, 0, e.what()};
  }
}

// `next`, an unstable interval beginning where the unstable `region` ends, joined to it: the
// boundary between becomes inner, the label the higher order's, the middle the larger growth's.
void merge_into(InstabilityRegion& region, const InstabilityRegion& next) {
  region.inner.push_back(region.upper);
  region.inner.insert(region.inner.end(), next.inner.begin(), next.inner.end());
  region.upper = next.upper;
  region.upper_open = next.upper_open;
  region.upper_unconverged = next.upper_unconverged;
  if (next.order > region.order) region.mode = next.mode, region.order = next.order;
  if (next.middle_max_abs_multiplier > region.middle_max_abs_multiplier) {
    region.middle_max_abs_multiplier = next.middle_max_abs_multiplier;
    region.middle_error_estimate = next.middle_error_estimate;
  }
}

// The candidates the verdicts keep (unstable or undecided), with their middles' answers, sorted
// along the line. Candidates of a sign come in order: an unstable one that begins where the last
// region (unstable, of that sign) ends continues it (merge_into).
std::vector<InstabilityRegion> regions_of(const std::vector<InstabilityRegion>& candidates,
                                          const std::vector<Verdict>& verdicts) {
  std::vector<InstabilityRegion> regions;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!verdicts[i].unstable && verdicts[i].undecided.empty()) continue;
    InstabilityRegion r = candidates[i];
    r.middle_max_abs_multiplier = verdicts[i].max_abs;
    r.middle_error_estimate = verdicts[i].error;
    r.undecided = verdicts[i].undecided;
    InstabilityRegion* last = regions.empty() ? nullptr : &regions.back();
    if (last && last->multiplier == r.multiplier && last->upper == r.lower && last->undecided.empty() &&
        r.undecided.empty()) {
      merge_into(*last, r);
    } else {
      regions.push_back(std::move(r));
    }
  }
  std::sort(regions.begin(), regions.end(),
            [](const InstabilityRegion& a, const InstabilityRegion& b) { return a.lower < b.lower; });
  return regions;
}

}  // namespace

std::vector<InstabilityRegion> instability_regions(const Scene& scene, const BoundaryRequest& request,
                                                   const BoundaryAnalysis& analysis, double tolerance) {
  const bool in_load = request.theta_rad_s.has_value();
  const double fcr = BladeProperties(scene.blade).critical_load();
  const auto value = [in_load](const Boundary& b) { return in_load ? b.peak_force_n : b.theta_rad_s; };
  // The boundaries of each multiplier sign, in order along the line, with whether each converged.
  std::map<int, std::vector<std::pair<Boundary, bool>>> by_sign;
  for (const EstimatedBoundary& e : analysis.boundaries) by_sign[e.boundary.multiplier].emplace_back(e.boundary, true);
  for (const UnconvergedBoundary& u : analysis.unconverged) by_sign[u.boundary.multiplier].emplace_back(u.boundary, false);
  // The scene at a point of the line: θ at the scene's load, or F_max at the given θ. Along θ the
  // boundary equations keep the series' coefficients, so a pulse series keeps its duty t_c/T_p
  // (docs/guide/boundaries.md): the contact, a fraction of a revolution, scales with θ_scene/θ.
  const double scene_theta = pulse_train(scene).angular_frequency();
  const auto at_point = [&](double x) {
    Scene at = scene;
    if (in_load) {
      at.load.pulse_frequency_hz = *request.theta_rad_s / two_pi;
      at.load.fmax_over_fcr = x / fcr;
    } else {
      at.load.pulse_frequency_hz = x / two_pi;
      if (at.operation.speed_rad_s > 0) at.load.contact_time_rev *= scene_theta / x;
    }
    return at;
  };
  // Every interval between neighbouring boundaries of a sign (the window closing the first and
  // last) is a candidate; their verdicts are independent and run side by side.
  std::vector<InstabilityRegion> candidates;
  for (auto& [multiplier, bounds] : by_sign) {
    std::sort(bounds.begin(), bounds.end(), [&](const auto& x, const auto& y) { return value(x.first) < value(y.first); });
    // Interval k lies between boundary k − 1 and boundary k; the window closes the first and last.
    for (std::size_t k = 0; k <= bounds.size(); ++k) {
      const Boundary* below = k > 0 ? &bounds[k - 1].first : nullptr;
      const Boundary* above = k < bounds.size() ? &bounds[k].first : nullptr;
      const double lo = below ? value(*below) : analysis.window.first;
      const double hi = above ? value(*above) : analysis.window.second;
      if (!(hi > lo) || (in_load && hi <= 0)) continue;
      InstabilityRegion r;
      r.lower = lo;
      r.upper = hi;
      r.lower_open = below == nullptr;
      r.upper_open = above == nullptr;
      r.lower_unconverged = below && !bounds[k - 1].second;
      r.upper_unconverged = above && !bounds[k].second;
      r.multiplier = multiplier;
      // The label of an end; where the two differ, the higher order (the dominant harmonic of a
      // boundary's eigenvector, which names it, drifts to lower orders at high loads).
      const Boundary* named = below && above ? (below->order >= above->order ? below : above) : below ? below : above;
      r.mode = named ? named->mode : 0;
      r.order = named ? named->order : 0;
      candidates.push_back(r);
    }
  }
  // The verdicts together may take a quarter of the request's work, in equal shares (a quarter of a
  // share for each of its monodromy ladders, StabilityRequest::work_flops).
  StabilityRequest verdict{FloquetMethod::automatic, 0, tolerance, 0, {}};
  verdict.verdict_only = true;
  verdict.work_flops = request.work_flops / (4.0 * std::max<std::size_t>(1, candidates.size()));
  const std::vector<Verdict> verdicts = run_indexed(candidates.size(), request.threads, [&](std::size_t i) {
    const InstabilityRegion& r = candidates[i];
    return verdict_at(at_point(0.5 * (r.lower + r.upper)), r.multiplier, verdict);
  });
  return regions_of(candidates, verdicts);
}

}  // namespace bladestab
