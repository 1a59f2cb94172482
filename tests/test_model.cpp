// The Ritz model: quadrature, exact symmetry of the matrices, the static centrifugal stretch.
#include <catch2/catch.hpp>

#include <cmath>

#include "basis.hpp"
#include "bladestab/model.hpp"
#include "bladestab/numerical_error.hpp"
#include "quadrature.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

TEST_CASE("Gauss-Legendre rule integrates polynomials of degree 2n-1 exactly", "[model]") {
  for (int n : {1, 2, 5, 13, 40}) {
    const QuadratureRule rule = gauss_legendre(n, 0.5, 2.0);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      const double exact = (std::pow(2.0, k + 1) - std::pow(0.5, k + 1)) / (k + 1);
      const double sum = rule.weights.dot(rule.points.array().pow(k).matrix());
      CHECK(sum == Approx(exact).epsilon(1e-13));
    }
  }
}

TEST_CASE("model matrices have exact symmetry, skew-symmetry and a positive definite mass", "[model]") {
  for (const char* basis : {"sine", "legendre"}) {
    for (const char* theory : {"timoshenko", "euler-bernoulli"}) {
      const Scene s = paper_scene({std::string("model.basis=") + basis, std::string("model.theory=") + theory});
      const BladeModel m = assemble_model(s);
      CHECK(m.M == m.M.transpose());
      CHECK(m.K_S == m.K_S.transpose());
      CHECK(m.K_C1 == m.K_C1.transpose());
      CHECK(m.G == m.G.transpose());
      CHECK(m.C_G1 == -m.C_G1.transpose());
      CHECK(m.C_G1.norm() > 0);
      CHECK(Eigen::LLT<Eigen::MatrixXd>(m.M).info() == Eigen::Success);
      CHECK(m.layout.size() == (std::string(theory) == "timoshenko" ? 48 : 32));
    }
  }
}

TEST_CASE("dropping fields and Coriolis shrinks the model as documented", "[model]") {
  const Scene s = paper_scene({"model.axial=false", "model.theory=euler-bernoulli", "model.terms=5"});
  const BladeModel m = assemble_model(s);
  CHECK(m.layout.size() == 5);
  const Scene c = paper_scene({"model.coriolis=false"});
  CHECK(assemble_model(c).C_G1.norm() == 0);
}

TEST_CASE("sine-basis quadrature is converged to rounding", "[model]") {
  // The sine basis is not polynomial; doubling the number of points must not change the matrices.
  const Scene s = paper_scene({"model.basis=sine", "model.terms=30"});
  const int n = quadrature_points_needed(BasisKind::sine, 30);
  const QuadratureRule a = gauss_legendre(n, 0, 1), b = gauss_legendre(2 * n, 0, 1);
  for (FieldRole role : {FieldRole::rotation, FieldRole::lateral, FieldRole::axial}) {
    const BasisSamples sa = sample_basis(BasisKind::sine, role, 30, 1.0, a.points);
    const BasisSamples sb = sample_basis(BasisKind::sine, role, 30, 1.0, b.points);
    const Eigen::MatrixXd ga = sa.slope.transpose() * a.weights.asDiagonal() * sa.slope;
    const Eigen::MatrixXd gb = sb.slope.transpose() * b.weights.asDiagonal() * sb.slope;
    CHECK((ga - gb).cwiseAbs().maxCoeff() < 1e-13 * gb.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("static centrifugal stretch matches the closed-form spinning bar", "[model]") {
  // EA u'' + ρAΩ² u + ρAΩ²(r + s) = 0, u(0) = 0, u'(L) = 0, with k = Ω sqrt(ρ/E):
  // u = r cos ks + b sin ks − (r + s),  b = (1 + r k sin kL) / (k cos kL).
  const Scene s = paper_scene();
  const BladeModel m = assemble_model(s);
  const double W = 300, r = 0.5, L = 1.0, k = W * std::sqrt(4466.0 / 117e9);
  const double b = (1 + r * k * std::sin(k * L)) / (k * std::cos(k * L));
  const double exact = r * std::cos(k * L) + b * std::sin(k * L) - (r + L);
  const Eigen::VectorXd f = m.stiffness(W).ldlt().solve(W * W * m.P_cf1);
  const double tip = m.tip_axial * f;
  CHECK(tip == Approx(exact).epsilon(1e-12));
  CHECK(tip == Approx(2.0e-3).epsilon(0.02));  // SPEC §7: ≈ 2.0 mm
  CHECK(std::abs(m.tip_lateral * f) < 1e-15);
}

TEST_CASE("derived blade quantities follow SPEC section 3 and 7", "[model]") {
  const BladeProperties b(paper_scene().blade);
  CHECK(b.critical_load() == Approx(64637.0).epsilon(1e-4));  // SPEC §8: 0.064637 MN
  CHECK(b.slenderness() == Approx(0.01).epsilon(1e-14));
  CHECK(b.I == Approx(2.239e-7).epsilon(1e-14));
  CHECK(b.shear_modulus == Approx(117e9 / 2.6).epsilon(1e-15));
}

TEST_CASE("a model without a positive definite mass is refused naming the scene's numbers", "[model]") {
  // Built in code, past the scene's validation: a density of 0 leaves the mass singular.
  Scene s = paper_scene();
  s.blade.density = 0;
  try {
    assemble_model(s);
    FAIL("assemble_model accepted a zero density");
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    CHECK(message.find("mass matrix is not positive definite") != std::string::npos);
    CHECK(message.find("blade.density = 0") != std::string::npos);
    CHECK(message.find("model.terms = 16") != std::string::npos);
  }
  s.blade.youngs_modulus = std::nan("");
  s.blade.density = 7850;
  CHECK_THROWS_WITH(assemble_model(s), Catch::Matchers::Contains("matrices are not finite") &&
                                                           Catch::Matchers::Contains("blade.youngs_modulus = nan"));
}
