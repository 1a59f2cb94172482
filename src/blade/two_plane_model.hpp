#pragma once
// The Ritz model of a tabled blade bending in two planes (docs/theory.md §9): internal to blade/.
#include "bladestab/blade/model.hpp"

namespace bladestab {

// The matrices of the blade with a section table (BladeSpec::two_planes) in the model `spec`, into
// `model` (its blade properties already set; sizes from dof_layout(spec, true)).
void assemble_two_planes(BladeModel& model, const BladeSpec& blade, const ModelSpec& spec);

// The kinetic-energy families of the assembled (symmetrized) model: rotation, flap, edge, axial.
void add_two_plane_families(BladeModel& model, const BladeSpec& blade);

// F_cr of a tabled blade: its Euler–Bernoulli buckling load at rest under a compressive tip force,
// the least F with det(K_E − F G) = 0 over both planes (docs/theory.md §9), in a 24-term Legendre
// basis per plane (independent of the scene's model).
double tabled_buckling_load(const BladeSpec& blade);

}  // namespace bladestab
