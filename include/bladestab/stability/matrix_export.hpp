#pragma once
// The periodic system that the Floquet analysis integrates, written for other programs (the
// benchmark's SciPy integrators, bench/): ẏ = (A₀ + φ(t) B) y with φ(t) = F(t) − F₀ and
// F(t) = Σ_{|m| ≤ M} F_m e^{imθt}, F_{−m} = conj F_m (periodic_system.hpp).
//
// Matrix Market files, written and read by Eigen's SparseExtra module (scipy.io.mmread reads
// them too), 17 significant digits, so every double comes back bit for bit:
//   <stem>.A0.mtx    A₀, real coordinate general (exact zeros are left out)
//   <stem>.B.mtx     B, likewise
//   <stem>.load.mtx  F_m for m = 0..M [N], complex array general (one column)
#include <string>

#include <Eigen/Dense>

#include "bladestab/stability/periodic_system.hpp"

namespace bladestab {

struct ExportedArrays {
  std::string A0, B, load;  // file names
};

// The files of `stem` (a path without extension).
ExportedArrays matrix_market_files(const std::string& stem);

// Writes the three files; InputError naming the file if one cannot be written.
ExportedArrays write_matrix_market(const PeriodicSystem& sys, const std::string& stem);
// The same into the given files (the program's temporaries, renamed into place with a manifest).
ExportedArrays write_matrix_market(const PeriodicSystem& sys, const ExportedArrays& files);

// Reads them back into A0, B and the load coefficients (the rest of the system is left empty);
// std::runtime_error if a file is missing or malformed.
PeriodicSystem read_matrix_market(const std::string& stem);

}  // namespace bladestab
