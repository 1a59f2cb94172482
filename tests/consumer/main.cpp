// Uses the installed library as another program would: a scene from TOML text, its modes with their
// error estimate, and the Floquet answer at the paper blade's operating point. Exits 0 when the
// slender, non-rotating Euler–Bernoulli cantilever's first two Λ match the closed form
// (β₁L = 1.8751040687119612, β₂L = 4.6940911329741746: Λ = (βL)², the roots of
// cos βL cosh βL = −1) within the library's own error estimate, and the paper point is unstable.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "bladestab/modal/basis_error.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/stability/stability_analysis.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer PAPER_SCENE.toml\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream text;
  text << in.rdbuf();
  try {
    const bladestab::Scene cantilever = bladestab::parse_scene(
        text.str(), argv[1],
        {"model.theory=euler-bernoulli", "model.axial=false", "operation.speed_rad_s=0", "blade.hub_radius=0"});
    const bladestab::ConvergedModes modes =
        bladestab::modes_with_error_estimate(cantilever, 2, bladestab::EigenSolverKind::dense, 1e-8);
    const double beta_l[2] = {1.8751040687119612, 4.6940911329741746};
    const double closed_form[2] = {beta_l[0] * beta_l[0], beta_l[1] * beta_l[1]};
    bool ok = true;
    for (int k = 0; k < 2; ++k) {
      const double lambda = modes.solution.modes.at(k).lambda;
      const double error = std::abs(lambda / closed_form[k] - 1);
      std::printf("mode %d: Lambda = %.9f, closed form %.9f, relative error %.2e (estimate %.2e)\n", k + 1, lambda,
                  closed_form[k], error, modes.budget(k).total());
      ok = ok && error <= modes.budget(k).total() + 1e-12;
    }
    const bladestab::Scene paper = bladestab::parse_scene(text.str(), argv[1], {"model.terms=8"});
    const bladestab::StabilityAnswer answer = bladestab::analyse_stability(paper, {});
    std::printf("paper point: max|rho| = %.8f (estimate %.1e)\n", answer.floquet.max_abs_multiplier,
                answer.budget.total());
    ok = ok && answer.floquet.max_abs_multiplier > 1 + answer.budget.total();
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
