// Campbell diagram: mode tracking by shape through crossings, engine-order crossing points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <complex>
#include <string>
#include <vector>

#include <boost/math/tools/toms748_solve.hpp>

#include "bladestab/modal/campbell.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/base/input_error.hpp"
#include "bladestab/modal/basis_error.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {
constexpr double two_pi = 6.28318530717958647692;
constexpr double pi = two_pi / 2;

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
  return v;
}

// Every natural frequency [Hz] of a model at one speed, by the dense solve of the whole Ritz
// model, with its relative rounding. Undamped, each is the Rayleigh functional of its dense
// eigenvector: the dense eigenvalue itself carries ~eps·ω_max/ω of rounding, where the functional
// (quadratic in the vector's error) is limited by the stiffness form's own (frequency_rounding).
struct Reference {
  std::vector<double> hz, rounding;
};
Reference whole_frequencies(const BladeModel& model, const DampingSpec& damping, double speed) {
  const SecondOrderSystem sys = system_at(model, speed, damping_matrix(model, damping, speed));
  const ModalSolution sol = solve_modes(model, sys, speed, 0, EigenSolverKind::dense);
  const Eigen::MatrixXd absolute = sys.K.cwiseAbs();
  Reference out;
  for (const Mode& m : sol.modes) {
    const double k = (m.shape.adjoint() * sys.K * m.shape)(0).real();
    out.rounding.push_back(frequency_rounding(absolute, m.shape.cwiseAbs(), k));
    if (damping.model != DampingModel::none) {
      out.hz.push_back(m.frequency_hz);
      continue;
    }
    // (λ²M + λC + K)q = 0 at λ = iω: k + ω·(i qᴴCq) − ω² m = 0, i qᴴCq real for a skew C.
    const double c = (std::complex<double>(0, 1) * (m.shape.adjoint() * sys.C * m.shape)(0)).real();
    const double mass = (m.shape.adjoint() * sys.M * m.shape)(0).real();
    out.hz.push_back((c + std::sqrt(c * c + 4 * k * mass)) / (2 * mass) / two_pi);
  }
  return out;
}

// Relative distance from f to the nearest reference frequency, less that one's rounding.
double nearest(const Reference& reference, double f) {
  double best = 1e300;
  for (std::size_t k = 0; k < reference.hz.size(); ++k) {
    best = std::min(best, std::max(0.0, std::abs(f / reference.hz[k] - 1) - reference.rounding[k]));
  }
  return best;
}

// A model converged far beyond the estimates checked against it (Legendre, 36 terms: the 12th
// mode of the paper blade changes by ~1e-12 from 30 terms on).
BladeModel converged(const Scene& s) {
  ModelSpec spec = s.model;
  spec.basis = BasisKind::legendre;
  spec.terms = 36;
  return assemble_model(s, spec);
}

// The converged model's own crossing of the line k·Ω/2π, by secant steps from the reported one.
double converged_crossing(const BladeModel& truth, const DampingSpec& damping, const EngineOrderCrossing& x) {
  const double line = x.engine_order / two_pi;
  const auto g = [&](double speed) {
    const std::vector<double> f = whole_frequencies(truth, damping, speed).hz;
    const double near = *std::min_element(f.begin(), f.end(), [&](double a, double b) {
      return std::abs(a - line * speed) < std::abs(b - line * speed);
    });
    return near - line * speed;
  };
  double a = x.speed_rad_s, b = x.speed_rad_s * (1 + 1e-6), ga = g(a), gb = g(b);
  for (int iteration = 0; iteration < 6 && gb != ga && std::abs(b - a) > 1e-14 * b; ++iteration) {
    const double next = b - gb * (b - a) / (gb - ga);
    a = b, ga = gb, b = next, gb = g(b);
  }
  return b;
}

struct Variant {
  std::string name;
  std::vector<std::string> overrides;
  int count;
  double tolerance;
};
}  // namespace

TEST_CASE("without Coriolis coupling, bending modes cross the first axial mode and tracking follows shapes",
          "[campbell]") {
  const Scene s = paper_scene({"model.coriolis=false"});
  const BladeModel model = assemble_model(s);
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 1500, 31), {}, 6});
  const CampbellCurve& axial = d.curves[4];
  REQUIRE(axial.family == ModeFamily::axial);
  // The axial frequency only softens slightly with speed (−ρAΩ² ∫u²): Ω = 0 value (2n−1)π/2 · c/L.
  const double f_axial = std::sqrt(117e9 / 4466.0) / 4;
  CHECK(axial.frequency_hz.front() == Approx(f_axial).epsilon(1e-9));
  for (std::size_t i = 0; i < d.speeds_rad_s.size(); ++i) {
    // Decoupled axial bar spinning: ω² = ω0² − Ω² exactly for every axial mode.
    const double W = d.speeds_rad_s[i];
    CHECK(axial.frequency_hz[i] == Approx(std::sqrt(std::pow(two_pi * f_axial, 2) - W * W) / two_pi).epsilon(1e-8));
    CHECK(axial.correlation[i] == Approx(1).epsilon(1e-12));
  }
  // Bending modes 3 and 4 start below and end above it; sort order would have swapped labels.
  for (int k : {2, 3}) {
    CHECK(d.curves[k].frequency_hz.front() < axial.frequency_hz.front());
    CHECK(d.curves[k].frequency_hz.back() > axial.frequency_hz.back());
    for (std::size_t i = 1; i < d.speeds_rad_s.size(); ++i) {
      CHECK(d.curves[k].frequency_hz[i] > d.curves[k].frequency_hz[i - 1]);
    }
  }
}

TEST_CASE("with Coriolis coupling, modes veer and stay tracked", "[campbell]") {
  const Scene s = paper_scene();
  const BladeModel model = assemble_model(s);
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 1500, 61), {}, 6});
  for (const CampbellCurve& c : d.curves) {
    for (std::size_t i = 1; i < c.frequency_hz.size(); ++i) {
      CHECK(c.correlation[i] > 0.5);
      CHECK(std::abs(c.frequency_hz[i] / c.frequency_hz[i - 1] - 1) < 0.1);
    }
  }
}

TEST_CASE("engine-order crossings are where a dense scan of the whole model's frequencies meets the line", "[campbell]") {
  // Independent of campbell.cpp's tracking and root finding: the j-th lowest frequency of the whole
  // Ritz model (dense solve, Rayleigh-refined) is continuous in Ω, so every crossing of mode j with
  // f = kΩ/2π is a sign change of f_j(Ω) − kΩ/2π on a 40 rad/s grid, solved here by Boost's TOMS 748
  // to 1e-13. With Coriolis coupling the first four modes veer but do not cross below 600 rad/s,
  // so the j-th lowest is the diagram's curve j.
  const Scene s = paper_scene();
  const BladeModel model = assemble_model(s);
  const std::vector<int> orders{2, 3, 4, 8};
  const int modes = 4;
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 600, 13), orders, modes});
  const auto lowest = [&](double speed) {
    std::vector<double> hz = whole_frequencies(model, s.damping, speed).hz;
    std::sort(hz.begin(), hz.end());
    hz.resize(modes);
    return hz;
  };
  struct Found {
    int order, mode;
    double speed;
  };
  std::vector<Found> expected;
  const std::vector<double> grid = linspace(0, 600, 16);
  std::vector<std::vector<double>> sampled;  // [speed][mode − 1]
  for (double speed : grid) sampled.push_back(lowest(speed));
  for (int k : orders) {
    for (int j = 1; j <= modes; ++j) {
      const auto gap = [&](double speed) { return lowest(speed)[j - 1] - k * speed / two_pi; };
      for (std::size_t i = 1; i < grid.size(); ++i) {
        const double below = sampled[i - 1][j - 1] - k * grid[i - 1] / two_pi;
        const double above = sampled[i][j - 1] - k * grid[i] / two_pi;
        if ((below > 0) == (above > 0)) continue;
        std::uintmax_t iterations = 60;
        const std::pair<double, double> root = boost::math::tools::toms748_solve(
            gap, grid[i - 1], grid[i], below, above,
            [](double a, double b) { return std::abs(b - a) <= 1e-13 * b; }, iterations);
        expected.push_back({k, j, 0.5 * (root.first + root.second)});
      }
    }
  }
  REQUIRE(expected.size() >= 5);
  CHECK(d.crossings.size() == expected.size());  // none missed, none invented
  double worst = 0;
  for (const Found& e : expected) {
    INFO("EO " << e.order << ", mode " << e.mode << ": the scan finds " << e.speed << " rad/s");
    const auto x = std::find_if(d.crossings.begin(), d.crossings.end(), [&](const EngineOrderCrossing& c) {
      return c.engine_order == e.order && c.mode == e.mode;
    });
    REQUIRE(x != d.crossings.end());
    INFO("campbell: " << x->speed_rad_s << " rad/s, " << x->frequency_hz << " Hz");
    // The crossing's speed to 1e-9: the frequencies' rounding (~1e-13) times the crossing's
    // amplification (below 10 here); measured ≤ 4e-13.
    CHECK(std::abs(x->speed_rad_s / e.speed - 1) < 1e-9);
    CHECK(std::abs(x->frequency_hz / (e.order * e.speed / two_pi) - 1) < 1e-9);
    worst = std::max(worst, std::abs(x->speed_rad_s / e.speed - 1));
  }
  for (std::size_t i = 1; i < d.crossings.size(); ++i) {
    CHECK(d.crossings[i].speed_rad_s >= d.crossings[i - 1].speed_rad_s);
  }
  WARN(expected.size() << " crossings; largest relative difference of their speeds from the scan's " << worst);
}

TEST_CASE("without Coriolis coupling the axial mode meets engine order k at the closed form omega0/sqrt(1 + k^2)",
          "[campbell]") {
  // The decoupled spinning bar: K_uu − Ω²M_uu, so ω² = ω0² − Ω² with ω0 = (π/2) sqrt(E/ρ)/L (16
  // Legendre terms resolve sin(πs/2L) to rounding); kΩ = sqrt(ω0² − Ω²) at Ω = ω0/sqrt(1 + k²).
  const Scene s = paper_scene({"model.coriolis=false"});
  const BladeModel model = assemble_model(s);
  const std::vector<int> orders{8, 10, 12};
  const CampbellDiagram d = campbell_diagram(model, s.damping, {linspace(0, 1200, 25), orders, 6});
  const double omega0 = pi / 2 * std::sqrt(117e9 / 4466.0) / 1.0;
  for (int k : orders) {
    INFO("EO " << k);
    const auto x = std::find_if(d.crossings.begin(), d.crossings.end(), [&](const EngineOrderCrossing& c) {
      return c.engine_order == k && d.curves[c.mode - 1].family == ModeFamily::axial;
    });
    REQUIRE(x != d.crossings.end());
    const double exact = omega0 / std::sqrt(1.0 + k * k);
    INFO("campbell " << x->speed_rad_s << " rad/s, closed form " << exact << " rad/s");
    CHECK(std::abs(x->speed_rad_s / exact - 1) < 1e-10);  // measured ≤ 5e-16
    WARN("EO " << k << ": relative difference from the closed form " << std::abs(x->speed_rad_s / exact - 1));
  }
}

TEST_CASE("the reduced sweep's frequencies are the whole Ritz model's within their bounds, 0 to 600 rad/s",
          "[campbell][reduced][long_under_sanitizers]") {
  const std::vector<Variant> variants{
      {"paper blade", {}, 8, 0},
      {"paper blade, 12 modes", {}, 12, 0},
      {"thick blade d = 0.1", {"blade.slenderness=0.1"}, 8, 0},
      {"sine basis, 10 terms", {"model.basis=sine", "model.terms=10"}, 8, 0},
      {"Coriolis off (true crossings)", {"model.coriolis=false"}, 8, 0},
      {"Euler-Bernoulli", {"model.theory=euler-bernoulli"}, 8, 0},
      {"no axial field", {"model.axial=false"}, 6, 0},
  };
  const std::vector<double> speeds = linspace(0, 600, 61);
  for (const Variant& v : variants) {
    const Scene s = paper_scene(v.overrides);
    const BladeModel model = assemble_model(s);
    CampbellOptions options{speeds, {}, v.count};
    options.reduction_tolerance = 1e-8;
    const CampbellDiagram d = campbell_diagram(model, s.damping, options);
    INFO(v.name);
    REQUIRE(d.reduced);
    double worst = 0, worst_bound = 0;
    for (std::size_t k = 0; k < speeds.size(); ++k) {
      const Reference whole = whole_frequencies(model, s.damping, speeds[k]);
      for (const CampbellCurve& c : d.curves) {
        INFO("speed " << speeds[k] << ", mode " << c.mode << ", " << c.frequency_hz[k] << " Hz");
        const double error = nearest(whole, c.frequency_hz[k]);
        // The bound holds, up to the rounding of both values (the reference's is of the same size).
        CHECK(error <= c.reduction_bound[k] + 2 * c.rounding[k]);
        CHECK(c.reduction_bound[k] <= options.reduction_tolerance);  // and meets the wanted one
        worst = std::max(worst, error);
        worst_bound = std::max(worst_bound, c.reduction_bound[k]);
      }
    }
    WARN(v.name << ": " << d.basis_vectors << " vectors from " << d.sample_speeds_rad_s.size()
                << " speeds; largest difference from the whole model " << worst << ", largest bound "
                << worst_bound);
  }
}

TEST_CASE("Campbell error estimates cover the error against a converged model, points and crossings",
          "[campbell][budget][slow][parallel]") {
  const std::vector<Variant> variants{
      {"paper blade", {}, 8, 1e-6},
      {"thick blade d = 0.1", {"blade.slenderness=0.1"}, 8, 1e-6},
      {"sine basis, 10 terms", {"model.basis=sine", "model.terms=10"}, 6, 1e-2},
      {"Coriolis off", {"model.coriolis=false"}, 8, 1e-6},
      {"loose tolerance, 8 terms", {"model.terms=8"}, 6, 1e-4},
  };
  const std::vector<double> speeds = linspace(0, 600, 11);
  for (const Variant& v : variants) {
    const Scene s = paper_scene(v.overrides);
    const CampbellWithErrors r = campbell_with_error_estimate(s, {speeds, {1, 2, 3, 4, 6}, v.count}, v.tolerance);
    const BladeModel truth = converged(s);
    INFO(v.name << ", " << r.model.spec.terms << " terms");
    REQUIRE(r.diagram.reduced);
    double lowest_ratio = 1e300, highest_ratio = 0;
    for (std::size_t k = 0; k < speeds.size(); ++k) {
      const Reference whole = whole_frequencies(r.model, s.damping, speeds[k]);
      const Reference exact = whole_frequencies(truth, s.damping, speeds[k]);
      for (std::size_t i = 0; i < r.diagram.curves.size(); ++i) {
        const double f = r.diagram.curves[i].frequency_hz[k];
        const ErrorBudget& b = r.budget[i][k];
        INFO("speed " << speeds[k] << ", mode " << i + 1 << ", " << f << " Hz, estimate " << b.total());
        CHECK(b.total() <= v.tolerance);                // the terms were raised until it was met
        CHECK(nearest(whole, f) <= v.tolerance);        // the fast path is the chosen model's to within it
        const double error = nearest(exact, f);
        CHECK(error <= b.total());                      // the estimate covers the true error
        if (error > 1e-11) {
          lowest_ratio = std::min(lowest_ratio, b.total() / error);
          highest_ratio = std::max(highest_ratio, b.total() / error);
        }
      }
    }
    // Crossings: the converged model's own crossing, by secant steps from the reported one.
    for (std::size_t c = 0; c < r.diagram.crossings.size(); ++c) {
      const EngineOrderCrossing& x = r.diagram.crossings[c];
      const double b = converged_crossing(truth, s.damping, x);
      const double error = std::abs(x.speed_rad_s / b - 1);
      INFO("EO " << x.engine_order << ", mode " << x.mode << " at " << x.speed_rad_s << " rad/s: converged "
                 << b << ", estimate " << r.crossing_budget[c].total());
      CHECK(error <= r.crossing_budget[c].total());
    }
    WARN(v.name << ": " << r.model.spec.terms << " terms, estimate/true " << lowest_ratio << " to "
                << highest_ratio << " where the true error exceeds 1e-11; " << r.diagram.crossings.size()
                << " crossings checked");
  }
}

TEST_CASE("a crossing where the richer model's reduced sweep cannot bound its modes is estimated on the dense sweep",
          "[campbell][budget][parallel]") {
  // Two speeds 0 and 2250 rad/s at 6 terms: the richer model's reduced basis, sampled at 0, 1125
  // and 2250 rad/s, cannot bound its modes at the 4th engine order's crossing of mode 2 (~472 rad/s).
  const Scene s = paper_scene({"model.terms=6"});
  const CampbellWithErrors r = campbell_with_error_estimate(s, {linspace(0, 2250, 2), {4}, 8}, 1e-6);
  const BladeModel truth = converged(s);
  REQUIRE(!r.diagram.crossings.empty());
  for (std::size_t c = 0; c < r.diagram.crossings.size(); ++c) {
    const EngineOrderCrossing& x = r.diagram.crossings[c];
    const double error = std::abs(x.speed_rad_s / converged_crossing(truth, s.damping, x) - 1);
    INFO("EO 4, mode " << x.mode << " at " << x.speed_rad_s << " rad/s, estimate " << r.crossing_budget[c].total());
    CHECK(std::isfinite(r.crossing_budget[c].total()));
    CHECK(r.crossing_budget[c].total() <= 1e-6);
    CHECK(error <= r.crossing_budget[c].total());
  }
}

TEST_CASE("damped blades take the dense sweep, and their estimates cover the error too", "[campbell][budget][slow][parallel]") {
  const std::vector<Variant> variants{
      {"modal 2 %", {"damping.model=modal", "damping.ratio=0.02"}, 4, 1e-6},
      {"Rayleigh 2 %", {"damping.model=rayleigh", "damping.ratio=0.02", "damping.frequencies_hz=[50, 2000]"}, 4,
       1e-6},
      {"paper (37) 1 %", {"damping.model=paper", "damping.ratio=0.01"}, 4, 1e-6},
  };
  const std::vector<double> speeds = linspace(50, 600, 6);  // the paper's damping is undefined at rest
  for (const Variant& v : variants) {
    const Scene s = paper_scene(v.overrides);
    const CampbellWithErrors r = campbell_with_error_estimate(s, {speeds, {2}, v.count}, v.tolerance);
    const BladeModel truth = converged(s);
    INFO(v.name << ", " << r.model.spec.terms << " terms");
    CHECK_FALSE(r.diagram.reduced);
    for (std::size_t k = 0; k < speeds.size(); ++k) {
      const Reference exact = whole_frequencies(truth, s.damping, speeds[k]);
      for (std::size_t i = 0; i < r.diagram.curves.size(); ++i) {
        const double f = r.diagram.curves[i].frequency_hz[k];
        INFO("speed " << speeds[k] << ", mode " << i + 1 << ", " << f << " Hz");
        CHECK(r.diagram.curves[i].damping_ratio[k] > 0);
        if (f == 0) continue;  // overdamped (the paper's damping at low speed): 0 Hz, no relative error
        CHECK(r.budget[i][k].total() <= v.tolerance);
        CHECK(nearest(exact, f) <= r.budget[i][k].total());
      }
    }
  }
}

TEST_CASE("heavy damping's overdamped roots among the modes take no tracked mode's place", "[campbell][budget][slow]") {
  // Rayleigh ζ = 0.3 (met at 50 and 2000 Hz): from about 600 rad/s five overdamped rotation and axial
  // roots lie by |λ| below mode 8, the bending mode near 3100 Hz (ζ ≈ 0.42). It was left for an
  // overdamped root (0 Hz, MAC 6e-7, "bending>rotation"). Each curve against the converged model.
  const Scene s = paper_scene({"damping.model=rayleigh", "damping.ratio=0.3", "damping.frequencies_hz=[50, 2000]"});
  const std::vector<double> speeds = linspace(500, 1000, 6);
  const CampbellWithErrors r = campbell_with_error_estimate(s, {speeds, {2}, 8}, 1e-6);
  const BladeModel truth = converged(s);
  for (std::size_t k = 0; k < speeds.size(); ++k) {
    const Reference exact = whole_frequencies(truth, s.damping, speeds[k]);
    for (std::size_t i = 0; i < r.diagram.curves.size(); ++i) {
      const double f = r.diagram.curves[i].frequency_hz[k];
      INFO("speed " << speeds[k] << ", mode " << i + 1 << ", " << f << " Hz");
      REQUIRE(f > 0);
      CHECK(r.diagram.curves[i].correlation[k] > 0.99);
      CHECK(nearest(exact, f) <= r.budget[i][k].total());
    }
  }
  CHECK(r.diagram.curves[7].frequency_hz[1] == Approx(3103.8947).epsilon(1e-7));  // 600 rad/s
}

TEST_CASE("campbell --tolerance and modes --tolerance choose the same model and agree", "[campbell][modes][parallel]") {
  Scene at300 = paper_scene({"operation.speed_rad_s=300"});
  const ConvergedModes m = modes_with_error_estimate(at300, 8, EigenSolverKind::dense, 1e-6);
  const CampbellWithErrors r = campbell_with_error_estimate(at300, {{300, 310}, {}, 8}, 1e-6);
  CHECK(r.model.spec.terms == m.model.spec.terms);
  for (int i = 0; i < 8; ++i) {
    const double f = r.diagram.curves[i].frequency_hz[0], g = m.solution.modes[i].frequency_hz;
    INFO("mode " << i + 1 << ": campbell " << f << " Hz, modes " << g << " Hz");
    CHECK(std::abs(f / g - 1) <= r.budget[i][0].total() + m.budget(i).total());
  }
}

TEST_CASE("an unreachable tolerance is a parameter error naming the tolerance, not a CLI flag", "[campbell][parallel]") {
  const std::vector<double> speeds = linspace(0, 400, 5);
  const auto message_of = [&](const Scene& scene, double tolerance) -> std::string {
    try {
      campbell_with_error_estimate(scene, {speeds, {}, 4}, tolerance);
    } catch (const ParameterError& e) {
      CHECK(e.parameter() == "tolerance");
      return e.what();
    }
    FAIL("no ParameterError for tolerance " << tolerance);
    return "";
  };
  const std::string sine = message_of(paper_scene({"model.basis=sine", "model.terms=10"}), 1e-6);
  CHECK(sine.rfind("tolerance 1e-06: not met", 0) == 0);
  CHECK(sine.find("legendre") != std::string::npos);
  CHECK(message_of(paper_scene(), 1e-13).rfind("tolerance 1e-13:", 0) == 0);
}

TEST_CASE("campbell with overdamped modes: the estimate the tolerance holds is over the points that oscillate",
          "[campbell][budget]") {
  // Rayleigh ζ = 0.3 at 68 and 558 Hz overdamps modes 5 and 6 at every speed (mode 4 oscillates at
  // 1484 Hz at 1000 rad/s, ζ = 0.73, past eight overdamped roots by |λ|). Their points (0 Hz) carry
  // a budget of 1, which the header printed as the diagram's error beside "tolerance 1e-06" that
  // the sweep had met on the oscillating points.
  const Scene s = paper_scene({"damping.model=rayleigh", "damping.ratio=0.3", "damping.frequencies_hz=[68, 558]"});
  const CampbellWithErrors r = campbell_with_error_estimate(s, {linspace(0, 1000, 2), {1}, 6}, 1e-6);
  CHECK(r.worst().total() <= 1e-6);
  CHECK(r.points_not_oscillating() == 4);
  // Mode 1 at 1000 rad/s against an independent dense solve of the 24-term model there.
  Scene fast = s;
  fast.operation.speed_rad_s = 1000;
  fast.model.terms = 24;
  const ConvergedModes reference = modes_with_error_estimate(fast, 1, EigenSolverKind::dense);
  const double f = r.diagram.curves[0].frequency_hz[1], f_ref = reference.solution.modes[0].frequency_hz;
  CHECK(std::abs(f / f_ref - 1) <= r.budget[0][1].total() + reference.budget(0).total());
}
