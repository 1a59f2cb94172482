#include "bladestab/blade/static_limits.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/blade/undamped_modes.hpp"
#include "support/scalar_search.hpp"

namespace bladestab {
namespace {

// The least eigenpair of K(Ω, F) x = μ K_E x (dsygvx: K_E is positive definite).
UndampedModes weakest_direction(const BladeModel& model, double speed, double tip_force_n, bool with_shape) {
  return generalized_modes(model.stiffness(speed, tip_force_n), model.elastic_stiffness(), 1, with_shape);
}

// The field holding most of the mass of the weakest direction at (Ω, F).
std::string weakest_field(const BladeModel& model, double speed, double tip_force_n) {
  const Eigen::VectorXd x = weakest_direction(model, speed, tip_force_n, true).shapes.col(0);
  const char* heaviest = "";
  double most = -1;
  for (const FieldFamily& family : model.families) {
    if (family.count == 0) continue;
    const auto xf = x.segment(family.offset, family.count);
    const double share = xf.dot(family.mass * xf);
    if (share > most) most = share, heaviest = family.share_name;
  }
  return heaviest;
}

// The root of the path's margin between a value within (margin > 0) and one past (margin ≤ 0).
double path_root(const std::function<double(double)>& margin, double within, double g_within, double past,
                 double g_past) {
  if (g_past == 0) return past;
  return within < past ? bracketed_root(margin, within, g_within, past, g_past)
                       : bracketed_root(margin, past, g_past, within, g_within);
}

}  // namespace

const char* to_string(StaticLimitKind kind) {
  return kind == StaticLimitKind::spin_divergence ? "spin divergence" : "buckling";
}

double static_margin(const BladeModel& model, double speed, double tip_force_n) {
  return weakest_direction(model, speed, tip_force_n, false).omega2(0);
}

std::optional<double> static_buckling_load(const BladeModel& model, double speed) {
  const Eigen::MatrixXd unloaded = model.elastic_stiffness() + speed * speed * model.K_C1;
  if (Eigen::LLT<Eigen::MatrixXd>(unloaded).info() != Eigen::Success) return std::nullopt;
  // G is positive semi-definite, so μ ≥ 0 and the largest one buckles first.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> buckling(model.G, unloaded, Eigen::EigenvaluesOnly);
  return 1 / buckling.eigenvalues().maxCoeff();
}

std::optional<StaticLimit> static_limit_at(const BladeModel& model, double speed, double tip_force_n) {
  const double margin = static_margin(model, speed, tip_force_n);
  if (margin > 0) return std::nullopt;
  const double no_tip_force = -model.static_tip_force_n;  // cancels the model's own static force
  const double unloaded = static_margin(model, speed, no_tip_force);
  if (unloaded > 0) {
    // No load where K_E + Ω²K_C1 is within rounding of singular: any compression buckles it.
    const double load = static_buckling_load(model, speed).value_or(0);
    return StaticLimit{StaticLimitKind::buckling, weakest_field(model, speed, tip_force_n), load};
  }
  // The unloaded blade at rest has the margin 1: the divergence speed lies between rest and Ω.
  const auto along = [&](double w) { return static_margin(model, w, no_tip_force); };
  const double where = path_root(along, 0, along(0), speed, unloaded);
  return StaticLimit{StaticLimitKind::spin_divergence, weakest_field(model, speed, no_tip_force), where};
}

std::optional<InputError> static_limit_error(const BladeModel& model, double speed, const std::string& speed_key) {
  const std::optional<StaticLimit> limit = static_limit_at(model, speed);
  if (!limit) return std::nullopt;
  const double fcr = model.blade.critical_load();
  if (limit->kind == StaticLimitKind::buckling) {
    return InputError(fmt::format("operation.tip_compression_over_fcr = {:.6g}: the blade is statically unstable "
                                  "under it at {} = {}: it buckles at {:.6g} F_cr ({} basis, {} terms); must be "
                                  "below that",
                                  -model.static_tip_force_n / fcr, speed_key, speed, limit->where / fcr,
                                  to_string(model.spec.basis), model.spec.terms));
  }
  return InputError(fmt::format("{} = {}: the unloaded blade is statically unstable at this speed: it diverges "
                                "above {:.9g} rad/s, where the spin softening of its {} field outweighs the stiffness "
                                "of blade.length = {:g} m, blade.youngs_modulus = {:g} Pa, blade.density = {:g} "
                                "kg/m^3; lower the speed or stiffen the blade",
                                speed_key, speed, limit->where, limit->field, model.blade.L, model.blade.E,
                                model.blade.rho));
}

PathWithinLimits path_within_limits(const std::vector<double>& values, const std::function<double(double)>& margin,
                                    const std::function<std::optional<StaticLimit>(double)>& limit, bool continuous) {
  const auto root = [&](double within, double g_within, double past, double g_past) {
    return continuous ? path_root(margin, within, g_within, past, g_past) : past;
  };
  PathWithinLimits path;
  const std::size_t n = values.size();
  std::size_t i = 0;
  double g = 0, g_before = 0;
  for (; i < n; ++i, g_before = g) {
    if ((g = margin(values[i])) > 0) break;
  }
  path.first = path.end = i;
  if (i == n) return path;
  if (i > 0) {
    path.before = limit(values[i - 1]).value();
    path.before->where = root(values[i], g, values[i - 1], g_before);
  }
  double g_last = g;
  for (++i; i < n; ++i, g_last = g) {
    if ((g = margin(values[i])) <= 0) break;
  }
  path.end = i;
  if (i < n) {
    path.after = limit(values[i]).value();
    path.after->where = root(values[i - 1], g_last, values[i], g);
  }
  return path;
}

PathWithinLimits speeds_within_limits(const BladeModel& model, const std::vector<double>& speeds) {
  // The margin, the lowest ω² of K(Ω) = K_e + Ω² K_C1 − F_a G against M, is concave in Ω² (a
  // minimum of functions affine in it): the speeds of one sign within the limits form an interval
  // in Ω², so where the slowest and the fastest are within, all are (a Campbell diagram of 20000
  // speeds solved each, ~1 s a round).
  if (speeds.size() > 2) {
    const auto [slowest, fastest] = std::minmax_element(
        speeds.begin(), speeds.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    const auto [lowest, highest] = std::minmax_element(speeds.begin(), speeds.end());
    const bool one_sign = *lowest >= 0 || *highest <= 0;
    if (one_sign && static_margin(model, *slowest) > 0 && static_margin(model, *fastest) > 0) {
      PathWithinLimits all;
      all.end = speeds.size();
      return all;
    }
  }
  return path_within_limits(
      speeds, [&model](double speed) { return static_margin(model, speed); },
      [&model](double speed) { return static_limit_at(model, speed); });
}

std::string describe_path_limits(const PathWithinLimits& path, bool ascending,
                                 const std::function<std::string(double)>& value) {
  const auto clause = [&](const StaticLimit& limit, bool above) {
    const std::string verb = limit.kind == StaticLimitKind::buckling
                                 ? std::string("buckles under its static tip compression")
                                 : fmt::format("diverges (the spin softening of its {} field)", limit.field);
    return fmt::format("{} {} {}", verb, above ? "above" : "below", value(limit.where));
  };
  std::string text;
  if (path.before) text = clause(*path.before, !ascending);
  if (path.after) text += (text.empty() ? "" : " and ") + clause(*path.after, ascending);
  return text.empty() ? text : "the blade " + text;
}

}  // namespace bladestab
