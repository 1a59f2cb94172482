#include "bladestab/floquet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "bladestab/magnus.hpp"
#include "bladestab/rkf45.hpp"

namespace bladestab {
namespace {

using cplx = std::complex<double>;

double max_abs(const Eigen::VectorXcd& rho) { return rho.cwiseAbs().maxCoeff(); }

Eigen::VectorXcd sorted_by_magnitude(Eigen::VectorXcd rho) {
  std::sort(rho.data(), rho.data() + rho.size(), [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  return rho;
}

// The Hill matrix in the real sin/cos basis: with x = Σ c_k e^{ikθt}, a_k = c_k + c_{−k} and
// b_k = i (c_k − c_{−k}) are the cosine and sine amplitudes; H_r = P H P⁻¹ is real.
Eigen::MatrixXd real_hill_matrix(const PeriodicSystem& sys, int q) {
  const int n = sys.state_size(), N = n * (2 * q + 1);
  const Eigen::MatrixXcd H = hill_matrix(sys, q);
  Eigen::MatrixXcd P = Eigen::MatrixXcd::Zero(N, N), Pinv = Eigen::MatrixXcd::Zero(N, N);
  const auto I = Eigen::MatrixXcd::Identity(n, n);
  const cplx i(0, 1);
  P.block(0, q * n, n, n) = I;  // constant term first
  Pinv.block(q * n, 0, n, n) = I;
  for (int k = 1; k <= q; ++k) {
    const int cos_row = (2 * k - 1) * n, sin_row = 2 * k * n, plus = (q + k) * n, minus = (q - k) * n;
    P.block(cos_row, plus, n, n) = I;
    P.block(cos_row, minus, n, n) = I;
    P.block(sin_row, plus, n, n) = i * I;
    P.block(sin_row, minus, n, n) = -i * I;
    Pinv.block(plus, cos_row, n, n) = 0.5 * I;
    Pinv.block(plus, sin_row, n, n) = -0.5 * i * I;
    Pinv.block(minus, cos_row, n, n) = 0.5 * I;
    Pinv.block(minus, sin_row, n, n) = 0.5 * i * I;
  }
  return (P * H * Pinv).real();
}

// ln ρ / T, and (46) δ = −2π Re λ / |Im λ|.
std::optional<double> log_decrement(cplx rho, double T) {
  const cplx lambda = std::log(rho) / T;
  if (lambda.imag() == 0) return std::nullopt;
  return -2 * 3.14159265358979323846 * lambda.real() / std::abs(lambda.imag());
}

struct Attempt {
  Eigen::VectorXcd multipliers;
  double error = 0;
  int harmonics = 0, steps = 0;
};

// Raises q by 2 from `start` until two successive truncations agree within tol, the Hill
// matrix would exceed `max_size`, or q passes `max_q`. Returns whether the tolerance was met.
template <class Method>
bool refine_harmonics(const PeriodicSystem& sys, Method method, int start, int max_q, int max_size, double tol,
                      Attempt& out) {
  Eigen::VectorXcd previous = method(sys, std::max(start - 2, 1));
  for (int q = start; q <= max_q && sys.state_size() * (2 * q + 1) <= max_size; q += 2) {
    const Eigen::VectorXcd current = method(sys, q);
    out = {current, std::abs(max_abs(current) - max_abs(previous)), q, 0};
    if (out.error <= tol * std::max(1.0, max_abs(current))) return true;
    previous = current;
  }
  return false;
}

// Doubles the Magnus steps until two successive counts agree within tol. Too few steps for the
// stiff modes overflow (the Magnus series diverges); such results never count as agreement.
Attempt refine_steps(const PeriodicSystem& sys, int start, double tol) {
  constexpr int max_steps = 1 << 16;
  Eigen::VectorXcd previous = monodromy_multipliers(sys, start);
  for (int steps = 2 * start; steps <= max_steps; steps *= 2) {
    const Eigen::VectorXcd current = monodromy_multipliers(sys, steps);
    const double error = std::abs(max_abs(current) - max_abs(previous));
    if (std::isfinite(error) && error <= tol * std::max(1.0, max_abs(current))) return {current, error, 0, steps};
    previous = current;
  }
  throw std::runtime_error(fmt::format("the monodromy matrix did not converge to {:g} within {} steps", tol, max_steps));
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

Eigen::MatrixXcd hill_matrix(const PeriodicSystem& sys, int q) {
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
  // Φ(T) ≈ C e^{HT} W: only the central block column of e^{HT} is needed, from H = V Λ V⁻¹ as
  // V e^{ΛT} (V⁻¹ W); C sums the block rows.
  const int n = sys.state_size(), N = n * (2 * q + 1);
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(hill_matrix(sys, q));
  if (eig.info() != Eigen::Success) throw std::runtime_error("Hill eigenvalues did not converge");
  Eigen::MatrixXcd W = Eigen::MatrixXcd::Zero(N, n);
  W.block(q * n, 0, n, n).setIdentity();
  Eigen::MatrixXcd Y = eig.eigenvectors().partialPivLu().solve(W);
  for (int i = 0; i < N; ++i) Y.row(i) *= std::exp(eig.eigenvalues()(i) * sys.period());
  const Eigen::MatrixXcd E = eig.eigenvectors() * Y;
  Eigen::MatrixXcd Phi = Eigen::MatrixXcd::Zero(n, n);
  for (int j = 0; j <= 2 * q; ++j) Phi += E.block(j * n, 0, n, n);
  return sorted_by_magnitude(Eigen::ComplexEigenSolver<Eigen::MatrixXcd>(Phi, false).eigenvalues());
}

Eigen::MatrixXd magnus_monodromy(const PeriodicSystem& sys, int steps) {
  return magnus_propagator([&sys](double t) { return sys.A(t); }, sys.state_size(), 0, sys.period(), steps);
}

Eigen::VectorXcd monodromy_multipliers(const PeriodicSystem& sys, int steps) {
  return sorted_by_magnitude(Eigen::EigenSolver<Eigen::MatrixXd>(magnus_monodromy(sys, steps), false).eigenvalues());
}

Eigen::MatrixXd rkf45_monodromy(const PeriodicSystem& sys, double rtol) {
  const int n = sys.state_size();
  // The n fundamental solutions as one vector: Ẋ = A(t) X, X(0) = I.
  const OdeFunction rhs = [&sys, n](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    dx.resize(x.size());
    Eigen::Map<Eigen::MatrixXd>(dx.data(), n, n).noalias() = sys.A(t) * Eigen::Map<const Eigen::MatrixXd>(x.data(), n, n);
  };
  Eigen::VectorXd x = Eigen::MatrixXd::Identity(n, n).reshaped();
  StepControl control;
  control.rtol = rtol;
  control.atol = rtol;  // the scaled coordinates make every entry of Φ order one
  rkf45_integrate(rhs, x, 0, sys.period(), control, {}, {}, [](double, const Eigen::VectorXd&) {});
  return x.reshaped(n, n);
}

FloquetResult floquet_multipliers(const PeriodicSystem& sys, const FloquetOptions& options) {
  const double tol = options.tolerance;
  const int q = options.harmonics;
  constexpr int max_q = 40, unlimited = 1 << 30;
  // Few Magnus steps suffice for the slowly varying load even when stiff modes are present; the
  // load's highest harmonic sets the minimum.
  const int first_steps = std::max(64, 8 * static_cast<int>(sys.load.size()));
  Attempt attempt;
  FloquetMethod used = options.method;
  switch (options.method) {
    case FloquetMethod::hill:
    case FloquetMethod::koopman_hill: {
      const auto method = options.method == FloquetMethod::hill ? hill_multipliers : koopman_hill_multipliers;
      if (q > 0) {
        const Eigen::VectorXcd current = method(sys, q), coarser = method(sys, std::max(1, q - 2));
        attempt = {current, q > 1 ? std::abs(max_abs(current) - max_abs(coarser)) : max_abs(current), q, 0};
      } else {
        refine_harmonics(sys, method, 2, max_q, unlimited, tol, attempt);
      }
      break;
    }
    case FloquetMethod::monodromy:
      attempt = refine_steps(sys, first_steps, tol);
      break;
    case FloquetMethod::monodromy_rkf45: {
      const auto rho = [&sys](double rtol) {
        return sorted_by_magnitude(Eigen::EigenSolver<Eigen::MatrixXd>(rkf45_monodromy(sys, rtol), false).eigenvalues());
      };
      const Eigen::VectorXcd tight = rho(tol * 1e-2), loose = rho(tol);
      attempt = {tight, std::abs(max_abs(tight) - max_abs(loose)), 0, 0};
      break;
    }
    case FloquetMethod::automatic:
      // Koopman–Hill while its matrix is small (a dense eigensolve of n(2q+1)); else monodromy.
      used = FloquetMethod::koopman_hill;
      if (!refine_harmonics(sys, koopman_hill_multipliers, 2, max_q, 480, tol, attempt)) {
        used = FloquetMethod::monodromy;
        attempt = refine_steps(sys, first_steps, tol);
      }
      break;
  }
  FloquetResult result;
  result.method = used;
  result.harmonics = attempt.harmonics;
  result.steps = attempt.steps;
  result.multipliers = attempt.multipliers;
  result.error_estimate = attempt.error;
  result.max_abs_multiplier = max_abs(attempt.multipliers);
  result.max_real_exponent = std::log(result.max_abs_multiplier) / sys.period();
  result.stable = result.max_abs_multiplier <= 1 + std::max(attempt.error, 1e-9);
  for (Eigen::Index k = 0; k < attempt.multipliers.size(); ++k) {
    result.log_decrements.push_back(log_decrement(attempt.multipliers(k), sys.period()));
  }
  return result;
}

}  // namespace bladestab
