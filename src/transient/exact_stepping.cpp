#include "bladestab/transient/exact_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>

#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bladestab/base/input_error.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/blade/reduction.hpp"
#include "bladestab/blade/undamped_modes.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/step_doubling.hpp"
#include "support/work_pool.hpp"
#include "bladestab/transient/transient.hpp"

namespace bladestab {
namespace {

// ‖X − Y‖_F / ‖Y‖_F over the homogeneous block and, apart, over each of the last `forcing`
// columns (their scale is the forced response's, not the propagator's).
double map_distance(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, int forcing) {
  const Eigen::Index s = X.rows() - forcing;
  double largest = (X.topLeftCorner(s, s) - Y.topLeftCorner(s, s)).norm() / Y.topLeftCorner(s, s).norm();
  for (Eigen::Index c = s; c < X.cols(); ++c) {
    const double scale = Y.col(c).head(s).norm();
    if (scale > 0) largest = std::max(largest, (X.col(c) - Y.col(c)).head(s).norm() / scale);
  }
  return largest;
}

// Two times equal up to rounding on the scale of their own stretch: a free flight's length, or an
// offset within the contact (never the pulse period, which may be many revolutions long).
bool same_time(double a, double b, double scale) { return std::abs(a - b) <= 1e-12 * scale; }

// Φ and ω²: the modes of the whole model, or of the reduced one in the span of its basis V
// (Vᵀ M V = I, so Φ = V Q with Q the eigenvectors of Vᵀ K V is M-orthonormal).
UndampedModes kept_modes(const BladeModel& model, const Scene& scene, const Eigen::MatrixXd& C_D, double peak_n,
                         const std::optional<ReductionSpec>& reduction) {
  const double speed = scene.operation.speed_rad_s;
  if (!reduction) return undamped_modes(model, speed);
  const ReducedSystem reduced = reduce(model, speed, C_D, -peak_n, *reduction);
  const ReducedModes modes = reduced_modes(reduced);
  return {modes.omega2, reduced.basis * modes.shapes};
}

}  // namespace

ExactStepper::ExactStepper(const BladeModel& model, const Scene& scene, double tolerance,
                           const std::optional<ReductionSpec>& reduction, double piece_work_flops)
    : pulses_(pulse_train(scene)), tolerance_(tolerance), piece_work_flops_(piece_work_flops) {
  if (!pulses_.frequency_known) {
    throw InputError("operation.speed_rad_s = 0: the pulses have no frequency; give load.pulse_frequency_hz");
  }
  const double speed = scene.operation.speed_rad_s;
  const Eigen::MatrixXd C_D = damping_matrix(model, scene.damping, speed);
  const UndampedModes modes = kept_modes(model, scene, C_D, pulses_.peak_n, reduction);
  if (!(modes.omega2(0) > 0)) {
    throw NumericalError(fmt::format("exact stepping: K(Ω) at {} rad/s is not positive definite", speed));
  }
  n_ = static_cast<int>(modes.omega2.size()), dofs_ = 2 * n_;
  omega_ = modes.omega2.cwiseSqrt();
  Phi_ = modes.shapes;
  PhiT_M_ = Phi_.transpose() * model.M;
  equilibrium_ = rotating_equilibrium(model, speed).head(model.layout.size());
  damped_ = !C_D.isZero(0);
  const Eigen::MatrixXd C_hat = Phi_.transpose() * (C_D + model.gyroscopic(speed)) * Phi_;
  const Eigen::MatrixXd G_hat = Phi_.transpose() * model.G * Phi_;
  const int n = n_, s = dofs_;
  A_free_ = Eigen::MatrixXd::Zero(s + 1, s + 1);
  A_free_.block(0, n, n, n) = omega_.asDiagonal();
  A_free_.block(n, 0, n, n) = -Eigen::MatrixXd(omega_.asDiagonal());
  A_free_.block(n, n, n, n) = -C_hat;
  in_plane_share_ = model.in_plane_share;
  mu_in_plane_ = scene.load.friction * in_plane_share_;
  const Eigen::VectorXd forcing = model.tip_axial.transpose() - model.G * equilibrium_ +
                                  mu_in_plane_ * model.tip_lateral.transpose();
  B_ = Eigen::MatrixXd::Zero(s + 1, s + 1);
  B_.block(n, 0, n, n) = -G_hat * omega_.cwiseInverse().asDiagonal();
  B_.block(n, s, n, 1) = Phi_.transpose() * forcing;
  // W' = −ḟᵀ C_D ḟ = yᵀ Q y in free flight.
  Q_damping_ = Eigen::MatrixXd::Zero(s, s);
  Q_damping_.block(n, n, n, n) = -Phi_.transpose() * C_D * Phi_;
  rim_speed_ = speed * model.blade.tip_radius();
  tip_lateral_ = model.tip_lateral;
  mirror_ = contact_mirror(A_free_, B_, pulses_, damped_);
}

std::vector<double> ExactStepper::kinks() const {
  if (pulses_.profile == PulseProfile::triangular) return {0.5 * pulses_.contact_time_s};
  return {};
}

Eigen::VectorXd ExactStepper::physical(const Eigen::VectorXd& z) const {
  const Eigen::Index n = equilibrium_.size();
  Eigen::VectorXd x(2 * n);
  x.head(n) = equilibrium_ + Phi_ * z.head(n_).cwiseQuotient(omega_);
  x.tail(n) = Phi_ * z.segment(n_, n_);
  return x;
}

Eigen::VectorXd ExactStepper::modal(const Eigen::VectorXd& x) const {
  const Eigen::Index n = equilibrium_.size();
  Eigen::VectorXd z(dofs_ + 1);
  z.head(n_) = omega_.cwiseProduct(PhiT_M_ * (x.head(n) - equilibrium_));
  z.segment(n_, n_) = PhiT_M_ * x.segment(n, n);
  z(dofs_) = 1;
  return z;
}

double ExactStepper::sliding_speed(const Eigen::VectorXd& z) const {
  return rim_speed_ + in_plane_share_ * tip_lateral_.dot(Phi_ * z.segment(n_, n_));
}

const ExactStepper::Piece& ExactStepper::free_piece(double h) {
  for (const Piece& p : free_) {
    if (same_time(p.end, h, std::max(p.end, h))) return p;
  }
  const int s = dofs_;
  Piece piece{0, h, {}, {}};
  if (damped_) {
    // Van Loan: e^{H τ} = [[F1, G1], [0, F2]] for H = [[−Aᵀ, Q], [0, A]] gives F2 = e^{Aτ} and
    // S(τ) = ∫₀^τ e^{Aᵀσ} Q e^{Aσ} dσ = F2ᵀ G1, the damping's work over τ from any start y as yᵀ S y.
    // F1 = e^{−Aᵀτ} grows with the damping (e^{6700} for the paper's ζ on the stiffest mode over a
    // sample interval), so H is exponentiated only over τ = h/2^k with ‖A‖₁ τ ≤ 1, and S doubled
    // k times by S(2τ) = S(τ) + e^{Aᵀτ} S(τ) e^{Aτ}, which holds only bounded matrices.
    const Eigen::MatrixXd A = A_free_.topLeftCorner(s, s);
    const double norm = A.cwiseAbs().colwise().sum().maxCoeff() * h;
    const int doublings = norm > 1 ? static_cast<int>(std::ceil(std::log2(norm))) : 0;
    const double tau = std::ldexp(h, -doublings);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * s, 2 * s);
    H.topLeftCorner(s, s) = -A.transpose();
    H.topRightCorner(s, s) = Q_damping_;
    H.bottomRightCorner(s, s) = A;
    const Eigen::MatrixXd E = (H * tau).exp();
    piece.map = E.bottomRightCorner(s, s);
    piece.work = piece.map.transpose() * E.topRightCorner(s, s);
    for (int k = 0; k < doublings; ++k) {
      piece.work += piece.map.transpose() * piece.work * piece.map;
      piece.map = piece.map * piece.map;
    }
  } else {
    piece.map = (A_free_.topLeftCorner(s, s) * h).exp();
  }
  ++stats_.free_exponentials;
  free_.push_back(std::move(piece));
  return free_.back();
}

const ExactStepper::Piece* ExactStepper::cached_contact(double start, double end) const {
  for (const Piece& p : contact_) {
    if (same_time(p.start, start, pulses_.contact_time_s) && same_time(p.end, end, pulses_.contact_time_s)) return &p;
  }
  return nullptr;
}

const ExactStepper::Piece& ExactStepper::keep(Integrated integrated) {
  stats_.magnus_steps += integrated.steps;
  stats_.contact_error = std::max(stats_.contact_error, integrated.error);
  ++stats_.contact_pieces;
  contact_.push_back(std::move(integrated.piece));
  return contact_.back();
}

const ExactStepper::Piece& ExactStepper::contact_piece(double start, double end) {
  if (const Piece* p = cached_contact(start, end)) return *p;
  return keep(integrate_contact(start, end));
}

ExactStepper::Integrated ExactStepper::integrate_contact(double start, double end) const {
  return integrate(A_free_, B_, 1, start, end);
}

ExactStepper::Integrated ExactStepper::integrate(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int forcing,
                                                 double start, double end) const {
  const std::function<double(double)> load = [this](double tau) { return pulses_.force(tau); };
  // From 1/32 of the count where h‖A‖₁ ≤ 2 (the exponential takes the stiff modes exactly).
  const double norm = A.cwiseAbs().colwise().sum().maxCoeff() + pulses_.peak_n * B.cwiseAbs().colwise().sum().maxCoeff();
  const double safe = std::max(1.0, norm * (end - start) / 2);
  constexpr int most_steps = 1 << 16;
  const double first_level = std::ceil(std::log2(std::max(1.0, safe / 32)));
  // Three levels are the fewest whose distances show a contraction (StepDoubling): refuse at once
  // a piece whose first level leaves room for fewer.
  if (first_level + 2 > std::log2(most_steps)) {
    throw NumericalError(fmt::format("exact stepping: the contact piece [{:.6g}, {:.6g}] s needs about {:.3g} Magnus "
                                     "steps (h‖A‖₁ ≤ 2 with ‖A‖₁ = {:.3g}/s: a damping that overdamps the stiffest "
                                     "modes, or a long contact on a stiff model), past the {} it may take; use fewer "
                                     "terms or a lighter damping",
                                     start, end, safe, norm, most_steps));
  }
  const int first = 1 << static_cast<int>(first_level);
  StepDoubling ladder(first, most_steps, static_cast<int>(std::min(safe, 1e9)), magnus_step_work(A.rows()),
                      piece_work_flops_);
  Integrated result;
  Eigen::MatrixXd previous;
  for (int steps = first; steps <= ladder.last(); steps *= 2) {
    Eigen::MatrixXd map = magnus_propagator(A, B, load, start, end, steps);
    result.steps += steps;
    if (!map.allFinite()) {
      if (ladder.overflowed(steps)) {
        throw NumericalError(fmt::format("exact stepping: the propagator of the contact piece [{:.6g}, {:.6g}] s "
                                         "overflows the double range: the state grows past it within the contact",
                                         start, end));
      }
      previous.resize(0, 0);
      continue;
    }
    if (previous.size() > 0) {
      if (const std::optional<double> error = ladder.judge(steps, map_distance(map, previous, forcing), tolerance_, 1e-15)) {
        result.error = *error;
        result.piece = {start, end, std::move(map), {}};
        return result;
      }
    }
    previous = std::move(map);
  }
  ladder.give_up(fmt::format("exact stepping: the contact piece [{:.6g}, {:.6g}] s did not converge to {:g}", start,
                             end, tolerance_),
                 "Magnus steps");
}

std::optional<std::pair<double, double>> ExactStepper::contact_offsets(double a, double b) const {
  const double mid = 0.5 * (a + b);
  const std::optional<double> tau = pulses_.time_in_pulse(mid);
  if (!tau) return std::nullopt;
  const double pulse_start = mid - *tau;
  return std::pair{std::max(0.0, a - pulse_start), std::min(pulses_.contact_time_s, b - pulse_start)};
}

void ExactStepper::prepare(const std::vector<double>& landings, int threads,
                           const std::function<void(int, int)>& progress) {
  std::vector<std::pair<double, double>> missing;
  for (std::size_t k = 1; k < landings.size(); ++k) {
    if (!(landings[k] > landings[k - 1])) continue;
    const auto offsets = contact_offsets(landings[k - 1], landings[k]);
    if (!offsets || cached_contact(offsets->first, offsets->second)) continue;
    const bool listed = std::any_of(missing.begin(), missing.end(), [&](const std::pair<double, double>& m) {
      return same_time(m.first, offsets->first, pulses_.contact_time_s) &&
             same_time(m.second, offsets->second, pulses_.contact_time_s);
    });
    if (!listed) missing.push_back(*offsets);
  }
  if (missing.empty()) return;
  std::vector<Integrated> pieces = mirror_ ? mirrored_pieces(missing, threads, progress)
                                           : integrate_side_by_side(A_free_, B_, 1, missing, threads, progress);
  for (Integrated& piece : pieces) keep(std::move(piece));
}

std::vector<ExactStepper::Integrated> ExactStepper::integrate_side_by_side(
    const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int forcing, const std::vector<std::pair<double, double>>& intervals,
    int threads, const std::function<void(int, int)>& progress) const {
  std::mutex reporting;
  int done = 0;
  return run_indexed(intervals.size(), threads, [&](std::size_t i) {
    Integrated piece = integrate(A, B, forcing, intervals[i].first, intervals[i].second);
    if (progress) {
      const std::lock_guard<std::mutex> lock(reporting);
      progress(++done, static_cast<int>(intervals.size()));
    }
    return piece;
  });
}

bool ExactStepper::step(double a, double b, Eigen::VectorXd& z, double& work) {
  if (const auto offsets = contact_offsets(a, b)) {
    ++stats_.intervals;
    z = contact_piece(offsets->first, offsets->second).map * z;
    return true;
  }
  free_flight(b - a, z, work);
  return false;
}

void ExactStepper::free_flight(double h, Eigen::VectorXd& z, double& work) {
  ++stats_.intervals;
  const Piece& piece = free_piece(h);
  const auto y = z.head(dofs_);
  if (damped_) work += y.dot(piece.work * y);
  z.head(dofs_) = piece.map * y;
}

}  // namespace bladestab
