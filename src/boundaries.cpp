#include "bladestab/boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bladestab {
namespace {

using cplx = std::complex<double>;
constexpr double accept_imag = 1e-7;  // |Im| / |value| below which an eigenvalue counts as real

// The harmonic set S: −1 family odd k, +1 family even k (K-th approximation).
std::vector<int> harmonic_set(int multiplier, int K) {
  std::vector<int> S;
  if (multiplier < 0) {
    for (int k = -(2 * K - 1); k <= 2 * K - 1; k += 2) S.push_back(k);
  } else {
    for (int k = -2 * K; k <= 2 * K; k += 2) S.push_back(k);
  }
  return S;
}

// Q(θ, scale) = K₀ + scale·K₁ + θ C₁ + θ² M₁ with
//   K₀ = diag(Λ), K₁ = load coupling (F_m Ĝ, m = 0 on the diagonal), C₁ = diag(i k/2 Ĉ), M₁ = diag(−(k/2)² I).
struct Pencil {
  Eigen::MatrixXcd K0, K1, C1, M1;
  std::vector<int> harmonics;
  int n = 0;
};

Pencil harmonic_balance(const PeriodicSystem& sys, int multiplier, int K) {
  Pencil p;
  p.harmonics = harmonic_set(multiplier, K);
  p.n = static_cast<int>(sys.modal_frequencies.size());
  const int n = p.n, N = n * static_cast<int>(p.harmonics.size());
  p.K0 = p.K1 = p.C1 = p.M1 = Eigen::MatrixXcd::Zero(N, N);
  const int M = static_cast<int>(sys.load.size()) - 1;
  for (std::size_t a = 0; a < p.harmonics.size(); ++a) {
    const int k = p.harmonics[a];
    p.K0.block(a * n, a * n, n, n).diagonal() = sys.modal_frequencies.array().square().cast<cplx>();
    p.C1.block(a * n, a * n, n, n) = cplx(0, k / 2.0) * sys.modal_C.cast<cplx>();
    p.M1.block(a * n, a * n, n, n).diagonal().setConstant(-(k / 2.0) * (k / 2.0));
    for (std::size_t b = 0; b < p.harmonics.size(); ++b) {
      const int two_m = k - p.harmonics[b];  // c_{k−2m} couples through F_m
      const int m = two_m / 2;
      if (std::abs(m) > M) continue;
      const cplx F = m >= 0 ? sys.load[m] : std::conj(sys.load[-m]);
      p.K1.block(a * n, b * n, n, n) = F * sys.modal_G.cast<cplx>();
    }
  }
  return p;
}

// Dominant (harmonic, mode) of an eigenvector: the mode index and the order |k|. Returns false
// when, beyond the first approximation, it peaks in the highest harmonic kept: such a root is an
// artefact of the truncation (it moves when harmonics are added) and is dropped.
bool classify(const Pencil& p, const Eigen::VectorXcd& c, int approximation, Boundary& b) {
  Eigen::Index at = 0;
  c.cwiseAbs().maxCoeff(&at);
  b.mode = static_cast<int>(at % p.n) + 1;
  b.order = std::abs(p.harmonics[at / p.n]);
  return approximation == 1 || b.order < p.harmonics.back();
}

void add_family(const PeriodicSystem& sys, int multiplier, int approximation, double scale, std::vector<Boundary>& out) {
  const Pencil p = harmonic_balance(sys, multiplier, approximation);
  const Eigen::Index N = p.K0.rows();
  // (K + θC + θ²M)c = 0 with μ = 1/θ: (μ²K + μC + M)c = 0, linearized with K invertible; μ = 0
  // belongs to the harmonic k = 0, which has no inertia (θ = ∞).
  const Eigen::MatrixXcd K = p.K0 + scale * p.K1;
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(K);
  Eigen::MatrixXcd L = Eigen::MatrixXcd::Zero(2 * N, 2 * N);
  L.topRightCorner(N, N).setIdentity();
  L.bottomLeftCorner(N, N) = -lu.solve(p.M1);
  L.bottomRightCorner(N, N) = -lu.solve(p.C1);
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(L);
  if (eig.info() != Eigen::Success) throw std::runtime_error("boundary eigenproblem did not converge");
  for (Eigen::Index j = 0; j < 2 * N; ++j) {
    const cplx mu = eig.eigenvalues()(j);
    if (std::abs(mu) < 1e-14 || mu.real() <= 0 || std::abs(mu.imag()) > accept_imag * std::abs(mu)) continue;
    Boundary b;
    b.theta_rad_s = 1 / mu.real();
    b.peak_force_n = scale;
    b.multiplier = multiplier;
    if (classify(p, eig.eigenvectors().col(j).head(N), approximation, b)) out.push_back(b);
  }
}

}  // namespace

std::vector<Boundary> boundary_frequencies(const PeriodicSystem& sys, double peak_force_n, int approximation) {
  // The system's load is already at peak_force_n; K1 carries it, so scale 1.
  std::vector<Boundary> out;
  for (int multiplier : {-1, 1}) add_family(sys, multiplier, approximation, 1.0, out);
  for (Boundary& b : out) b.peak_force_n = peak_force_n;
  std::sort(out.begin(), out.end(), [](const Boundary& a, const Boundary& b) { return a.theta_rad_s < b.theta_rad_s; });
  return out;
}

std::vector<Boundary> boundary_loads(const PeriodicSystem& sys, double system_peak_force_n, double theta,
                                     int approximation) {
  std::vector<Boundary> out;
  for (int multiplier : {-1, 1}) {
    const Pencil p = harmonic_balance(sys, multiplier, approximation);
    // (A + s K₁) c = 0 with A = K₀ + θC₁ + θ²M₁ and s = F_max / system_peak_force_n: A⁻¹K₁ c = −(1/s) c.
    const Eigen::MatrixXcd A = p.K0 + theta * p.C1 + theta * theta * p.M1;
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(A.partialPivLu().solve(p.K1));
    if (eig.info() != Eigen::Success) throw std::runtime_error("boundary eigenproblem did not converge");
    for (Eigen::Index j = 0; j < eig.eigenvalues().size(); ++j) {
      const cplx nu = eig.eigenvalues()(j);
      if (std::abs(nu) < 1e-300 || std::abs(nu.imag()) > accept_imag * std::abs(nu) || nu.real() >= 0) continue;
      Boundary b;
      b.theta_rad_s = theta;
      b.peak_force_n = -system_peak_force_n / nu.real();
      b.multiplier = multiplier;
      if (classify(p, eig.eigenvectors().col(j), approximation, b)) out.push_back(b);
    }
  }
  std::sort(out.begin(), out.end(), [](const Boundary& a, const Boundary& b) { return a.peak_force_n < b.peak_force_n; });
  return out;
}

}  // namespace bladestab
