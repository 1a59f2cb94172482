#include "bladestab/mode_convergence.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bladestab/damping.hpp"
#include "bladestab/input_error.hpp"

namespace bladestab {
namespace {

constexpr int max_terms = 200;

ModalSolution modes_of(const BladeModel& model, const Scene& scene, int count, EigenSolverKind solver) {
  const double speed = scene.operation.speed_rad_s;
  return solve_modes(model, system_at(model, speed, damping_matrix(model, scene.damping, speed)), speed, count,
                     solver);
}

std::vector<double> compare(const ModalSolution& base, const ModalSolution& reference) {
  std::vector<double> error;
  int rank_in_family[3] = {0, 0, 0};
  for (const Mode& m : base.modes) {
    const int rank = rank_in_family[static_cast<int>(m.family)]++;
    int seen = 0;
    double e = 1;  // no counterpart: nothing is known
    for (const Mode& r : reference.modes) {
      if (r.family != m.family) continue;
      if (seen++ == rank) {
        e = r.frequency_hz > 0 ? std::abs(m.frequency_hz - r.frequency_hz) / r.frequency_hz
                               : std::abs(m.eigenvalue - r.eigenvalue) / std::max(std::abs(r.eigenvalue), 1e-300);
        break;
      }
    }
    error.push_back(e);
  }
  return error;
}

}  // namespace

double ConvergedModes::max_relative_error() const {
  return relative_error.empty() ? 0 : *std::max_element(relative_error.begin(), relative_error.end());
}

int reference_terms(BasisKind basis, int terms) {
  const int richer = basis == BasisKind::legendre ? terms + std::max(4, terms / 2) : 2 * terms;
  return std::min(richer, max_terms + 40);
}

ConvergedModes modes_with_error_estimate(const Scene& scene, int count, EigenSolverKind solver,
                                         std::optional<double> tolerance) {
  ModelSpec spec = scene.model;
  while (true) {
    BladeModel model = assemble_model(scene.blade, spec);
    ModalSolution solution = modes_of(model, scene, count, solver);
    ModelSpec richer = spec;
    richer.terms = reference_terms(spec.basis, spec.terms);
    // The richer model needs more modes so that every family is represented to the same rank.
    const ModalSolution reference = modes_of(assemble_model(scene.blade, richer), scene, 0, EigenSolverKind::dense);
    ConvergedModes result{std::move(model), std::move(solution), richer.terms, {}};
    result.relative_error = compare(result.solution, reference);
    if (!tolerance || result.max_relative_error() <= *tolerance) return result;
    if (spec.terms >= max_terms) {
      throw InputError(fmt::format("--tolerance {}: not met with {} terms per field (estimated error {:.2g}); "
                                   "use the legendre basis or a looser tolerance",
                                   *tolerance, spec.terms, result.max_relative_error()));
    }
    spec.terms = std::min(max_terms, spec.basis == BasisKind::legendre ? spec.terms + 2 : spec.terms * 2);
  }
}

}  // namespace bladestab
