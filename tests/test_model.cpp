// The Ritz model: quadrature, the matrices against the energy integrals they stand for, the static
// centrifugal stretch.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "blade/basis.hpp"
#include "bladestab/blade/model.hpp"
#include "bladestab/base/numerical_error.hpp"
#include "blade/quadrature.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

// The paper blade's data (docs/theory.md §7, Table 2), written out rather than taken from the model.
constexpr double length = 1.0, hub = 0.5, area = 22.39e-4, youngs = 117e9, rho = 4466.0, kappa = 0.833;
constexpr double inertia = 0.01 * 0.01 * area * length * length;  // I = d̄² A L²
constexpr double shear_modulus = youngs / (2 * (1 + 0.3));
constexpr double pi = 3.14159265358979323846;
const double cos_beta = std::cos(-60 * pi / 180);

// The fields θ, v, u and their s-derivatives at one point.
struct Fields {
  double theta = 0, theta_s = 0, v = 0, v_s = 0, v_ss = 0, u = 0, u_s = 0;
};
using Integrand = std::function<double(const Fields&, const Fields&, double)>;

// Shape function k (1-based) of a field, value and derivatives, from docs/theory.md §2's definitions:
// paper basis (18a–c) U = sin λs, V = (1 − cos λs)/λ, W = sin λs/λ with λ = (2k − 1)π/(2L);
// integrated Legendre φ_k(s) = ∫₀ˢ P_{k−1}(2ξ/L − 1) dξ (std::legendre under Boost's 30-point
// Gauss rule, exact to degree 59), and for the Euler–Bernoulli lateral field
// ψ_k = ∫₀ˢ φ_k = ∫₀ˢ (s − ξ) P_{k−1}(2ξ/L − 1) dξ.
enum class Field { rotation, lateral, axial };
struct Shape {
  double value, slope, curvature;
};
Shape shape(BasisKind basis, Field field, bool clamped_slope, int k, double s) {
  if (basis == BasisKind::sine) {
    const double lambda = (2 * k - 1) * pi / (2 * length), sn = std::sin(lambda * s), cs = std::cos(lambda * s);
    switch (field) {
      case Field::rotation: return {sn, lambda * cs, -lambda * lambda * sn};
      case Field::lateral: return {(1 - cs) / lambda, sn, lambda * cs};
      case Field::axial: return {sn / lambda, cs, -lambda * sn};
    }
  }
  using boost::math::quadrature::gauss;
  const auto P = [k](double xi) { return std::legendre(k - 1, 2 * xi / length - 1); };
  const double phi = gauss<double, 30>::integrate(P, 0.0, s);
  if (field == Field::lateral && clamped_slope) {
    return {gauss<double, 30>::integrate([&](double xi) { return (s - xi) * P(xi); }, 0.0, s), phi, P(s)};
  }
  return {phi, P(s), std::nan("")};  // φ'' is not part of any energy here
}

// The blade's fields from a coefficient vector f = [X; Y; Z] laid out as the model's, and the
// integral of an energy density over the span. The shape functions at each point are kept: the
// quadrature visits the same points for every form.
struct IndependentBlade {
  BasisKind basis;
  bool timoshenko;
  DofLayout layout;
  mutable std::map<double, std::vector<Shape>> shapes_at;  // U_1..U_N, V_1..V_N, W_1..W_N as laid out

  const std::vector<Shape>& shapes(double s) const {
    auto [it, inserted] = shapes_at.try_emplace(s);
    if (inserted) {
      for (int k = 1; k <= layout.theta_count; ++k) it->second.push_back(shape(basis, Field::rotation, false, k, s));
      for (int k = 1; k <= layout.lateral_count; ++k) {
        it->second.push_back(shape(basis, Field::lateral, !timoshenko, k, s));
      }
      for (int k = 1; k <= layout.axial_count; ++k) it->second.push_back(shape(basis, Field::axial, false, k, s));
    }
    return it->second;
  }

  Fields fields(const Eigen::VectorXd& f, double s) const {
    const std::vector<Shape>& shape = shapes(s);
    Fields out;
    for (int i = layout.theta_offset(); i < layout.theta_offset() + layout.theta_count; ++i) {
      out.theta += f(i) * shape[i].value;
      out.theta_s += f(i) * shape[i].slope;
    }
    for (int i = layout.lateral_offset(); i < layout.lateral_offset() + layout.lateral_count; ++i) {
      out.v += f(i) * shape[i].value;
      out.v_s += f(i) * shape[i].slope;
      out.v_ss += f(i) * shape[i].curvature;
    }
    for (int i = layout.axial_offset(); i < layout.axial_offset() + layout.axial_count; ++i) {
      out.u += f(i) * shape[i].value;
      out.u_s += f(i) * shape[i].slope;
    }
    return out;
  }

  // ∫₀ᴸ density(a(s), b(s), s) ds and ∫₀ᴸ |density| ds (the scale of its rounding).
  std::pair<double, double> integrate(const Integrand& density, const Eigen::VectorXd& a,
                                      const Eigen::VectorXd& b) const {
    using boost::math::quadrature::gauss_kronrod;
    const auto at = [&](double s) { return density(fields(a, s), fields(b, s), s); };
    double error = 0, magnitude = 0;
    const double value = gauss_kronrod<double, 61>::integrate(at, 0.0, length, 12, 1e-14, &error, &magnitude);
    return {value, magnitude};
  }
};

// One model matrix and the polarized energy density it must reproduce: aᵀXb = ∫ density(a, b) ds.
struct EnergyForm {
  const char* name;
  Eigen::MatrixXd matrix;
  Integrand integrand;
};

std::vector<EnergyForm> energy_forms(const BladeModel& m) {
  const bool timoshenko = m.layout.theta_count > 0;
  const double EI = youngs * inertia, kGA = kappa * shear_modulus * area, EA = youngs * area;
  return {
      // T = ½∫[ρA(v̇² + u̇²) + ρI θ̇²] (Euler–Bernoulli: no rotary inertia).
      {"M", m.M,
       [](const Fields& a, const Fields& b, double) {
         return rho * area * (a.v * b.v + a.u * b.u) + rho * inertia * a.theta * b.theta;
       }},
      // U = ½∫[EI θ'² + κGA(v' − θ)² + EA u'²]; Euler–Bernoulli θ = v': ½∫[EI v''² + EA u'²].
      {"K_S", m.K_S,
       [=](const Fields& a, const Fields& b, double) {
         const double bending = timoshenko ? EI * a.theta_s * b.theta_s + kGA * (a.v_s - a.theta) * (b.v_s - b.theta)
                                           : EI * a.v_ss * b.v_ss;
         return bending + EA * a.u_s * b.u_s;
       }},
      // Per Ω²: ½∫ T_cf v'² with T_cf/Ω² = ρA[r(L − s) + (L² − s²)/2], and the spin softening
      // −½ρA cos²β ∫v², −½ρI ∫θ², −½ρA ∫u² (docs/theory.md §1).
      {"K_C1", m.K_C1,
       [](const Fields& a, const Fields& b, double s) {
         const double tension = rho * area * (hub * (length - s) + (length * length - s * s) / 2);
         return tension * a.v_s * b.v_s - rho * area * cos_beta * cos_beta * a.v * b.v -
                rho * inertia * a.theta * b.theta - rho * area * a.u * b.u;
       }},
      // Per newton of tip tension: ½∫ v'² (N = T_cf + F).
      {"G", m.G, [](const Fields& a, const Fields& b, double) { return a.v_s * b.v_s; }},
      // Per Ω: the Coriolis forces −2ρAΩ cos β u̇ on v and +2ρAΩ cos β v̇ on u, moved to the left
      // side: δfᵀ C ḟ = −(their virtual work) = ∫ 2ρA cos β (δv u̇ − δu v̇).
      {"C_G1", m.C_G1,
       [](const Fields& a, const Fields& b, double) { return 2 * rho * area * cos_beta * (a.v * b.u - a.u * b.v); }},
  };
}

}  // namespace

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

TEST_CASE("model matrices are the SPEC's energy forms evaluated independently and the mass is positive definite",
          "[model]") {
  // For random coefficient vectors a, b (both orders, so an error in one triangle shows even though
  // the assembly symmetrizes), aᵀXb against the energy integral of docs/theory.md §1–2 that X stands for,
  // evaluated here from the shape functions' definitions (18a–c) / the integrated Legendre
  // polynomials with Boost's adaptive Gauss–Kronrod rule. Measured agreement ≤ 2e-15 of the
  // integrand's magnitude (asserted 1e-12); a wrong sign of K_θv, a missing cos β or a block put in
  // the wrong place is off by order one.
  std::mt19937 generator(2005);
  std::uniform_real_distribution<double> uniform(-1, 1);
  double worst = 0;
  for (BasisKind basis : {BasisKind::sine, BasisKind::legendre}) {
    for (BeamTheory theory : {BeamTheory::timoshenko, BeamTheory::euler_bernoulli}) {
      const Scene s = paper_scene({std::string("model.basis=") + to_string(basis),
                                   std::string("model.theory=") + to_string(theory)});
      const BladeModel m = assemble_model(s);
      CHECK(Eigen::LLT<Eigen::MatrixXd>(m.M).info() == Eigen::Success);
      CHECK(m.layout.size() == (theory == BeamTheory::timoshenko ? 48 : 32));
      const IndependentBlade blade{basis, theory == BeamTheory::timoshenko, m.layout};
      for (int pair = 0; pair < 3; ++pair) {
        const Eigen::VectorXd a = Eigen::VectorXd::NullaryExpr(m.layout.size(), [&] { return uniform(generator); });
        const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(m.layout.size(), [&] { return uniform(generator); });
        for (const auto& [x, y] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
          for (const EnergyForm& form : energy_forms(m)) {
            const auto [exact, magnitude] = blade.integrate(form.integrand, *x, *y);
            const double ours = x->dot(form.matrix * *y);
            INFO(to_string(basis) << ", " << to_string(theory) << ", " << form.name << ", pair " << pair << ": model "
                                  << ours << ", integral " << exact);
            CHECK(std::abs(ours - exact) <= 1e-12 * magnitude);
            worst = std::max(worst, std::abs(ours - exact) / magnitude);
          }
        }
        // Load and tip vectors: ρA ∫(r + s) u ds, v(L), u(L), v'(L).
        const Fields tip = blade.fields(a, length);
        const auto [centrifugal, magnitude] =
            blade.integrate([](const Fields& f, const Fields&, double s) { return rho * area * (hub + s) * f.u; }, a, a);
        INFO(to_string(basis) << ", " << to_string(theory) << ", pair " << pair);
        CHECK(std::abs(m.P_cf1.dot(a) - centrifugal) <= 1e-12 * magnitude);
        CHECK(m.tip_lateral.dot(a) == Approx(tip.v).epsilon(1e-12));
        CHECK(m.tip_axial.dot(a) == Approx(tip.u).epsilon(1e-12));
        CHECK(m.tip_slope.dot(a) == Approx(tip.v_s).epsilon(1e-12));
      }
    }
  }
  WARN("largest |aᵀXb − integral| / ∫|integrand|: " << worst);
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
  CHECK(tip == Approx(2.0e-3).epsilon(0.02));  // docs/theory.md §7: ≈ 2.0 mm
  CHECK(std::abs(m.tip_lateral * f) < 1e-15);
}

TEST_CASE("derived blade quantities follow SPEC section 3 and 7", "[model]") {
  const BladeProperties b(paper_scene().blade);
  CHECK(b.critical_load() == Approx(64637.0).epsilon(1e-4));  // docs/theory.md §8: 0.064637 MN
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
