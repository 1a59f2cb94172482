#include "bladestab/modal/modes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <lapacke.h>

#include "bladestab/base/constants.hpp"

namespace bladestab {
namespace {

bool is_skew(const Eigen::MatrixXd& C) { return (C + C.transpose()).cwiseAbs().maxCoeff() == 0; }

// L⁻¹ X L⁻ᵀ for the Cholesky factor L of M.
Eigen::MatrixXd congruence(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& X) {
  const auto L = llt.matrixL();
  const Eigen::MatrixXd left = L.solve(X);
  return L.solve(left.transpose()).transpose();
}

// q = L⁻ᵀ p, for complex p.
Eigen::VectorXcd to_dofs(const Eigen::LLT<Eigen::MatrixXd>& mass, const Eigen::VectorXcd& p) {
  const auto Lt = mass.matrixU();
  const Eigen::VectorXd re = Lt.solve(p.real()), im = Lt.solve(p.imag());
  Eigen::VectorXcd q(p.size());
  q.real() = re;
  q.imag() = im;
  return q;
}

// Eigenpairs with Im λ ≥ 0 (one of each conjugate pair; real eigenvalues all), lifted to dofs.
// `rows` holds p, or ṗ when `rows_are_velocity` (then p = ṗ/λ).
Eigenpairs upper_half_plane(const Eigen::VectorXcd& values, const Eigen::MatrixXcd& rows,
                            const Eigen::LLT<Eigen::MatrixXd>& mass, bool rows_are_velocity) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    const bool real = std::abs(values(k).imag()) <= 1e-12 * std::abs(values(k));
    if (values(k).imag() > 0 || real) keep.push_back(k);
  }
  Eigenpairs out{Eigen::VectorXcd(keep.size()), Eigen::MatrixXcd(rows.rows(), keep.size())};
  for (std::size_t j = 0; j < keep.size(); ++j) {
    std::complex<double> lambda = values(keep[j]);
    if (std::abs(lambda.imag()) <= 1e-12 * std::abs(lambda)) lambda.imag(0);
    out.values(j) = lambda;
    const Eigen::VectorXcd p = rows_are_velocity && lambda != 0.0 ? Eigen::VectorXcd(rows.col(keep[j]) / lambda)
                                                                   : Eigen::VectorXcd(rows.col(keep[j]));
    out.vectors.col(j) = to_dofs(mass, p);
  }
  return out;
}

// The upper half of the eigenpairs of a Hermitian matrix H of even order 2n, ascending — for
// H = −iS, the n positive frequencies ω: LAPACK's MRRR driver zheevr for that subset. The QR
// iteration that Eigen's SelfAdjointEigenSolver calls (zheev) accumulates its rotations into all
// 2n complex vectors, two thirds of a parameter sweep's time (measured with perf); both are
// backward stable, with absolute eigenvalue errors of order ε‖H‖.
void upper_half_eigenpairs(Eigen::MatrixXcd H, Eigen::VectorXd& values, Eigen::MatrixXcd& vectors) {
  const lapack_int order = static_cast<lapack_int>(H.rows()), n = order / 2;
  values.resize(order);
  vectors.resize(order, n);
  std::vector<lapack_int> support(2 * static_cast<std::size_t>(n));
  lapack_int found = 0;
  const lapack_int info =
      LAPACKE_zheevr(LAPACK_COL_MAJOR, 'V', 'I', 'L', order, H.data(), order, 0, 0, n + 1, order,
                     LAPACKE_dlamch('S'), &found, values.data(), vectors.data(), order, support.data());
  if (info != 0 || found != n) throw std::runtime_error("Hermitian eigenvalue iteration did not converge");
  values.conservativeResize(n);
}

}  // namespace

ModeFamily dominant_family(const BladeModel& model, const Eigen::VectorXcd& q, std::vector<double>& shares) {
  shares.assign(model.families.size(), 0.0);
  std::size_t most = 0;
  for (std::size_t f = 0; f < model.families.size(); ++f) {
    const FieldFamily& family = model.families[f];
    if (family.count == 0) continue;
    const auto qf = q.segment(family.offset, family.count);
    shares[f] = (qf.adjoint() * family.mass * qf)(0).real();
    if (shares[f] > shares[most]) most = f;
  }
  return model.families[most].family;
}

namespace {

Mode describe(const BladeModel& model, std::complex<double> lambda, Eigen::VectorXcd q) {
  Mode mode;
  mode.eigenvalue = lambda;
  // A pair split off the real axis by rounding at critical damping (a double root moves by about
  // √(ε‖A‖|λ|): 32 terms under Rayleigh ζ = 0.25 gave "axial" roots at 0.0002 Hz, ζ = 1 − 1e-15)
  // does not oscillate: below 1e-4 of |λ|, a "period" over which it decays by e^(−6e4).
  const double omega = std::abs(lambda.imag()) > 1e-4 * std::abs(lambda) ? std::abs(lambda.imag()) : 0.0;
  mode.frequency_hz = omega / two_pi;
  mode.lambda = model.blade.lambda_from_omega(omega);
  mode.damping_ratio = std::abs(lambda) > 0 ? -lambda.real() / std::abs(lambda) : 0;
  const double norm2 = (q.adjoint() * model.M * q)(0).real();
  q /= std::sqrt(norm2);
  // Make the largest entry real positive, so shapes print the same on every run.
  Eigen::Index big = 0;
  q.cwiseAbs().maxCoeff(&big);
  q *= std::polar(1.0, -std::arg(q(big)));
  mode.family = dominant_family(model, q, mode.energy_share);
  mode.shape = std::move(q);
  return mode;
}

}  // namespace

const char* to_string(ModeFamily f) {
  switch (f) {
    case ModeFamily::bending: return "bending";
    case ModeFamily::axial: return "axial";
    case ModeFamily::rotation: return "rotation";
    case ModeFamily::flap: return "flap";
    case ModeFamily::edge: return "edge";
  }
  return "?";
}

const char* to_string(EigenSolverKind k) {
  switch (k) {
    case EigenSolverKind::automatic: return "auto";
    case EigenSolverKind::dense: return "dense";
    case EigenSolverKind::arpack: return "arpack";
  }
  return "?";
}

Eigenpairs dense_eigenpairs(const SecondOrderSystem& sys) {
  const Eigen::Index n = sys.M.rows();
  const Eigen::LLT<Eigen::MatrixXd> mass(sys.M);
  if (mass.info() != Eigen::Success) throw std::runtime_error("mass matrix is not positive definite");
  Eigen::MatrixXd Kt = congruence(mass, sys.K);
  Kt = 0.5 * (Kt + Kt.transpose());
  const Eigen::MatrixXd Ct = congruence(mass, sys.C);

  const Eigen::LLT<Eigen::MatrixXd> stiffness(Kt);
  if (stiffness.info() == Eigen::Success) {
    // K̃ = R Rᵀ > 0: with y = [Rᵀp; ṗ], ẏ = S y, S = [[0, Rᵀ], [−R, −C̃]]. Its entries scale like
    // the frequencies, not their squares, so the small eigenvalues keep their relative accuracy.
    const Eigen::MatrixXd R = stiffness.matrixL();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    S.topRightCorner(n, n) = R.transpose();
    S.bottomLeftCorner(n, n) = -R;
    S.bottomRightCorner(n, n) = -Ct;
    Eigenpairs out{Eigen::VectorXcd(n), Eigen::MatrixXcd(n, n)};
    if (is_skew(sys.C)) {
      // Conservative gyroscopic system: S is real skew, −iS Hermitian, its eigenvalues ω exact.
      S.bottomRightCorner(n, n) = -0.5 * (Ct - Ct.transpose());  // skew to the last bit
      Eigen::VectorXd omega;
      Eigen::MatrixXcd vectors;
      upper_half_eigenpairs(std::complex<double>(0, -1) * S.cast<std::complex<double>>(), omega, vectors);
      for (Eigen::Index k = 0; k < n; ++k) {
        out.values(k) = std::complex<double>(0, omega(k));
        out.vectors.col(k) = to_dofs(mass, vectors.col(k).tail(n) / out.values(k));  // p = ṗ/λ
      }
      return out;
    }
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(S.cast<std::complex<double>>());
    if (eig.info() != Eigen::Success) throw std::runtime_error("eigenvalue iteration did not converge");
    return upper_half_plane(eig.eigenvalues(), eig.eigenvectors().bottomRows(n), mass, true);
  }

  // K̃ indefinite (statically unstable): first-order form ż = [[0, I], [−K̃, −C̃]] z, z = [p; ṗ].
  Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -Kt.cast<std::complex<double>>();
  A.bottomRightCorner(n, n) = -Ct.cast<std::complex<double>>();
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(A);
  if (eig.info() != Eigen::Success) throw std::runtime_error("eigenvalue iteration did not converge");
  return upper_half_plane(eig.eigenvalues(), eig.eigenvectors().topRows(n), mass, false);
}

ModalSolution solve_modes(const BladeModel& model, const SecondOrderSystem& system, double speed, int count,
                          EigenSolverKind solver) {
  const int n = model.layout.size();
  if (count <= 0 || count > n) count = n;
  if (solver == EigenSolverKind::automatic) {
    solver = n >= arpack_threshold_dofs && count < n / 2 ? EigenSolverKind::arpack : EigenSolverKind::dense;
  }
  const Eigenpairs pairs =
      solver == EigenSolverKind::arpack ? arpack_eigenpairs(system, count) : dense_eigenpairs(system);

  ModalSolution solution;
  solution.speed_rad_s = speed;
  solution.solver = solver;
  for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
    solution.modes.push_back(describe(model, pairs.values(k), pairs.vectors.col(k)));
  }
  // By |λ| (the undamped natural frequency for proportional damping), so that overdamped pairs
  // stand where their stiffness puts them rather than first.
  std::sort(solution.modes.begin(), solution.modes.end(), [](const Mode& a, const Mode& b) {
    const double ra = std::abs(a.eigenvalue), rb = std::abs(b.eigenvalue);
    return ra != rb ? ra < rb : a.eigenvalue.real() > b.eigenvalue.real();
  });
  if (static_cast<int>(solution.modes.size()) > count) solution.modes.resize(count);
  for (std::size_t k = 0; k < solution.modes.size(); ++k) solution.modes[k].index = static_cast<int>(k) + 1;
  return solution;
}

double modal_assurance(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b, const Eigen::MatrixXd& M) {
  const std::complex<double> ab = (a.adjoint() * M * b)(0);
  const double aa = (a.adjoint() * M * a)(0).real(), bb = (b.adjoint() * M * b)(0).real();
  return std::norm(ab) / (aa * bb);
}

}  // namespace bladestab
