#include "bladestab/ltp/floquet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "bladestab/base/constants.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/pulse_monodromy.hpp"
#include "bladestab/ltp/rkf45.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

double max_abs(const Eigen::VectorXcd& rho) { return rho.cwiseAbs().maxCoeff(); }

Eigen::VectorXcd sorted_by_magnitude(Eigen::VectorXcd rho) {
  std::sort(rho.data(), rho.data() + rho.size(), [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  return rho;
}

// The Hill matrix in the real sin/cos basis: with x = Σ c_k e^{ikθt}, a_k = c_k + c_{−k} and
// b_k = i (c_k − c_{−k}) are the cosine and sine amplitudes; H_r = P H P⁻¹ is real. P and P⁻¹
// have at most two identity blocks per block row and column, so H_r is summed block by block
// (O(N² n) instead of two dense complex N × N products, N = n(2q + 1)).
Eigen::MatrixXd real_hill_matrix(const PeriodicSystem& sys, int q) {
  const int n = sys.state_size(), N = n * (2 * q + 1);
  const Eigen::MatrixXcd H = hill_matrix(sys, q);
  struct Entry {
    int row, col;  // block indices
    cplx value;    // times the identity block
  };
  const cplx i(0, 1);
  std::vector<Entry> P{{0, q, 1}}, Pinv{{q, 0, 1}};  // constant term first
  for (int k = 1; k <= q; ++k) {
    const int cos_row = 2 * k - 1, sin_row = 2 * k, plus = q + k, minus = q - k;
    P.insert(P.end(), {{cos_row, plus, 1}, {cos_row, minus, 1}, {sin_row, plus, i}, {sin_row, minus, -i}});
    Pinv.insert(Pinv.end(),
                {{plus, cos_row, 0.5}, {plus, sin_row, -0.5 * i}, {minus, cos_row, 0.5}, {minus, sin_row, 0.5 * i}});
  }
  Eigen::MatrixXd Hr = Eigen::MatrixXd::Zero(N, N);
  for (const Entry& p : P) {
    for (const Entry& r : Pinv) {
      Hr.block(p.row * n, r.col * n, n, n) += (p.value * r.value * H.block(p.col * n, r.row * n, n, n)).real();
    }
  }
  return Hr;
}

// ln ρ / T, and (46) δ = −2π Re λ / |Im λ|.
std::optional<double> log_decrement(cplx rho, double T) {
  const cplx lambda = std::log(rho) / T;
  if (lambda.imag() == 0) return std::nullopt;
  return -two_pi * lambda.real() / std::abs(lambda.imag());
}

struct Attempt {
  Eigen::VectorXcd multipliers;
  double error = 0;
  int harmonics = 0, steps = 0;
  Eigen::MatrixXd monodromy;  // Φ(T), where the method has one
};

bool all_finite(const Eigen::MatrixXd& m) { return m.allFinite(); }

Eigen::VectorXcd eigenvalues_of(const Eigen::MatrixXd& phi) {
  Eigen::EigenSolver<Eigen::MatrixXd> eig(phi, false);
  if (eig.info() != Eigen::Success) throw NumericalError("the eigenvalues of the monodromy matrix did not converge");
  return sorted_by_magnitude(eig.eigenvalues());
}

// Counts refinement levels for FloquetOptions::progress. plan(n): at most n more levels (and the
// stages after them) from here.
class LevelCounter {
public:
  explicit LevelCounter(const std::function<void(int, int)>& progress) : progress_(progress) {}
  void plan(int levels) { planned_ = std::max(levels, 1); }
  void level_done() {
    ++done_, planned_ = std::max(planned_ - 1, 1);
    if (progress_) progress_(done_, done_ + planned_);
  }
  void finished() {
    if (progress_) progress_(done_, done_);
  }

private:
  const std::function<void(int, int)>& progress_;
  int done_ = 0, planned_ = 1;
};

// The harmonic levels q = start, start + 2, … that refine_harmonics may take.
int harmonic_levels(const PeriodicSystem& sys, int start, int max_q, int max_size) {
  int levels = 0;
  for (int q = start; q <= max_q && sys.state_size() * (2 * q + 1) <= max_size; q += 2) ++levels;
  return levels;
}

// Raises q by 2 from `start` until the whole multiplier sets of two successive truncations agree
// within tol, the Hill matrix would exceed `max_size` rows, or q passes `max_q`. Returns whether
// the tolerance was met; `out` holds the last truncation either way.
template <class Method>
bool refine_harmonics(const PeriodicSystem& sys, Method method, int start, int max_q, int max_size, double tol,
                      Attempt& out, LevelCounter& counter) {
  const int levels = harmonic_levels(sys, start, max_q, max_size);
  counter.plan(levels + 1);  // and the monodromy the result is checked against
  Eigen::VectorXcd previous = method(sys, std::max(start - 2, 1));
  for (int level = 0, q = start; level < levels; ++level, q += 2) {
    const Eigen::VectorXcd current = method(sys, q);
    counter.level_done();
    out = {current, multiplier_set_distance(current, previous), q, 0, {}};
    if (out.error <= tol * std::max(1.0, max_abs(current))) return true;
    previous = current;
  }
  return false;
}

constexpr int max_magnus_steps = 1 << 17;

// The Magnus levels refine_steps may take: from `first` doubled up to max_magnus_steps.
int step_levels(int first) {
  int levels = 0;
  for (int steps = first; steps <= max_magnus_steps; steps *= 2) ++levels;
  return levels;
}

// Why a period needs more than max_magnus_steps steps (h‖A‖ ≤ 2 asks ‖A‖T/2 of them): the pulses
// are too slow where even the slowest kept mode needs that many (a speed range from 0 to 1e-300
// rad/s did), else the model keeps modes stiffer than the period takes. Which of the settings
// that choose the modes the scene has is not known here: the message states how many it kept.
NumericalError too_many_steps(const PeriodicSystem& sys) {
  const double slowest = sys.modal_frequencies.minCoeff(), stiffest = sys.modal_frequencies.maxCoeff();
  const std::string need = fmt::format("the monodromy needs more than {} Magnus steps per period 2π/θ = {:.3g} s "
                                       "(θ = {:.3g} rad/s)", max_magnus_steps, sys.period(), sys.angular_frequency);
  if (slowest * sys.period() / 2 > max_magnus_steps) {
    return NumericalError(fmt::format("{} even for the slowest mode kept, {:.3g} rad/s: the pulses are too slow for "
                                      "a Floquet analysis of this blade; raise the pulse frequency", need, slowest));
  }
  return NumericalError(fmt::format("{}: the model keeps {} of its {} modes, the stiffest at {:.3g} rad/s; keep "
                                    "fewer (a modal cut-off below it, or fewer reduction vectors)",
                                    need, sys.kept_modes, sys.all_modes, stiffest));
}

// Doubles the Magnus steps until the multiplier sets of successive counts show convergence.
//
// The ladder starts at 1/64 of the count where h‖A‖ ≤ 2 (the Magnus series' sufficient
// condition): the exponential takes A₀'s stiff modes exactly, and on the paper blade 128 steps
// are within 1e-8 where that condition asks for 512. Below the condition a level is trusted only
// on evidence: with Δ_N the distance between the sets at N and N/2 steps and r = Δ_{N/2}/Δ_N,
//  - 16 ≤ r ≤ 256: the sixth-order method is in its asymptotic range (each doubling divides the
//    error by ~64); the error of level N is then at most Δ_N/15, the bound for a convergence of
//    fourth order or better from here on;
//  - 4 ≤ r < 16, or three levels within tol, or h‖A‖ ≤ 2: the error is taken as Δ_N;
//  - r > 256: level N/2 was pre-asymptotic and may have landed near the answer by chance
//    (measured: Δ_N 15× below the true error at F̄ = 12, N = 256); the next level decides.
// Two levels that agree by chance (the first release's failure) do not pass: the level before
// them must disagree by the ratio.
Attempt refine_steps(const PeriodicSystem& sys, double tol, LevelCounter& counter) {
  const int safe = minimum_magnus_steps(sys);
  if (safe > max_magnus_steps) throw too_many_steps(sys);
  const int first = std::max(8, safe / 64);
  counter.plan(step_levels(first) + 1);  // and the checks after
  Eigen::VectorXcd previous;
  double previous_distance = std::numeric_limits<double>::infinity();
  bool overflowed_before = false;
  for (int steps = first; steps <= max_magnus_steps; steps *= 2) {
    Eigen::MatrixXd phi = magnus_monodromy(sys, steps);
    counter.level_done();
    if (!all_finite(phi)) {
      // From the safe count on the Magnus series converges: two overflows in a row there are growth.
      if (steps > safe && overflowed_before) {
        throw NumericalError("the monodromy matrix overflows the double range (max|ρ| > 1e308): the blade diverges "
                             "within one period, e.g. the mean tip load is far past static buckling; lower "
                             "load.fmax_over_fcr");
      }
      overflowed_before = steps >= safe;
      previous.resize(0);
      previous_distance = std::numeric_limits<double>::infinity();
      continue;
    }
    const Eigen::VectorXcd current = eigenvalues_of(phi);
    if (previous.size() == current.size()) {
      const double distance = multiplier_set_distance(current, previous);
      const double allowed = tol * std::max(1.0, max_abs(current));
      // The ratio needs three levels: with two, previous_distance is still infinite.
      const bool three_levels = std::isfinite(previous_distance);
      const double ratio = three_levels ? previous_distance / distance : 0;
      double error = std::numeric_limits<double>::infinity();
      if (ratio >= 16 && ratio <= 256) {
        error = distance / 15;
      } else if ((ratio >= 4 && ratio < 16) || (three_levels && previous_distance <= allowed) || steps >= safe) {
        error = distance;
      }
      // Not below the rounding of Φ's eigenvalues: an estimate of 0 would claim more than is known.
      error = std::max(error, 1e-14 * std::max(1.0, max_abs(current)));
      if (error <= allowed) return {current, error, 0, steps, phi};
      previous_distance = distance;
    }
    previous = current;
  }
  throw NumericalError(fmt::format("the monodromy matrix did not converge to {:g} within {} Magnus steps per period",
                                   tol, max_magnus_steps));
}

// The system is Hamiltonian (undamped, gyroscopic at most) when Ĉ is skew-symmetric.
bool is_hamiltonian(const PeriodicSystem& sys) {
  const Eigen::MatrixXd& C = sys.modal_C;
  return (C + C.transpose()).norm() <= 1e-12 * std::max(1.0, C.norm());
}

double reciprocal_error(const Eigen::VectorXcd& rho) {
  double worst = 0;
  for (Eigen::Index i = 0; i < rho.size() && std::abs(rho(i)) >= 1; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < rho.size(); ++j) nearest = std::min(nearest, std::abs(rho(i) * rho(j) - 1.0));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// ẏ = (A₀ + φ(t) B) y over one period: the load variation φ and the times where it jumps. Where φ
// is constant from `varies_until` to the period (a pulse train between its contacts), RKF45 stops
// there and `rest` carries the state over the remainder exactly.
struct LoadVariation {
  std::function<double(double)> phi;
  std::vector<double> breakpoints;
  double varies_until = 0;  // 0: the whole period
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)> rest;
};

LoadVariation series_variation(const PeriodicSystem& sys) {
  return {[&sys](double t) { return sys.load_variation(t); }, {}, 0, {}};
}

// Whether A₀ and B have the blocks of periodic_system.hpp's state y = [D η; η̇]: A₀ = [[0, D], [·, ·]]
// with D diagonal, B = [[0, 0], [·, 0]] (exact zeros, as periodic_system builds them; a load scaled
// into A₀ keeps them).
bool has_modal_state_blocks(const PeriodicSystem& sys) {
  const Eigen::Index n = sys.state_size(), m = n / 2;
  if (n != 2 * m) return false;
  Eigen::MatrixXd off_diagonal = sys.A0.topRightCorner(m, m);
  off_diagonal.diagonal().setZero();
  return off_diagonal.isZero(0) && sys.A0.topLeftCorner(m, m).isZero(0) && sys.B.topRows(m).isZero(0) &&
         sys.B.bottomRightCorner(m, m).isZero(0);
}

// X(T) of Ẋ = (A₀ + φ(t) B) X from X(0) by RKF45, landing on the load's breakpoints (and by the
// load's exact `rest` after `varies_until`).
constexpr Eigen::Index few_columns = 4;
Eigen::MatrixXd rkf45_propagate(const PeriodicSystem& sys, const LoadVariation& load, const Eigen::MatrixXd& X0,
                                double rtol, double atol) {
  const Eigen::Index n = X0.rows(), columns = X0.cols(), m = n / 2;
  const bool blocks = columns > few_columns && has_modal_state_blocks(sys);
  Eigen::MatrixXd lower_left(blocks ? m : 0, blocks ? m : 0);  // A₀'s lower-left block + φ(t) B's
  const OdeFunction rhs = [&sys, &load, n, m, columns, blocks, &lower_left](double t, const Eigen::VectorXd& y,
                                                                            Eigen::VectorXd& dy) {
    dy.resize(y.size());
    const auto Y = Eigen::Map<const Eigen::MatrixXd>(y.data(), n, columns);
    auto D = Eigen::Map<Eigen::MatrixXd>(dy.data(), n, columns);
    if (blocks) {
      // A whole monodromy's n columns by GEMM on the nonzero blocks: a quarter of the full products' work.
      D.topRows(m).noalias() = sys.A0.topRightCorner(m, m).diagonal().asDiagonal() * Y.bottomRows(m);
      lower_left = sys.A0.bottomLeftCorner(m, m) + load.phi(t) * sys.B.bottomLeftCorner(m, m);
      D.bottomRows(m).noalias() = lower_left * Y.topRows(m);
      D.bottomRows(m).noalias() += sys.A0.bottomRightCorner(m, m) * Y.bottomRows(m);
    } else if (columns <= few_columns) {
      // A few columns (an eigenvector): Eigen's coefficient-wise product, as its blocked GEMM would
      // spend more time packing the n×n operand than multiplying.
      D.noalias() = sys.A0.lazyProduct(Y);
      D.noalias() += load.phi(t) * sys.B.lazyProduct(Y);
    } else {
      D.noalias() = sys.A0 * Y;
      D.noalias() += (load.phi(t) * sys.B) * Y;
    }
  };
  Eigen::VectorXd x = X0.reshaped();
  StepControl control;
  control.rtol = rtol;
  control.atol = atol;
  const double end = load.rest ? load.varies_until : sys.period();
  rkf45_integrate(rhs, x, 0, end, control, load.breakpoints, {}, [](double, const Eigen::VectorXd&) {});
  return load.rest ? load.rest(x.reshaped(n, columns)) : Eigen::MatrixXd(x.reshaped(n, columns));
}

// The dominant eigenpair (ρ, v) of Φ against x(T), v integrated over one period by RKF45.
struct DominantCheck {
  double residual = 0;          // ‖x(T) − ρ v‖ / |ρ|
  double multiplier_error = 0;  // |ρ' − ρ| / |ρ|, ρ' = wᴴx(T) / wᴴv with w the left eigenvector
};

// The residual carries every error of Φ in the direction of v, also those that move no multiplier
// (a Magnus Φ of a stable blade was 3.6e-5 off in v while its multipliers had settled to 2e-7);
// ρ' is first-order exact in x(T) and its error second order in v's: the check of the multiplier
// itself. Where ρ is ill-conditioned (a near-defective pair), the residual stands for it.
DominantCheck check_dominant(const Eigen::MatrixXd& phi, const PeriodicSystem& sys, const LoadVariation& load,
                             double rtol) {
  Eigen::EigenSolver<Eigen::MatrixXd> eig(phi, true);
  if (eig.info() != Eigen::Success) throw NumericalError("the eigenvectors of the monodromy matrix did not converge");
  Eigen::Index k = 0;
  eig.eigenvalues().cwiseAbs().maxCoeff(&k);
  const cplx rho = eig.eigenvalues()(k);
  Eigen::VectorXcd v = eig.eigenvectors().col(k).normalized();
  Eigen::VectorXcd start, end;  // v as integrated, and x(T)
  DominantCheck c;
  if (rho.imag() == 0) {
    // A real multiplier has a real eigenvector up to a phase: one column to integrate, not two.
    Eigen::Index largest = 0;
    v.cwiseAbs().maxCoeff(&largest);
    v *= std::conj(v(largest)) / std::abs(v(largest));
    const Eigen::VectorXd x = v.real();
    const Eigen::VectorXd xT = rkf45_propagate(sys, load, x, rtol, rtol * 1e-3);
    c.residual = ((xT - rho.real() * x).norm() + v.imag().norm() * (1 + std::abs(rho))) / std::abs(rho);
    start = x.cast<cplx>();
    end = xT.cast<cplx>();
  } else {
    Eigen::MatrixXd X(sys.state_size(), 2);
    X << v.real(), v.imag();
    const Eigen::MatrixXd XT = rkf45_propagate(sys, load, X, rtol, rtol * 1e-3);
    end = XT.col(0).cast<cplx>() + cplx(0, 1) * XT.col(1).cast<cplx>();
    start = v;
    c.residual = (end - rho * v).norm() / std::abs(rho);
  }
  // wᴴ is row k of V⁻¹ (wᴴv = 1); ‖w‖‖v‖ is ρ's condition number κ: ~1 for the blade's separate
  // multipliers, 1e7 for the double one on a damped Mathieu boundary, where ρ' was 9e-4 off (its
  // error grows like κ) and the residual 6e-10.
  const Eigen::RowVectorXcd w = eig.eigenvectors().partialPivLu().inverse().row(k);
  const double condition = w.norm() * eig.eigenvectors().col(k).norm();
  c.multiplier_error = condition > 1e3 ? c.residual : std::abs((w * end)(0) / (w * start)(0) - rho) / std::abs(rho);
  return c;
}

// Checks of a monodromy matrix that do not share the Magnus propagator's failure modes; throws
// NumericalError naming the check that failed.
FloquetChecks check_monodromy(const Eigen::MatrixXd& phi, const Eigen::VectorXcd& rho, const PeriodicSystem& sys,
                              double tol, bool integrate, const LoadVariation& load) {
  FloquetChecks c;
  // Φ carries relative errors of ~1e-13 (rounding over the steps), which its determinant magnifies by
  // Φ's condition (measured: 8e-7 at 1/rcond = 2.7e7); not informative beyond 1e10.
  const double rcond = Eigen::PartialPivLU<Eigen::MatrixXd>(phi).rcond();
  c.determinant_error = rcond < 1e-10 ? std::numeric_limits<double>::quiet_NaN() : liouville_error(phi, sys);
  c.reciprocal_error = is_hamiltonian(sys) ? reciprocal_error(rho) : std::numeric_limits<double>::quiet_NaN();
  const double rtol = std::clamp(tol * 1e-2, 1e-9, 1e-6);
  // An explicit integration of a stiff (unreduced) system would take far longer than the answer.
  const double integrated = load.rest ? load.varies_until / sys.period() : 1;
  const bool affordable = minimum_magnus_steps(sys) * integrated <= 8192;
  if (integrate && affordable) {
    const DominantCheck d = check_dominant(phi, sys, load, rtol);
    c.residual = d.residual;
    c.multiplier_error = d.multiplier_error;
  } else {
    c.residual = c.multiplier_error = std::numeric_limits<double>::quiet_NaN();
  }
  c.monodromy_max_abs_multiplier = max_abs(rho);
  const double allowed = std::max(10 * tol, 1e-8);
  if (c.determinant_error > allowed + 1e-13 / rcond) {
    throw NumericalError(fmt::format("monodromy check failed: det Φ(T) is off Liouville's exp(∫tr A) by {:.2g}; "
                                     "lower the tolerance", c.determinant_error));
  }
  // The partner 1/ρ of a large ρ is known only to the rounding of Φ, ~1e-13‖Φ‖ with ‖Φ‖ ~ max|ρ|;
  // ρ times it then carries 1e-13 max|ρ|² (measured 2e-13 at max|ρ| = 2.6e5): a margin of 100.
  if (c.reciprocal_error > allowed + 1e-11 * max_abs(rho) * max_abs(rho)) {
    throw NumericalError(fmt::format("monodromy check failed: the undamped multipliers are not reciprocal pairs "
                                     "(|ρ ρ' − 1| = {:.2g}); lower the tolerance", c.reciprocal_error));
  }
  // RKF45's global error over the many oscillations of a period reaches ~1e2–1e3 rtol.
  if (c.multiplier_error > allowed + 1e3 * rtol) {
    throw NumericalError(fmt::format("monodromy check failed: an independent RKF45 integration of the dominant "
                                     "Floquet vector gives a multiplier {:.2g} away; lower the tolerance",
                                     c.multiplier_error));
  }
  return c;
}

FloquetResult result_of(FloquetMethod method, const Attempt& attempt, const FloquetChecks& checks, double period) {
  FloquetResult result;
  result.method = method;
  result.harmonics = attempt.harmonics;
  result.steps = attempt.steps;
  result.multipliers = attempt.multipliers;
  result.error_estimate = attempt.error;
  result.checks = checks;
  result.max_abs_multiplier = max_abs(attempt.multipliers);
  result.max_real_exponent = std::log(result.max_abs_multiplier) / period;
  result.stable = result.max_abs_multiplier <= 1 + std::max(attempt.error, 1e-9);
  for (Eigen::Index k = 0; k < attempt.multipliers.size(); ++k) {
    result.log_decrements.push_back(log_decrement(attempt.multipliers(k), period));
  }
  return result;
}

}  // namespace

const char* to_string(FloquetMethod m) {
  switch (m) {
    case FloquetMethod::hill: return "hill";
    case FloquetMethod::koopman_hill: return "koopman-hill";
    case FloquetMethod::monodromy: return "monodromy";
    case FloquetMethod::monodromy_rkf45: return "monodromy-rkf45";
    case FloquetMethod::automatic: return "auto";
  }
  return "?";
}

int minimum_magnus_steps(const PeriodicSystem& sys) {
  // max_t ‖A(t)‖₂ ≤ ‖A₀‖₂ + ‖B‖₂ Σ_{m≥1} 2|F_m|
  double load = 0;
  for (std::size_t m = 1; m < sys.load.size(); ++m) load += 2 * std::abs(sys.load[m]);
  // ‖a‖₂ = √λ_max(aᵀa), to the rounding of λ_max (ε‖a‖²): a symmetric eigenvalue solve, several
  // times cheaper than the SVD (which was 9 % of a map of the true pulse train).
  const auto norm2 = [](const Eigen::MatrixXd& a) {
    const Eigen::MatrixXd gram = a.transpose() * a;
    return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly)
                                       .eigenvalues()
                                       .maxCoeff()));
  };
  const double bound = norm2(sys.A0) + load * norm2(sys.B);
  const double steps = std::max({32.0, 8.0 * sys.load.size(), bound * sys.period() / 2});
  return steps > (1 << 30) ? (1 << 30) + 1 : 1 << static_cast<int>(std::ceil(std::log2(steps)));
}

double multiplier_set_distance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  // Pairs matched closest first over all pairs (a double root meets each partner once).
  std::vector<std::tuple<double, Eigen::Index, Eigen::Index>> pairs;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    for (Eigen::Index j = 0; j < b.size(); ++j) pairs.emplace_back(std::abs(a(i) - b(j)), i, j);
  }
  if (std::any_of(pairs.begin(), pairs.end(), [](const auto& p) { return std::isnan(std::get<0>(p)); })) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  double largest = 0;
  for (const auto& [d, i, j] : pairs) {
    if (used_a[i] || used_b[j]) continue;
    used_a[i] = used_b[j] = true;
    largest = std::max(largest, d);
  }
  return largest;
}

double liouville_error(const Eigen::MatrixXd& phi, const PeriodicSystem& sys) {
  // det Φ(T) = exp(∫₀ᵀ tr A dt) = exp(T tr A₀): the load enters only through B, whose trace is 0.
  // In logarithms from the LU factors: damped stiff modes put det Φ far below the smallest double.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(phi);
  double log_det = 0, sign = lu.permutationP().determinant();
  for (Eigen::Index i = 0; i < lu.matrixLU().rows(); ++i) {
    log_det += std::log(std::abs(lu.matrixLU()(i, i)));
    sign *= lu.matrixLU()(i, i) < 0 ? -1 : 1;
  }
  return std::abs(sign * std::exp(log_det - sys.A0.trace() * sys.period()) - 1);
}

Eigen::MatrixXcd hill_matrix(const PeriodicSystem& sys, int q) {
  // The eigensolvers and LU after it may not return on NaN or infinity.
  if (!sys.A0.allFinite() || !sys.B.allFinite() || !std::isfinite(sys.angular_frequency)) {
    throw NumericalError("the periodic system is not finite (check operation.speed_rad_s, load.fmax_over_fcr and "
                         "the damping)");
  }
  const int n = sys.state_size(), blocks = 2 * q + 1;
  const int M = static_cast<int>(sys.load.size()) - 1;
  Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(n * blocks, n * blocks);
  for (int j = -q; j <= q; ++j) {
    for (int k = std::max(-q, j - M); k <= std::min(q, j + M); ++k) {
      H.block((j + q) * n, (k + q) * n, n, n) = sys.harmonic(j - k);
    }
    H.block((j + q) * n, (j + q) * n, n, n).diagonal().array() -= cplx(0, j * sys.angular_frequency);
  }
  return H;
}

Eigen::VectorXcd hill_multipliers(const PeriodicSystem& sys, int q) {
  // Classical sorting: of the n(2q+1) exponents keep the n with the smallest |Im λ|.
  Eigen::EigenSolver<Eigen::MatrixXd> eig(real_hill_matrix(sys, q), false);
  if (eig.info() != Eigen::Success) throw std::runtime_error("Hill eigenvalues did not converge");
  std::vector<cplx> lambda(eig.eigenvalues().data(), eig.eigenvalues().data() + eig.eigenvalues().size());
  std::sort(lambda.begin(), lambda.end(), [](cplx a, cplx b) { return std::abs(a.imag()) < std::abs(b.imag()); });
  const int n = sys.state_size();
  Eigen::VectorXcd rho(n);
  for (int k = 0; k < n; ++k) rho(k) = std::exp(lambda[k] * sys.period());
  return sorted_by_magnitude(rho);
}

Eigen::VectorXcd koopman_hill_multipliers(const PeriodicSystem& sys, int q) {
  // Φ(T) ≈ C e^{HT} W: C sums the block rows, W is the central block column. In the real sin/cos
  // basis (real_hill_matrix: H = P⁻¹ H_r P) this is C_r e^{H_r T} E₀, with P W = E₀ the constant
  // term's block and C_r = C P⁻¹ = [I, I, 0, I, 0, …] (x(0) is a₀ plus the cosine amplitudes).
  // From H_r = V Λ V⁻¹: C_r V e^{ΛT} (V⁻¹ E₀), a real eigenproblem in place of a complex one.
  const int n = sys.state_size(), N = n * (2 * q + 1);
  Eigen::EigenSolver<Eigen::MatrixXd> eig(real_hill_matrix(sys, q), true);
  if (eig.info() != Eigen::Success) throw std::runtime_error("Hill eigenvalues did not converge");
  const Eigen::MatrixXcd V = eig.eigenvectors();
  Eigen::MatrixXcd Y = V.partialPivLu().solve(Eigen::MatrixXcd::Identity(N, n));
  for (int i = 0; i < N; ++i) Y.row(i) *= std::exp(eig.eigenvalues()(i) * sys.period());
  Eigen::MatrixXcd CV = V.topRows(n);  // the constant term, then each cosine amplitude
  for (int k = 1; k <= q; ++k) CV += V.middleRows((2 * k - 1) * n, n);
  const Eigen::MatrixXd Phi = (CV * Y).real();
  return sorted_by_magnitude(Eigen::EigenSolver<Eigen::MatrixXd>(Phi, false).eigenvalues());
}

Eigen::MatrixXd magnus_monodromy(const PeriodicSystem& sys, int steps) {
  return magnus_propagator(sys.A0, sys.B, [&sys](double t) { return sys.load_variation(t); }, 0, sys.period(), steps);
}

Eigen::VectorXcd monodromy_multipliers(const PeriodicSystem& sys, int steps) {
  const Eigen::MatrixXd phi = magnus_monodromy(sys, steps);
  if (!all_finite(phi)) throw NumericalError(fmt::format("the monodromy overflowed with {} Magnus steps", steps));
  return eigenvalues_of(phi);
}

Eigen::MatrixXd rkf45_monodromy(const PeriodicSystem& sys, double rtol) {
  // The scaled coordinates make every entry of Φ order one: atol = rtol.
  const int n = sys.state_size();
  return rkf45_propagate(sys, series_variation(sys), Eigen::MatrixXd::Identity(n, n), rtol, rtol);
}

FloquetResult floquet_multipliers(const PeriodicSystem& sys, const FloquetOptions& options) {
  const double tol = options.tolerance;
  const int q = options.harmonics;
  constexpr int max_q = 40, max_hill_rows = 1200;
  Attempt attempt;
  FloquetChecks checks;
  LevelCounter counter(options.progress);
  switch (options.method) {
    case FloquetMethod::hill:
    case FloquetMethod::koopman_hill: {
      const auto method = options.method == FloquetMethod::hill ? hill_multipliers : koopman_hill_multipliers;
      if (q > 0) {
        // A given q is held to the refinement's own limit: the dense Hill matrix's eigensolve grows
        // like rows³ (q = 60 on the paper blade's 24 states: 2904 rows, most of an hour).
        const int rows = sys.state_size() * (2 * q + 1);
        if (rows > max_hill_rows) {
          throw ParameterError("harmonics", fmt::format("{}: the Hill matrix would have {} rows ({} states × {} harmonics), "
                                       "beyond the {} its methods are held to; use fewer harmonics or the monodromy method",
                                       q, rows, sys.state_size(), 2 * q + 1, max_hill_rows));
        }
        const Eigen::VectorXcd current = method(sys, q), coarser = method(sys, std::max(1, q - 2));
        attempt = {current, multiplier_set_distance(current, coarser), q, 0, {}};
      } else if (!refine_harmonics(sys, method, 2, max_q, max_hill_rows, tol, attempt, counter)) {
        throw NumericalError(fmt::format("{}: the multipliers did not settle to {:g} up to q = {} ({} rows); use "
                                         "the monodromy method", to_string(options.method), tol, attempt.harmonics,
                                         sys.state_size() * (2 * attempt.harmonics + 1)));
      }
      // The kept exponents must agree with the monodromy's (sorting can pick wrong ones).
      const Attempt reference = refine_steps(sys, tol, counter);
      checks = check_monodromy(reference.monodromy, reference.multipliers, sys, tol, false, series_variation(sys));
      const double disagreement = std::abs(max_abs(attempt.multipliers) - max_abs(reference.multipliers));
      if (disagreement > attempt.error + reference.error + tol * std::max(1.0, max_abs(reference.multipliers))) {
        throw NumericalError(fmt::format("{} (q = {}): max|ρ| = {:.8g} disagrees with the monodromy's {:.8g}{}; use "
                                         "the monodromy method", to_string(options.method), attempt.harmonics,
                                         max_abs(attempt.multipliers), max_abs(reference.multipliers),
                                         options.method == FloquetMethod::hill
                                             ? " (the classical sorting kept the wrong exponents)"
                                             : ""));
      }
      break;
    }
    case FloquetMethod::monodromy:
    case FloquetMethod::automatic:
      attempt = refine_steps(sys, tol, counter);
      checks = check_monodromy(attempt.monodromy, attempt.multipliers, sys, tol, options.independent_check,
                               series_variation(sys));
      break;
    case FloquetMethod::monodromy_rkf45: {
      // RKF45's global error over a period's many oscillations is ~1e3 rtol (measured on the paper
      // blade: 600 rtol in the multipliers, 1300 rtol in det Φ): the loose run at tol·1e-3 meets tol,
      // and the distance to the tight one, 100 times finer, is its error estimate.
      const Eigen::MatrixXd tight = rkf45_monodromy(sys, tol * 1e-5), loose = rkf45_monodromy(sys, tol * 1e-3);
      if (!all_finite(tight) || !all_finite(loose)) throw NumericalError("the RKF45 monodromy overflowed");
      const Eigen::VectorXcd rho = eigenvalues_of(tight);
      attempt = {rho, multiplier_set_distance(rho, eigenvalues_of(loose)), 0, 0, tight};
      checks = check_monodromy(tight, rho, sys, tol, options.independent_check, series_variation(sys));
      break;
    }
  }
  counter.finished();
  return result_of(options.method == FloquetMethod::automatic ? FloquetMethod::monodromy : options.method, attempt,
                   checks, sys.period());
}

namespace {

// The pulse train for the independent check: RKF45 through the contact, and the free flight after it
// by the unloaded blade's eigenvectors, e^{A τ} = V e^{Λτ} V⁻¹ (not the Padé exponential that
// exact_pulse_monodromy takes). Where V is ill-conditioned (near-defective modes), RKF45 integrates
// the whole period. The impulse is a jump in the monodromy and a short rectangle here: RKF45 too.
LoadVariation pulse_variation(const PeriodicSystem& sys, const PulseTrain& train) {
  LoadVariation load{pulse_load_variation(sys, train), train.edges(0, sys.period()), 0, {}};
  if (train.profile == PulseProfile::impulse || !(train.contact_time_s < sys.period())) return load;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(free_state_matrix(sys), true);
  if (eig.info() != Eigen::Success) return load;
  const Eigen::MatrixXcd V = eig.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(V);
  if (!(lu.rcond() > 1e-8)) return load;
  const Eigen::VectorXcd growth = (eig.eigenvalues() * (sys.period() - train.contact_time_s)).array().exp();
  load.varies_until = train.contact_time_s;
  load.rest = [V, lu, growth](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
    return (V * (growth.asDiagonal() * lu.solve(X.cast<cplx>()))).real();
  };
  return load;
}

}  // namespace

FloquetResult pulse_train_multipliers(const PeriodicSystem& sys, const PulseTrain& train, const FloquetOptions& options) {
  const PulseMonodromy p = exact_pulse_monodromy(sys, train, options.tolerance, options.progress);
  const Attempt attempt{p.multipliers, p.error_estimate, 0, p.steps, p.monodromy};
  const LoadVariation load = options.independent_check ? pulse_variation(sys, train) : LoadVariation{};
  return result_of(FloquetMethod::monodromy, attempt,
                   check_monodromy(p.monodromy, p.multipliers, sys, options.tolerance, options.independent_check, load),
                   sys.period());
}

}  // namespace bladestab
