#include "bladestab/modes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bladestab {
namespace {

constexpr double two_pi = 6.28318530717958647692;

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

Mode describe(const BladeModel& model, std::complex<double> lambda, Eigen::VectorXcd q) {
  Mode mode;
  mode.eigenvalue = lambda;
  mode.frequency_hz = std::abs(lambda.imag()) / two_pi;
  mode.lambda = model.blade.lambda_from_omega(std::abs(lambda.imag()));
  mode.damping_ratio = std::abs(lambda) > 0 ? -lambda.real() / std::abs(lambda) : 0;
  const double norm2 = (q.adjoint() * model.M * q)(0).real();
  q /= std::sqrt(norm2);
  // Make the largest entry real positive, so shapes print the same on every run.
  Eigen::Index big = 0;
  q.cwiseAbs().maxCoeff(&big);
  q *= std::polar(1.0, -std::arg(q(big)));
  const DofLayout& l = model.layout;
  const int offsets[3] = {l.theta_offset(), l.lateral_offset(), l.axial_offset()};
  const int counts[3] = {l.theta_count, l.lateral_count, l.axial_count};
  for (int f = 0; f < 3; ++f) {
    const auto qf = q.segment(offsets[f], counts[f]);
    mode.energy_share(f) =
        counts[f] ? (qf.adjoint() * model.M.block(offsets[f], offsets[f], counts[f], counts[f]) * qf)(0).real() : 0;
  }
  Eigen::Index family = 0;
  mode.energy_share.maxCoeff(&family);
  mode.family = family == 0 ? ModeFamily::rotation : family == 1 ? ModeFamily::bending : ModeFamily::axial;
  mode.shape = std::move(q);
  return mode;
}

}  // namespace

const char* to_string(ModeFamily f) {
  switch (f) {
    case ModeFamily::bending: return "bending";
    case ModeFamily::axial: return "axial";
    case ModeFamily::rotation: return "rotation";
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
  if (is_skew(sys.C) && stiffness.info() == Eigen::Success) {
    // Conservative gyroscopic system: with K̃ = R Rᵀ and y = [Rᵀp; ṗ], ẏ = S y with S real skew,
    // so −iS is Hermitian and its eigenvalues ω are the exact frequencies.
    const Eigen::MatrixXd R = stiffness.matrixL();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    S.topRightCorner(n, n) = R.transpose();
    S.bottomLeftCorner(n, n) = -R;
    S.bottomRightCorner(n, n) = -0.5 * (Ct - Ct.transpose());
    const Eigen::MatrixXcd H = std::complex<double>(0, -1) * S.cast<std::complex<double>>();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eig(H);
    Eigenpairs out{Eigen::VectorXcd(n), Eigen::MatrixXcd(n, n)};
    for (Eigen::Index k = 0; k < n; ++k) {  // eigenvalues ascend: the last n are the positive ω
      const double omega = eig.eigenvalues()(n + k);
      out.values(k) = std::complex<double>(0, omega);
      // ṗ = iω p  ⇒  p = y₂ / (iω)
      const Eigen::VectorXcd p = eig.eigenvectors().col(n + k).tail(n) / std::complex<double>(0, omega);
      out.vectors.col(k) = to_dofs(mass, p);
    }
    return out;
  }

  // General case: first-order form ż = [[0, I], [−K̃, −C̃]] z.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -Kt;
  A.bottomRightCorner(n, n) = -Ct;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(A);
  if (eig.info() != Eigen::Success) throw std::runtime_error("eigenvalue iteration did not converge");
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < 2 * n; ++k) {
    if (eig.eigenvalues()(k).imag() >= 0) keep.push_back(k);
  }
  Eigenpairs out{Eigen::VectorXcd(keep.size()), Eigen::MatrixXcd(n, keep.size())};
  for (std::size_t j = 0; j < keep.size(); ++j) {
    out.values(j) = eig.eigenvalues()(keep[j]);
    out.vectors.col(j) = to_dofs(mass, eig.eigenvectors().col(keep[j]).head(n));
  }
  return out;
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
  std::sort(solution.modes.begin(), solution.modes.end(), [](const Mode& a, const Mode& b) {
    return a.frequency_hz != b.frequency_hz ? a.frequency_hz < b.frequency_hz
                                            : a.eigenvalue.real() > b.eigenvalue.real();
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
