#include "bladestab/modal/speed_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "modal/subset_eigensolver.hpp"

namespace bladestab {
namespace {
constexpr double unbounded = std::numeric_limits<double>::infinity();
// Rounds of basis enrichment before the reduced sweep gives up on a speed (each adds that
// speed's exact modes, so the bound there becomes rounding; far more than the paper blade needs).
constexpr int max_enrichments = 40;

// ---------------------------------------------------------------------------------------------
// Dense: solve_modes at every speed.

class DenseSweep final : public SpeedSweep {
public:
  DenseSweep(const BladeModel& model, const DampingSpec& damping, int count, EigenSolverKind solver)
      : model_(model), damping_(damping), count_(std::min(count, model.layout.size())), requested_(solver) {
    const Eigen::LLT<Eigen::MatrixXd> mass(model.M);
    upper_ = mass.matrixU();
    upper_complex_ = upper_.cast<std::complex<double>>();
  }

  std::vector<SpeedModes> solve(const std::vector<double>& speeds,
                                const std::function<void(int, int)>& progress) override {
    std::vector<SpeedModes> out;
    out.reserve(speeds.size());
    for (std::size_t s = 0; s < speeds.size(); ++s) {
      out.push_back(at(speeds[s], true));
      if (progress) progress(static_cast<int>(s) + 1, static_cast<int>(speeds.size()));
    }
    return out;
  }

  SpeedModes at(double speed, bool certify) override {
    const ModalSolution sol = oscillating_modes(speed);
    used_ = sol.solver;
    SpeedModes out;
    out.speed_rad_s = speed;
    const int k = static_cast<int>(sol.modes.size());
    out.shapes.resize(model_.layout.size(), k);
    for (int j = 0; j < k; ++j) {
      const Mode& m = sol.modes[j];
      out.frequency_hz.push_back(m.frequency_hz);
      out.natural_hz.push_back(std::abs(m.eigenvalue) / two_pi);
      out.damping_ratio.push_back(m.damping_ratio);
      out.family.push_back(m.family);
      out.shapes.col(j) = upper_complex_ * m.shape;  // Lᵀq: qᴴMq = 1 makes it a unit vector
    }
    if (certify) {
      out.bound.assign(k, 0.0);
      const Eigen::MatrixXd K = model_.stiffness(speed);
      const Eigen::MatrixXd absolute = K.cwiseAbs();
      for (const Mode& m : sol.modes) {
        out.rounding.push_back(
            frequency_rounding(absolute, m.shape.cwiseAbs(), (m.shape.adjoint() * K * m.shape)(0).real()));
      }
    }
    return out;
  }

  double whole_frequency(double speed, const Eigen::VectorXcd& shape) override {
    const SpeedModes modes = at(speed, false);
    Eigen::Index best = 0;
    (modes.shapes.adjoint() * shape).cwiseAbs2().maxCoeff(&best);
    return modes.frequency_hz[best];
  }

  Eigen::MatrixXd dofs() const override {
    return upper_.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(upper_.rows(), upper_.cols()));
  }
  Eigen::MatrixXd metric() const override { return upper_; }
  EigenSolverKind solver() const override { return used_; }
  bool reduced() const override { return false; }
  int vectors() const override { return model_.layout.size(); }
  std::vector<double> sample_speeds() const override { return {}; }

private:
  // The modes up to the count_-th that oscillates, by |λ| (solve_modes): overdamped roots (0 Hz) that
  // a heavy damping puts among them do not take a candidate's place (Rayleigh ζ = 0.3 at 600 rad/s
  // puts five rotation and axial roots at 3418 Hz below a bending mode at 3104 Hz, ζ = 0.42).
  ModalSolution oscillating_modes(double speed) const {
    const SecondOrderSystem system = system_at(model_, speed, damping_matrix(model_, damping_, speed));
    const int all = model_.layout.size();
    for (int count = count_;; ) {
      ModalSolution sol = solve_modes(model_, system, speed, count, requested_);
      const auto oscillating = std::count_if(sol.modes.begin(), sol.modes.end(),
                                             [](const Mode& m) { return m.frequency_hz > 0; });
      if (oscillating >= count_ || count >= all) return sol;
      count = std::min(all, count + count_ - static_cast<int>(oscillating));
    }
  }

  const BladeModel& model_;
  DampingSpec damping_;
  int count_;
  EigenSolverKind requested_, used_ = EigenSolverKind::dense;
  Eigen::MatrixXd upper_;  // Lᵀ, M = L Lᵀ
  Eigen::MatrixXcd upper_complex_;
};

// The positive root θ of k − θc − θ²m = 0 (k = xᵀKx, c = xᵀĈx, m = xᵀMx): for an eigenvector its
// frequency, for any vector the Rayleigh functional of the hyperbolic problem (stationary at the
// eigenvectors, so its error is quadratic in theirs).
double rayleigh_frequency(double k, double c, double m) {
  const double root = std::sqrt(c * c + 4 * k * m);
  return c >= 0 ? 2 * k / (c + root) : 0.5 * (root - c) / m;
}

// ---------------------------------------------------------------------------------------------
// Reduced: one basis for the whole speed range, every frequency bounded against the whole model.

class ReducedSweep final : public SpeedSweep {
public:
  ReducedSweep(const BladeModel& model, int count, double tolerance, double lo, double hi)
      : model_(model),
        n_(model.layout.size()),
        count_(std::min(count, model.layout.size())),
        pairs_(std::min(count_ + 1, model.layout.size())),
        tolerance_(tolerance),
        mass_(model.M) {
    // Ĉ₁ = J C_G1: the rows of u change sign.
    C1_ = model.C_G1;
    C1_.middleRows(model.layout.axial_offset(), model.layout.axial_count) *= -1;
    C1_ = 0.5 * (C1_ + C1_.transpose());
    gram_floor_ = std::clamp(0.002 * tolerance, 1e-24, 1e-10);
    absolute_KS_ = model.K_S.cwiseAbs();
    absolute_KC1_ = model.K_C1.cwiseAbs();
    V_.resize(n_, 0);
    for (double speed : {lo, 0.5 * (lo + hi), hi}) add_sample(speed);
  }

  std::vector<SpeedModes> solve(const std::vector<double>& speeds,
                                const std::function<void(int, int)>& progress) override {
    const int ns = static_cast<int>(speeds.size());
    std::vector<SpeedModes> out(ns);
    for (int s = 0; s < ns; ++s) {
      out[s] = at(speeds[s], true);
      if (progress) progress(s + 1, ns);
    }
    const auto worst_bound = [](const SpeedModes& m) {
      return m.bound.empty() ? 0.0 : *std::max_element(m.bound.begin(), m.bound.end());
    };
    for (int round = 0; round < max_enrichments; ++round) {
      int worst = -1;
      double largest = tolerance_;
      for (int s = 0; s < ns; ++s) {
        const double b = worst_bound(out[s]);
        if (b > largest) largest = b, worst = s;
      }
      if (worst < 0) break;
      const Eigen::Index before = V_.cols();
      add_sample(speeds[worst]);
      if (V_.cols() == before) break;  // that speed's modes are in the basis already
      for (int s = 0; s < ns; ++s) {
        if (worst_bound(out[s]) > tolerance_) {
          out[s] = at(speeds[s], true);
        } else {  // the basis grew by appending: old coordinates stay valid, padded with zeros
          const Eigen::Index rows = out[s].shapes.rows();
          out[s].shapes.conservativeResize(V_.cols(), Eigen::NoChange);
          out[s].shapes.bottomRows(V_.cols() - rows).setZero();
        }
      }
    }
    for (const SpeedModes& m : out) require_certified(m);
    return out;
  }

  SpeedModes at(double speed, bool certify) override {
    const int m = static_cast<int>(V_.cols());
    const int p = std::min(pairs_, m);
    Kr_ = KSr_;
    Kr_.noalias() += (speed * speed) * KC1r_;
    Cr_ = speed * C1r_;
    reduced_cholesky_.compute(Kr_);
    if (reduced_cholesky_.info() != Eigen::Success) throw not_positive(speed);
    // Hermitian form of Kr − ωĈr − ω²I: [[0, Rᵀ], [R, −Ĉr]] with Kr = R Rᵀ; eigenvalues ±ω.
    H_.setZero(2 * m, 2 * m);
    H_.bottomLeftCorner(m, m) = reduced_cholesky_.matrixL();
    H_.bottomRightCorner(m, m) = -Cr_;
    // The last speed's Ritz values guess these (the speeds come in order).
    eigensolver_.solve(H_, m, p, theta_.size() == p ? &theta_ : nullptr);
    Xr_ = eigensolver_.vectors().block(m, 0, m, p);
    Xr_.colwise().normalize();
    KrX_.noalias() = Kr_ * Xr_;
    CrX_.noalias() = Cr_ * Xr_;
    theta_.resize(p);
    stiffness_form_.resize(p);
    for (int j = 0; j < p; ++j) {
      // The positive root of k − θc − θ² = 0 (xᵀx = 1): the Ritz value, as a Rayleigh quotient.
      const double k = Xr_.col(j).dot(KrX_.col(j)), c = Xr_.col(j).dot(CrX_.col(j));
      theta_(j) = rayleigh_frequency(k, c, 1.0);
      stiffness_form_(j) = k;
    }
    SpeedModes out;
    out.speed_rad_s = speed;
    const int k = std::min(count_, p);
    out.frequency_hz.resize(k);
    out.damping_ratio.assign(k, 0.0);
    for (int j = 0; j < k; ++j) out.frequency_hz[j] = theta_(j) / two_pi;
    out.natural_hz = out.frequency_hz;
    out.shapes = Xr_.leftCols(k).cast<std::complex<double>>();
    if (certify) {
      out.bound = bounds(speed, k);
      families(out, speed, k);
    }
    return out;
  }

  double whole_frequency(double speed, const Eigen::VectorXcd& shape) override {
    Eigen::VectorXd omega;
    Eigen::MatrixXd X;
    whole_modes(speed, pairs_, omega, X);
    const Eigen::VectorXcd overlap = X.transpose().cast<std::complex<double>>() * (MV_.cast<std::complex<double>>() * shape);
    Eigen::Index best = 0;
    overlap.cwiseAbs2().maxCoeff(&best);
    return omega(best) / two_pi;
  }

  Eigen::MatrixXd dofs() const override { return V_; }
  Eigen::MatrixXd metric() const override { return MV_.transpose(); }
  EigenSolverKind solver() const override { return EigenSolverKind::dense; }
  bool reduced() const override { return true; }
  int vectors() const override { return static_cast<int>(V_.cols()); }
  std::vector<double> sample_speeds() const override { return samples_; }

private:
  ReducedSweepUnavailable not_positive(double speed) const {
    return ReducedSweepUnavailable(fmt::format("the stiffness is not positive definite at {} rad/s", speed));
  }

  // The `pairs` lowest modes of the whole model at `speed`: ω ascending, x M-normalized.
  void whole_modes(double speed, int pairs, Eigen::VectorXd& omega, Eigen::MatrixXd& X) {
    const Eigen::MatrixXd K = model_.stiffness(speed);
    const auto L = mass_.matrixL();
    Eigen::MatrixXd Kt = L.solve(K);
    Kt = L.solve(Kt.transpose()).transpose();
    Kt = 0.5 * (Kt + Kt.transpose());
    Eigen::MatrixXd Ct = L.solve(speed * C1_);
    Ct = L.solve(Ct.transpose()).transpose();
    Ct = 0.5 * (Ct + Ct.transpose());
    const Eigen::LLT<Eigen::MatrixXd> stiffness(Kt);
    if (stiffness.info() != Eigen::Success) throw not_positive(speed);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * n_, 2 * n_);
    H.bottomLeftCorner(n_, n_) = stiffness.matrixL();
    H.bottomRightCorner(n_, n_) = -Ct;
    SubsetEigensolver eig;
    eig.solve(H, n_, pairs);
    X = mass_.matrixU().solve(eig.vectors().block(n_, 0, n_, pairs));
    omega.resize(pairs);
    for (int j = 0; j < pairs; ++j) {
      X.col(j) /= std::sqrt(X.col(j).dot(model_.M * X.col(j)));
      omega(j) = rayleigh_frequency(X.col(j).dot(K * X.col(j)), speed * X.col(j).dot(C1_ * X.col(j)), 1.0);
    }
  }

  // Appends the whole model's modes at `speed` to the basis (their parts outside it, M-orthonormal).
  void add_sample(double speed) {
    Eigen::VectorXd omega;
    Eigen::MatrixXd W;
    whole_modes(speed, pairs_, omega, W);
    // What the basis misses of each mode, measured in energy (the K norm, each mode scaled to 1):
    // a part of energy share g changes the Ritz frequency by about g, whatever its mass share.
    const Eigen::MatrixXd K = model_.stiffness(speed);
    for (Eigen::Index j = 0; j < W.cols(); ++j) W.col(j) /= std::sqrt(W.col(j).dot(K * W.col(j)));
    for (int pass = 0; pass < 2 && V_.cols() > 0; ++pass) W -= V_ * (MV_.transpose() * W);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> energy(W.transpose() * K * W);
    Eigen::Index first = 0;
    while (first < energy.eigenvalues().size() && energy.eigenvalues()(first) < gram_floor_) ++first;
    W = W * energy.eigenvectors().rightCols(energy.eigenvalues().size() - first);
    // M-orthonormal, and M-orthogonal to the basis (twice: the second pass repairs the first's rounding).
    Eigen::MatrixXd added(n_, 0);
    for (int pass = 0; pass < 2 && W.cols() > 0; ++pass) {
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(W.transpose() * model_.M * W);
      const Eigen::VectorXd g = gram.eigenvalues();
      Eigen::Index dependent = 0;
      while (dependent < g.size() && g(dependent) <= 1e-14 * g(g.size() - 1)) ++dependent;
      const Eigen::Index kept = g.size() - dependent;
      added = W * gram.eigenvectors().rightCols(kept) * g.tail(kept).cwiseSqrt().cwiseInverse().asDiagonal();
      if (V_.cols() > 0) added -= V_ * (MV_.transpose() * added);
      W = added;
    }
    samples_.push_back(speed);
    if (added.cols() == 0) return;
    const Eigen::Index old = V_.cols();
    V_.conservativeResize(Eigen::NoChange, old + added.cols());
    V_.rightCols(added.cols()) = added;
    KSV_ = model_.K_S * V_;
    KC1V_ = model_.K_C1 * V_;
    C1V_ = C1_ * V_;
    MV_ = model_.M * V_;
    KSr_ = V_.transpose() * KSV_;
    KC1r_ = V_.transpose() * KC1V_;
    C1r_ = V_.transpose() * C1V_;
    KSr_ = 0.5 * (KSr_ + KSr_.transpose());
    KC1r_ = 0.5 * (KC1r_ + KC1r_.transpose());
    C1r_ = 0.5 * (C1r_ + C1r_.transpose());
  }

  // Relative bounds on the first k Ritz frequencies of the last at() against the whole model;
  // all unbounded if the Ritz intervals overlap or a mode could be missed.
  std::vector<double> bounds(double speed, int k) {
    const int p = static_cast<int>(theta_.size());
    std::vector<double> failed(k, unbounded);
    K_ = model_.K_S;
    K_.noalias() += (speed * speed) * model_.K_C1;
    stiffness_cholesky_.compute(K_);
    if (stiffness_cholesky_.info() != Eigen::Success) throw not_positive(speed);
    // Residuals Q(θ_j) x_j = K x − θ Ĉ x − θ² M x, in the K⁻¹ norm.
    KX_.noalias() = KSV_ * Xr_;
    KX_.noalias() += (speed * speed) * (KC1V_ * Xr_);
    CX_.noalias() = C1V_ * Xr_;
    MX_.noalias() = MV_ * Xr_;
    residual_ = KX_ - CX_ * (speed * theta_).asDiagonal();
    residual_.noalias() -= MX_ * theta_.cwiseAbs2().asDiagonal();
    stiffness_cholesky_.matrixL().solveInPlace(residual_);
    mu_.resize(p);
    eps_.resize(p);
    for (int j = 0; j < p; ++j) {
      mu_(j) = 1 / theta_(j);
      eps_(j) = residual_.col(j).norm() / (theta_(j) * std::sqrt(stiffness_form_(j) + theta_(j) * theta_(j)));
    }
    // Certify the lowest t ≥ k modes, t where the gap to mode t + 1 is widest; σ in that gap.
    int t = p;
    double tau = 0;  // all n modes present: no eigenvalue of the μ form lies in (0, 1/θ_n)
    if (p < n_) {
      double widest = 0;
      t = -1;
      for (int c = k; c < p; ++c) {  // c modes certified, mode c + 1 (index c) above them
        const double gap = (mu_(c - 1) - eps_(c - 1) - (mu_(c) + eps_(c))) / mu_(c - 1);
        if (gap > widest) widest = gap, t = c;
      }
      if (t < 0) return failed;
      tau = 0.5 * (mu_(t - 1) - eps_(t - 1) + mu_(t) + eps_(t));
      const double sigma = 1 / tau;
      Q_ = K_;
      Q_.noalias() -= (sigma * speed) * C1_;
      Q_.noalias() -= (sigma * sigma) * model_.M;
      if (inertia_.negatives(Q_) != t) return failed;
    }
    for (int j = 0; j + 1 < t; ++j) {
      if (!(mu_(j) - eps_(j) > mu_(j + 1) + eps_(j + 1))) return failed;
    }
    std::vector<double> bound(k);
    for (int j = 0; j < k; ++j) {
      const double below = j + 1 < t ? mu_(j + 1) + eps_(j + 1) : tau;  // the next eigenvalue of the μ form is below this
      bound[j] = eps_(j) * eps_(j) / (mu_(j) - below) / mu_(j);
    }
    return bound;
  }

  // Families from the kinetic-energy shares of the first k Ritz vectors, and their frequencies'
  // rounding (after bounds()).
  void families(SpeedModes& out, double speed, int k) {
    X_.noalias() = V_ * Xr_.leftCols(k);
    absolute_X_ = X_.cwiseAbs();
    spread_.noalias() = absolute_KS_ * absolute_X_;
    spread_.noalias() += (speed * speed) * (absolute_KC1_ * absolute_X_);
    out.family.resize(k);
    out.rounding.resize(k);
    for (int j = 0; j < k; ++j) {
      out.family[j] = dominant_family(model_, X_.col(j).cast<std::complex<double>>(), shares_);
      // frequency_rounding with |K(Ω)| ≤ |K_S| + Ω²|K_C1|
      out.rounding[j] = std::max(eigensolver_rounding, 10 * std::numeric_limits<double>::epsilon() *
                                                           absolute_X_.col(j).dot(spread_.col(j)) / stiffness_form_(j));
    }
  }

  const BladeModel& model_;
  int n_, count_, pairs_;
  double tolerance_, gram_floor_;
  Eigen::LLT<Eigen::MatrixXd> mass_;
  Eigen::MatrixXd C1_;
  Eigen::MatrixXd V_, KSV_, KC1V_, C1V_, MV_, KSr_, KC1r_, C1r_;
  std::vector<double> samples_;
  // Workspace of at() and bounds(), reused from speed to speed.
  Eigen::MatrixXd Kr_, Cr_, H_, Xr_, KrX_, CrX_, K_, Q_, KX_, CX_, MX_, residual_, X_, absolute_X_, spread_;
  Eigen::MatrixXd absolute_KS_, absolute_KC1_;
  Eigen::VectorXd theta_, stiffness_form_, mu_, eps_;
  std::vector<double> shares_;
  Eigen::LLT<Eigen::MatrixXd> reduced_cholesky_, stiffness_cholesky_;
  SubsetEigensolver eigensolver_;
  InertiaCounter inertia_;
};

}  // namespace

void require_certified(const SpeedModes& modes) {
  for (double bound : modes.bound) {
    if (!std::isfinite(bound)) {
      throw ReducedSweepUnavailable(
          fmt::format("the reduced model's modes could not be certified at {} rad/s", modes.speed_rad_s));
    }
  }
}

bool reduced_sweep_applies(const BladeModel& model, const DampingSpec& damping) {
  if (damping.damped()) return false;
  const DofLayout& l = model.layout;
  const int n = l.size();
  const auto axial = [&](int i) { return i >= l.axial_offset() && i < l.axial_offset() + l.axial_count; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (model.C_G1(i, j) != -model.C_G1(j, i)) return false;  // gyroscopic, not damping
      if (axial(i) != axial(j)) {
        if (model.M(i, j) != 0 || model.K_S(i, j) != 0 || model.K_C1(i, j) != 0) return false;
      } else if (model.C_G1(i, j) != 0) {
        return false;
      }
    }
  }
  return true;
}

std::unique_ptr<SpeedSweep> make_dense_speed_sweep(const BladeModel& model, const DampingSpec& damping, int count,
                                                   EigenSolverKind solver) {
  return std::make_unique<DenseSweep>(model, damping, count, solver);
}

std::unique_ptr<SpeedSweep> make_speed_sweep(const BladeModel& model, const DampingSpec& damping, int count,
                                             EigenSolverKind solver, double reduction_tolerance, double speed_lo,
                                             double speed_hi) {
  if (solver == EigenSolverKind::automatic && reduced_sweep_applies(model, damping)) {
    try {
      return std::make_unique<ReducedSweep>(model, count, reduction_tolerance, speed_lo, speed_hi);
    } catch (const ReducedSweepUnavailable&) {
      // statically unstable at a sample speed: the dense sweep says so properly
    }
  }
  return make_dense_speed_sweep(model, damping, count, solver);
}

}  // namespace bladestab
