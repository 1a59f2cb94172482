// Tables 4 and 5 of Sinha (2005): the first ten non-axial frequency parameters Λ of the paper
// blade at d̄ = 0.005, 0.01, 0.05, 0.1, at rest and at 300 rad/s, with the paper's sine basis.
//
// Finding: the tables match the sine basis with N = 20 terms per field (not the N = 10 the paper
// states) — to 0.02 % for most entries, 0.45 % at worst — except for three misprints. With N = 10 the higher modes
// are 1–6 % stiffer than the printed values; those entries are named below. The N = 10 values
// themselves are checked against the paper's Ritz model assembled here in closed form.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bladestab/blade/damping.hpp"
#include "bladestab/modal/modes.hpp"
#include "reference/timoshenko_cantilever.hpp"
#include "support/scenes.hpp"

using namespace bladestab;

namespace {

struct Column {
  double slenderness;
  std::vector<double> lambda;  // modes 1..10 as printed
};

const std::vector<Column> table4 = {  // Ω = 0
    {0.005, {3.5160, 22.0971, 61.5388, 120.3240, 198.2305, 293.0804, 408.1056, 539.8896, 688.3948, 853.3561}},
    {0.01, {3.4809, 21.9210, 60.8399, 117.9210, 192.1182, 281.9967, 384.3208, 500.4664, 627.4645, 764.5730}},
    {0.05, {3.4395, 19.1603, 46.8837, 79.6116, 114.9608, 151.3109, 187.5246, 220.7516, 238.7207, 250.6780}},
    {0.1, {3.2308, 14.5756, 31.8319, 48.4153, 62.6941, 68.4167, 81.0305, 89.5881, 102.6107, 110.3643}},
};
const std::vector<Column> table5 = {  // Ω = 300 rad/s
    {0.005, {15.3513, 43.7037, 88.2832, 150.8615, 225.0000, 327.9073, 443.4582, 576.4866, 725.7231, 891.3798}},
    {0.01, {8.3177, 28.9632, 68.6869, 127.7992, 200.3793, 290.1916, 393.9380, 510.3367, 637.6240, 775.0315}},
    {0.05, {3.7538, 19.5034, 47.2828, 80.0909, 115.5232, 151.9531, 188.2302, 221.3706, 238.9201, 251.1273}},
    {0.1, {3.3121, 14.6773, 31.9717, 48.5743, 62.8019, 68.5391, 81.1678, 89.7942, 102.7375, 110.6600}},
};

// Paper values that are wrong (docs/theory.md §8 and misprints found here); excluded from both checks.
struct Misprint {
  int table;
  double slenderness;
  int mode;
  const char* why;
};
const std::vector<Misprint> misprints = {
    {4, 0.01, 1, "3.4809 is below the exact 3.51265, impossible for a Ritz upper bound (docs/theory.md §8)"},
    {5, 0.005, 5, "225.0000: every other entry has four decimals of a computed value; N = 10 and 20 give 231.27, 230.58"},
    {5, 0.01, 4, "127.7992 is above even the N = 10 value 126.47; converged 126.004 (docs/theory.md §7)"},
};

// N = 10 entries more than 1 % from the paper (measured deviation in the comments): the printed
// values are the N = 20 ones, the paper's N = 10 is stiffer. Each is checked to deviate by more
// than 0.99 % with the N = 10 value of the closed-form model below.
struct Exception {
  int table;
  double slenderness;
  int mode;
  double paper;
};
const std::vector<Exception> n10_exceptions = {
    {4, 0.005, 8, 539.8896},  // +1.33 %
    {4, 0.005, 9, 688.3948},  // +1.30 %
    {4, 0.005, 10, 853.3561}, // +5.91 %
    {4, 0.01, 8, 500.4664},   // +1.47 %
    {4, 0.01, 9, 627.4645},   // +1.45 %
    {4, 0.01, 10, 764.5730},  // +5.96 %
    {4, 0.05, 4, 79.6116},    // +1.00 %
    {4, 0.05, 5, 114.9608},   // +1.12 %
    {4, 0.05, 6, 151.3109},   // +1.46 %
    {4, 0.05, 7, 187.5246},   // +1.33 %
    {4, 0.05, 8, 220.7516},   // +1.20 %
    {4, 0.05, 10, 250.6780},  // +1.07 %
    {4, 0.1, 3, 31.8319},     // +1.03 %
    {4, 0.1, 4, 48.4153},     // +1.12 %
    {4, 0.1, 8, 89.5881},     // +1.26 %
    {4, 0.1, 10, 110.3643},   // +1.37 %
    {5, 0.005, 8, 576.4866},  // +1.37 %
    {5, 0.005, 9, 725.7231},  // +1.34 %
    {5, 0.005, 10, 891.3798}, // +4.42 %
    {5, 0.01, 8, 510.3367},   // +1.49 %
    {5, 0.01, 9, 637.6240},   // +1.46 %
    {5, 0.01, 10, 775.0315},  // +5.45 %
    {5, 0.05, 4, 80.0909},    // +1.00 %
    {5, 0.05, 5, 115.5232},   // +1.11 %
    {5, 0.05, 6, 151.9531},   // +1.45 %
    {5, 0.05, 7, 188.2302},   // +1.33 %
    {5, 0.05, 8, 221.3706},   // +1.17 %
    {5, 0.05, 10, 251.1273},  // +1.07 %
    {5, 0.1, 3, 31.9717},     // +1.03 %
    {5, 0.1, 4, 48.5743},     // +1.11 %
    {5, 0.1, 8, 89.7942},     // +1.25 %
    {5, 0.1, 10, 110.6600},   // +1.37 %
};

std::vector<double> non_axial_lambdas(double slenderness, double speed, int terms) {
  const Scene s = testing_support::paper_scene({"model.basis=sine", "model.terms=" + std::to_string(terms),
                                                "blade.slenderness=" + std::to_string(slenderness),
                                                "operation.speed_rad_s=" + std::to_string(speed)});
  const BladeModel m = assemble_model(s);
  const ModalSolution sol = solve_modes(m, system_at(m, speed, damping_matrix(m, s.damping, speed)), speed, 0,
                                        EigenSolverKind::dense);
  std::vector<double> out;
  for (const Mode& mode : sol.modes) {
    if (mode.family != ModeFamily::axial && out.size() < 10) out.push_back(mode.lambda);
  }
  return out;
}

// ∫₀ᴸ sᵏ cos(cs) ds, k = 0, 1, 2 (by parts).
double cosine_moment(int k, double c, double L) {
  if (c == 0) return std::pow(L, k + 1) / (k + 1);
  const double sn = std::sin(c * L), cs = std::cos(c * L);
  switch (k) {
    case 0: return sn / c;
    case 1: return L * sn / c + (cs - 1) / (c * c);
    default: return L * L * sn / c + 2 * L * cs / (c * c) - 2 * sn / (c * c * c);
  }
}
// ∫₀ᴸ sin(cs) ds.
double sine_integral(double c, double L) { return c == 0 ? 0 : (1 - std::cos(c * L)) / c; }

// The paper's own Ritz model, N terms of the basis (18a–c) per field, assembled in closed form
// from docs/theory.md §2 (independent of the library's basis, quadrature and eigensolver), and its first ten
// non-axial Λ. With λ_n = (2n − 1)π/(2L): sin λ_nL = (−1)^{n+1}, cos λ_nL = 0, and
//   ∫U_iU_j = ∫V_i'V_j' = ∫W_i'W_j' = ∫U_iV_j' = (L/2)δ_ij,  ∫U_i'U_j' = λ_i²(L/2)δ_ij,
//   ∫W_iW_j = (L/2)δ_ij/λ_i²,  ∫V_iV_j = [L − sin λ_iL/λ_i − sin λ_jL/λ_j + (L/2)δ_ij]/(λ_iλ_j),
//   ∫sᵏ V_i'V_j' = ½[C_k(λ_i − λ_j) − C_k(λ_i + λ_j)],  C_k(c) = ∫sᵏ cos cs,
//   ∫V_iW_j = [1/λ_j − ½(S(λ_j + λ_i) + S(λ_j − λ_i))]/(λ_iλ_j),  S(c) = ∫sin cs.
// Modes are axial when the u field has the largest share of their kinetic energy.
std::vector<double> closed_form_lambdas(double slenderness, double speed, int N) {
  constexpr double L = 1.0, r = 0.5, A = 22.39e-4, E = 117e9, rho = 4466.0, kappa = 0.833, pi = 3.14159265358979323846;
  const double I = slenderness * slenderness * A * L * L, kGA = kappa * E / (2 * (1 + 0.3)) * A;
  const double cos_beta = std::cos(-60 * pi / 180), W2 = speed * speed;
  Eigen::VectorXd lambda(N), sin_end(N);
  for (int n = 0; n < N; ++n) lambda(n) = (2 * n + 1) * pi / (2 * L), sin_end(n) = n % 2 == 0 ? 1 : -1;
  Eigen::MatrixXd VV(N, N), tension(N, N), VW(N, N);
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) {
      const double li = lambda(i), lj = lambda(j), diagonal = i == j ? L / 2 : 0;
      VV(i, j) = (L - sin_end(i) / li - sin_end(j) / lj + diagonal) / (li * lj);
      // T_cf/Ω² = ρA[(rL + L²/2) − r s − s²/2]  (docs/theory.md §1)
      const auto moment = [&](int k) { return 0.5 * (cosine_moment(k, li - lj, L) - cosine_moment(k, li + lj, L)); };
      tension(i, j) = rho * A * ((r * L + L * L / 2) * moment(0) - r * moment(1) - moment(2) / 2);
      VW(i, j) = (1 / lj - 0.5 * (sine_integral(lj + li, L) + sine_integral(lj - li, L))) / (li * lj);
    }
  }
  const Eigen::MatrixXd half = Eigen::MatrixXd::Identity(N, N) * (L / 2);
  const Eigen::MatrixXd WW = (L / 2) * lambda.cwiseInverse().cwiseAbs2().asDiagonal().toDenseMatrix();
  const int th = 0, lv = N, ax = 2 * N, n = 3 * N;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = M, C = M;
  M.block(th, th, N, N) = rho * I * half;
  M.block(lv, lv, N, N) = rho * A * VV;
  M.block(ax, ax, N, N) = rho * A * WW;
  K.block(th, th, N, N) = E * I * (L / 2) * lambda.cwiseAbs2().asDiagonal().toDenseMatrix() + (kGA - W2 * rho * I) * half;
  K.block(th, lv, N, N) = -kGA * half;
  K.block(lv, th, N, N) = -kGA * half;
  K.block(lv, lv, N, N) = kGA * half + W2 * tension - W2 * rho * A * cos_beta * cos_beta * VV;
  K.block(ax, ax, N, N) = E * A * half - W2 * rho * A * WW;
  C.block(lv, ax, N, N) = speed * 2 * rho * A * cos_beta * VW;
  C.block(ax, lv, N, N) = -C.block(lv, ax, N, N).transpose();
  // λ²M + λC + K = 0 with z = [q; λq]: diag(K, M) z = λ B z, B = [[−C, −M], [M, 0]] skew, so with
  // λ = iω the Hermitian-definite pencil (iB) z = (1/ω) diag(K, M) z (exact for the lowest modes,
  // which have the largest 1/ω).
  using Complex = std::complex<double>;
  Eigen::MatrixXcd iB = Eigen::MatrixXcd::Zero(2 * n, 2 * n), energy = iB;
  iB.topLeftCorner(n, n) = Complex(0, -1) * C;
  iB.topRightCorner(n, n) = Complex(0, -1) * M;
  iB.bottomLeftCorner(n, n) = Complex(0, 1) * M;
  energy.topLeftCorner(n, n) = K;
  energy.bottomRightCorner(n, n) = M;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> eig(iB, energy);
  std::vector<std::pair<double, bool>> modes;  // ω, axial
  for (int k = 0; k < 2 * n; ++k) {
    if (eig.eigenvalues()(k) <= 0) continue;
    const Eigen::VectorXcd q = eig.eigenvectors().col(k).head(n);
    const auto share = [&](int offset) {
      return (q.segment(offset, N).adjoint() * M.block(offset, offset, N, N) * q.segment(offset, N))(0).real();
    };
    modes.emplace_back(1 / eig.eigenvalues()(k), share(ax) > std::max(share(th), share(lv)));
  }
  std::sort(modes.begin(), modes.end());
  std::vector<double> out;
  for (const auto& [omega, axial] : modes) {
    if (!axial && out.size() < 10) out.push_back(omega * L * L * std::sqrt(rho * A / (E * I)));
  }
  return out;
}

template <class List>
const typename List::value_type* find_entry(const List& list, int table, double d, int mode) {
  for (const auto& e : list) {
    if (e.table == table && e.slenderness == d && e.mode == mode) return &e;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("paper Tables 4 and 5 with the paper's basis, N = 10: within 1 % but for named entries", "[modes][paper]") {
  int within = 0, named = 0;
  double worst = 0;
  for (int table : {4, 5}) {
    for (const Column& column : table == 4 ? table4 : table5) {
      const double speed = table == 4 ? 0 : 300;
      const std::vector<double> ours = non_axial_lambdas(column.slenderness, speed, 10);
      const std::vector<double> closed_form = closed_form_lambdas(column.slenderness, speed, 10);
      REQUIRE(ours.size() == 10);
      REQUIRE(closed_form.size() == 10);
      for (int k = 0; k < 10; ++k) {
        INFO("Table " << table << ", d = " << column.slenderness << ", mode " << k + 1 << ": paper "
                      << column.lambda[k] << ", ours " << ours[k] << ", closed form " << closed_form[k]);
        // The library's N = 10 model is the paper's: measured ≤ 7.5e-13 apart.
        CHECK(std::abs(ours[k] / closed_form[k] - 1) < 1e-9);
        worst = std::max(worst, std::abs(ours[k] / closed_form[k] - 1));
        const double deviation = std::abs(closed_form[k] / column.lambda[k] - 1);
        if (find_entry(misprints, table, column.slenderness, k + 1) != nullptr) {
          ++named;
        } else if (find_entry(n10_exceptions, table, column.slenderness, k + 1) != nullptr) {
          CHECK(deviation > 0.0099);
          ++named;
        } else {
          CHECK(deviation <= 0.01);
          ++within;
        }
      }
    }
  }
  CHECK(within == 80 - 3 - 32);
  CHECK(named == 35);
  WARN("library N = 10 against the closed-form model: largest relative difference " << worst);
  // The misprints: the docs/theory.md §8 one really is below the exact value; 127.7992 is above the N = 10
  // value that the converged 126.004 (docs/theory.md §7) lies under; 225.0000 is more than 2 % from N = 10
  // and N = 20 alike.
  CHECK(3.4809 < reference::timoshenko_cantilever_lambdas(0.01, 2 * 1.3 / 0.833, 1)[0]);
  CHECK(127.7992 > closed_form_lambdas(0.01, 300, 10)[3]);
  CHECK(closed_form_lambdas(0.01, 300, 10)[3] > 126.004);
  CHECK(std::abs(closed_form_lambdas(0.005, 300, 10)[4] / 225 - 1) > 0.02);
  CHECK(std::abs(closed_form_lambdas(0.005, 300, 20)[4] / 225 - 1) > 0.02);
}

TEST_CASE("the paper's N = 10 model at rest bounds the closed-form Timoshenko frequencies from above", "[modes][paper]") {
  // Rayleigh–Ritz: at Ω = 0 the θ–v problem is a symmetric definite pencil, so the k-th Ritz value is
  // at least the k-th exact one (Huang's frequency equation, reference/timoshenko_cantilever.hpp,
  // whose roots include the second spectrum above the cutoff). Measured: mode 1 of d̄ = 0.01 is
  // 2e-5 above the exact 3.51265, the tenth modes 2–6 % above.
  for (const Column& column : table4) {
    const std::vector<double> ritz = closed_form_lambdas(column.slenderness, 0, 10);
    const std::vector<double> exact = reference::timoshenko_cantilever_lambdas(column.slenderness, 2 * 1.3 / 0.833, 10);
    for (int k = 0; k < 10; ++k) {
      INFO("d = " << column.slenderness << ", mode " << k + 1 << ": N = 10 " << ritz[k] << ", exact " << exact[k]);
      CHECK(ritz[k] >= exact[k] * (1 - 1e-12));
    }
  }
}

TEST_CASE("paper Tables 4 and 5 are the sine basis with N = 20", "[modes][paper]") {
  for (int table : {4, 5}) {
    for (const Column& column : table == 4 ? table4 : table5) {
      const std::vector<double> ours = non_axial_lambdas(column.slenderness, table == 4 ? 0 : 300, 20);
      for (int k = 0; k < 10; ++k) {
        if (find_entry(misprints, table, column.slenderness, k + 1) != nullptr) continue;
        INFO("Table " << table << ", d = " << column.slenderness << ", mode " << k + 1 << ": paper "
                      << column.lambda[k] << ", ours " << ours[k]);
        // Stubby columns agree to 0.1 % (modes 3–10 to 0.02 %); the slender ones' modes 2–6 differ
        // by up to 0.44 %.
        CHECK(std::abs(ours[k] / column.lambda[k] - 1) <= (column.slenderness >= 0.05 ? 1e-3 : 4.5e-3));
      }
    }
  }
}
