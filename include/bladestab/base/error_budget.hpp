#pragma once
// The whole error of a result against the continuum model of its scene, split by where it comes
// from. Every Floquet, boundary and frequency result carries one. Each part is an estimate of
// |computed − continuum| caused by one approximation, in the result's own measure (absolute on
// max|ρ| for Floquet multipliers, relative on θ or F_max for boundaries, relative on a frequency):
//
//   basis      the Ritz basis: this many terms against a richer basis
//   reduction  the reduced (or modally truncated) model against the full Ritz model
//   load       the load's series against the scene's true load (0 when the scene's load *is* the
//              series, as with the cosine approximation (42))
//   method     steps, harmonics, eigensolver rounding
//
// A part that could not be bounded is named in `unbounded`, and outputs say so.
#include <algorithm>
#include <string>
#include <vector>

namespace bladestab {

struct ErrorBudget {
  double basis = 0, reduction = 0, load = 0, method = 0;
  std::vector<std::string> unbounded;  // e.g. "load: the impulse has no Fourier series"

  double total() const { return basis + reduction + load + method; }
  // Each part raised to `other`'s where that is larger; its unbounded parts added, each once (the
  // worst budget over many results).
  void raise_to(const ErrorBudget& other) {
    basis = std::max(basis, other.basis);
    reduction = std::max(reduction, other.reduction);
    load = std::max(load, other.load);
    method = std::max(method, other.method);
    for (const std::string& u : other.unbounded) {
      if (std::find(unbounded.begin(), unbounded.end(), u) == unbounded.end()) unbounded.push_back(u);
    }
  }
};

}  // namespace bladestab
