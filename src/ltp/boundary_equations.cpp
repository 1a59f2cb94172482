#include "bladestab/ltp/boundary_equations.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <lapacke.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/ltp/magnus.hpp"
#include "bladestab/ltp/monodromy.hpp"
#include "bladestab/ltp/step_doubling.hpp"

namespace bladestab {
namespace {


using cplx = std::complex<double>;
constexpr double accept_imag = 1e-7;  // |Im| / |value| below which an eigenvalue counts as real

// The harmonic set S: multiplier −1 odd k, +1 even k (K-th approximation).
std::vector<int> harmonic_set(int multiplier, int K) {
  std::vector<int> S;
  if (multiplier < 0) {
    for (int k = -(2 * K - 1); k <= 2 * K - 1; k += 2) S.push_back(k);
  } else {
    for (int k = -2 * K; k <= 2 * K; k += 2) S.push_back(k);
  }
  return S;
}

// Q(θ, scale) = K₀ + scale·K₁ + θ C₁ + θ² M₁ over the harmonics k ∈ S, each a Kronecker product
// of an H × H matrix over the harmonics with an n × n modal one:
//   K₀ = I ⊗ Λ,  K₁ = F ⊗ Ĝ (F_ab = F_m, 2m = k_a − k_b),  C₁ = diag(i k/2) ⊗ Ĉ,  M₁ = diag(−(k/2)²) ⊗ I,
// in real form: a real solution has c_{−k} = conj c_k, and with c_{±k} = (a_k ∓ i b_k)/√2 (a, b real)
// each harmonic matrix X, for which X_{−k,−l} = conj X_{k,l}, becomes the real matrix TᴴXT (T
// unitary). The real eigenvalues are the boundaries, at about a quarter of the cost of the complex
// eigenproblem of the same size.
struct Pencil {
  Eigen::MatrixXd K0, K1, C1, M1;
  Eigen::MatrixXcd T;  // H × H: the harmonics c_k of a real solution x = (a, b) are (T ⊗ I) x
  std::vector<int> harmonics;
  int n = 0;
};

// T for the harmonic set S (sorted, symmetric about 0): the column of slot k > 0 holds a_k, that of
// slot −k holds b_k, and slot 0 (the +1 sign's constant term) is real already.
Eigen::MatrixXcd real_form(const std::vector<int>& harmonics) {
  const int H = static_cast<int>(harmonics.size());
  const double r = std::sqrt(0.5);
  Eigen::MatrixXcd T = Eigen::MatrixXcd::Zero(H, H);
  for (int a = 0; a < H; ++a) {
    const int k = harmonics[a], mirror = H - 1 - a;  // harmonics[mirror] = −k
    if (k == 0) {
      T(a, a) = 1;
    } else if (k > 0) {  // column a_k: c_k and c_{−k} both get a_k/√2
      T(a, a) = T(mirror, a) = r;
    } else {  // column b_|k| (slot a holds −|k|): c_{|k|} gets −i b/√2, c_{−|k|} gets +i b/√2
      T(mirror, a) = cplx(0, -r);
      T(a, a) = cplx(0, r);
    }
  }
  return T;
}

// Re(TᴴXT) ⊗ base. TᴴXT is real for the balance's harmonic matrices; an imaginary part above
// rounding would mean the conjugate symmetry is broken, and the real eigenproblem would not be
// the boundaries'.
Eigen::MatrixXd real_kron(const Eigen::MatrixXcd& T, const Eigen::MatrixXcd& X, const Eigen::MatrixXd& base) {
  const Eigen::MatrixXcd R = T.adjoint() * X * T;
  if (R.imag().cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, R.cwiseAbs().maxCoeff())) {
    throw std::logic_error("boundary equations: the harmonic balance is not conjugate-symmetric");
  }
  const Eigen::Index H = R.rows(), n = base.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(H * n, H * n);
  for (Eigen::Index b = 0; b < H; ++b) {
    for (Eigen::Index a = 0; a < H; ++a) {
      if (R(a, b).real() != 0) out.block(a * n, b * n, n, n) = R(a, b).real() * base;
    }
  }
  return out;
}

// Eigenvalues and right eigenvectors of a general real matrix, by LAPACK's dgeev: 1.2× faster than
// Eigen's EigenSolver at 216 unknowns and 3.3× at 450 (measured single-threaded), the sizes of
// the real boundary equations with 9 modes and 12 harmonics (in F_max, and in θ linearized).
struct RealMatrixEigenpairs {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;
};

RealMatrixEigenpairs real_eigenpairs(Eigen::MatrixXd a) {
  // dgeev on NaN or infinity may not return at all (the fuzzer found crashes and hangs there).
  if (!a.allFinite()) {
    throw NumericalError("the boundary equations are not finite: the scene's load, speed or pulse frequency put "
                         "them beyond the double range (load.fmax_over_fcr, operation.speed_rad_s, the pulse frequency θ)");
  }
  const lapack_int n = static_cast<lapack_int>(a.rows());
  Eigen::VectorXd re(n), im(n);
  Eigen::MatrixXd v(n, n);
  const lapack_int info =
      LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', n, a.data(), n, re.data(), im.data(), nullptr, 1, v.data(), n);
  if (info != 0) throw std::runtime_error(fmt::format("boundary eigenproblem did not converge (dgeev info {})", info));
  RealMatrixEigenpairs e{Eigen::VectorXcd(n), Eigen::MatrixXcd(n, n)};
  for (lapack_int j = 0; j < n; ++j) {
    e.values(j) = cplx(re(j), im(j));
    if (im(j) == 0) {
      e.vectors.col(j) = v.col(j).cast<cplx>();
    } else {  // a conjugate pair: columns j, j + 1 hold the real and imaginary parts
      e.vectors.col(j) = v.col(j).cast<cplx>() + cplx(0, 1) * v.col(j + 1).cast<cplx>();
      e.vectors.col(j + 1) = e.vectors.col(j).conjugate();
      e.values(j + 1) = cplx(re(j + 1), im(j + 1));
      ++j;
    }
  }
  return e;
}

Pencil harmonic_balance(const LinearPeriodicSystem& sys, int multiplier, int K) {
  Pencil p;
  p.harmonics = harmonic_set(multiplier, K);
  p.n = static_cast<int>(sys.modal->stiffness.size());
  const int n = p.n, H = static_cast<int>(p.harmonics.size());
  const int M = static_cast<int>(sys.coefficients.size()) - 1;
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(H, H), C = F, M1 = F;
  for (int a = 0; a < H; ++a) {
    const int k = p.harmonics[a];
    C(a, a) = cplx(0, k / 2.0);
    M1(a, a) = -(k / 2.0) * (k / 2.0);
    for (int b = 0; b < H; ++b) {
      const int m = (k - p.harmonics[b]) / 2;  // c_{k−2m} couples through F_m
      if (std::abs(m) <= M) F(a, b) = m >= 0 ? sys.coefficients[m] : std::conj(sys.coefficients[-m]);
    }
  }
  p.T = real_form(p.harmonics);
  const Eigen::MatrixXd Lambda = sys.modal->stiffness.asDiagonal();
  p.K0 = real_kron(p.T, Eigen::MatrixXcd::Identity(H, H), Lambda);
  p.K1 = real_kron(p.T, F, sys.modal->G);
  p.C1 = real_kron(p.T, C, sys.modal->C);
  p.M1 = real_kron(p.T, M1, Eigen::MatrixXd::Identity(n, n));
  return p;
}

// Dominant (harmonic, mode) of an eigenvector x of the real form: the mode index and the order
// |k|. Returns false when, beyond the first approximation, it peaks in the highest harmonic kept: such a root is an
// artefact of the truncation (it moves when harmonics are added) and is dropped.
bool classify(const Pencil& p, const Eigen::VectorXcd& x, int approximation, Boundary& b) {
  // c_k for every harmonic slot: column k of the n × H matrix of x's blocks times Tᵀ.
  const Eigen::MatrixXcd c = Eigen::Map<const Eigen::MatrixXcd>(x.data(), p.n, p.T.rows()) * p.T.transpose();
  Eigen::Index mode = 0, slot = 0;
  c.cwiseAbs().maxCoeff(&mode, &slot);
  b.mode = static_cast<int>(mode) + 1;
  b.order = std::abs(p.harmonics[slot]);
  return approximation == 1 || b.order < p.harmonics.back();
}

void add_boundaries_of_sign(const LinearPeriodicSystem& sys, int multiplier, int approximation, double scale, std::vector<Boundary>& out) {
  const Pencil p = harmonic_balance(sys, multiplier, approximation);
  const Eigen::Index N = p.K0.rows();
  // (K + θC + θ²M)c = 0 with μ = 1/θ: (μ²K + μC + M)c = 0, linearized with K invertible; μ = 0
  // belongs to the harmonic k = 0, which has no inertia (θ = ∞).
  const Eigen::MatrixXd K = p.K0 + scale * p.K1;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(2 * N, 2 * N);
  L.topRightCorner(N, N).setIdentity();
  L.bottomLeftCorner(N, N) = -lu.solve(p.M1);
  L.bottomRightCorner(N, N) = -lu.solve(p.C1);
  const RealMatrixEigenpairs eig = real_eigenpairs(std::move(L));
  for (Eigen::Index j = 0; j < 2 * N; ++j) {
    const cplx mu = eig.values(j);
    if (std::abs(mu) < 1e-14 || mu.real() <= 0 || std::abs(mu.imag()) > accept_imag * std::abs(mu)) continue;
    Boundary b;
    b.theta_rad_s = 1 / mu.real();
    b.peak_force_n = scale;
    b.multiplier = multiplier;
    if (classify(p, eig.vectors.col(j).head(N), approximation, b)) out.push_back(b);
  }
}

// The multipliers asked for: both for `sign` 0, else the one given.
std::vector<int> multiplier_signs(int sign) {
  if (sign != 0 && sign != -1 && sign != 1) {
    throw std::invalid_argument(fmt::format("boundary multiplier sign {}: -1 or +1 (0 for both)", sign));
  }
  return sign == 0 ? std::vector<int>{-1, 1} : std::vector<int>{sign};
}

}  // namespace

MultiplierGap multiplier_gap(const LinearPeriodicSystem& system, double system_peak_force_n, const Boundary& b,
                             double tolerance, double max_flops) {
  // The coefficient scaled to b's amplitude (A₀ moves by Δf₀ B) at b's frequency; a system without
  // load (F̄ = 0, its boundaries the tongues' tips θ = 2ω/n) is taken as it is.
  LinearPeriodicSystem at = system.scaled(system_peak_force_n > 0 ? b.peak_force_n / system_peak_force_n : 1);
  at.angular_frequency = b.theta_rad_s;
  // Φ(T) by Magnus steps doubled from a quarter of the count where h‖A‖ ≤ 2 until StepDoubling
  // accepts Φ entry-wise within `tolerance` relative to its largest entry. (The multipliers
  // themselves would not settle: at a boundary two of them meet in a Jordan pair, where a change
  // δ in Φ moves them by √δ.) The whole period is stepped (magnus_monodromy).
  const auto monodromy = [&at](int steps) { return magnus_monodromy(at, steps, true); };
  const int safe = minimum_magnus_steps(at), first = std::max(8, safe / 4);
  const double step_work = magnus_step_work(at.state_size());
  StepDoubling ladder(first, max_magnus_steps, safe, step_work, max_flops);
  MultiplierGap result;
  if (ladder.levels() < 2) return result;
  Eigen::MatrixXd previous = monodromy(first);
  for (int steps = 2 * first; steps <= ladder.last(); steps *= 2) {
    Eigen::MatrixXd phi = monodromy(steps);
    result.work = (2.0 * steps - first) * step_work;
    if (!phi.allFinite()) return result;
    const double distance = (phi - previous).cwiseAbs().maxCoeff();
    if (ladder.judge(steps, distance, tolerance * phi.cwiseAbs().maxCoeff())) {
      const Eigen::VectorXcd rho = sorted_eigenvalues(phi);
      result.gap = (rho.array() - std::complex<double>(b.multiplier, 0)).abs().minCoeff();
      return result;
    }
    previous = std::move(phi);
  }
  return result;
}

std::vector<Boundary> boundary_frequencies(const LinearPeriodicSystem& sys, double peak_force_n, int approximation,
                                           int multiplier_sign) {
  // The system's load is already at peak_force_n; K1 carries it, so scale 1.
  std::vector<Boundary> out;
  for (int multiplier : multiplier_signs(multiplier_sign)) add_boundaries_of_sign(sys, multiplier, approximation, 1.0, out);
  for (Boundary& b : out) b.peak_force_n = peak_force_n;
  std::sort(out.begin(), out.end(), [](const Boundary& a, const Boundary& b) { return a.theta_rad_s < b.theta_rad_s; });
  return out;
}

std::vector<Boundary> boundary_loads(const LinearPeriodicSystem& sys, double system_peak_force_n, double theta,
                                     int approximation, int multiplier_sign) {
  std::vector<Boundary> out;
  for (int multiplier : multiplier_signs(multiplier_sign)) {
    const Pencil p = harmonic_balance(sys, multiplier, approximation);
    // (A + s K₁) c = 0 with A = K₀ + θC₁ + θ²M₁ and s = F_max / system_peak_force_n: A⁻¹K₁ c = −(1/s) c.
    const Eigen::MatrixXd A = p.K0 + theta * p.C1 + theta * theta * p.M1;
    const RealMatrixEigenpairs eig = real_eigenpairs(A.partialPivLu().solve(p.K1));
    for (Eigen::Index j = 0; j < eig.values.size(); ++j) {
      const cplx nu = eig.values(j);
      if (std::abs(nu) < 1e-300 || std::abs(nu.imag()) > accept_imag * std::abs(nu) || nu.real() >= 0) continue;
      Boundary b;
      b.theta_rad_s = theta;
      b.peak_force_n = -system_peak_force_n / nu.real();
      b.multiplier = multiplier;
      if (classify(p, eig.vectors.col(j), approximation, b)) out.push_back(b);
    }
  }
  std::sort(out.begin(), out.end(), [](const Boundary& a, const Boundary& b) { return a.peak_force_n < b.peak_force_n; });
  return out;
}

}  // namespace bladestab
