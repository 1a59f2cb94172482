// The work counts of the boundary equations' eigenproblems (boundaries.hpp): what --max-seconds
// and --max-memory are checked against before a harmonic level is solved.
#include "bladestab/stability/boundaries.hpp"

namespace bladestab {

double boundary_level_flops(int k, int dofs, bool in_theta) {
  double flops = 0;
  for (const int harmonics : {2 * k, 2 * k + 1}) {
    const double unknowns = (in_theta ? 2 : 1) * harmonics * dofs;
    flops += (3 * unknowns + 800) * unknowns * unknowns;
  }
  return flops;
}

double boundary_level_bytes(int k, int dofs, bool in_theta) {
  const double unknowns = (in_theta ? 2 : 1) * (2 * k + 1.0) * dofs;
  return 64 * unknowns * unknowns;
}

}  // namespace bladestab
