#pragma once
// The blade under a periodic tip load as a linear time-periodic (LTP) system ẏ = A(t) y
// (docs/theory.md §4), written in scaled modal coordinates of the unloaded (reduced) blade at speed Ω:
//
//   q = Φ η,  Φᵀ M Φ = I,  Φᵀ K(Ω) Φ = Λ = diag(ω_k²),  y = [D η; η̇],  D = diag(ω_k)
//
//   A(t) = A₀ + (F(t) − F₀) B,   A₀ = [[0, D], [−(Λ + F₀ Ĝ) D⁻¹, −Ĉ]],   B = [[0, 0], [−Ĝ D⁻¹, 0]]
//
// with Ĝ = Φᵀ G Φ and Ĉ = Φᵀ C Φ. Displacements and velocities then carry the same units, so the
// monodromy matrix is well conditioned. The system is built on a reduced model (reduction.hpp):
// by default the span of the loaded modes, which keeps the 46 kHz rotation modes and the Ritz
// basis's spurious top modes out of the time integration (docs/theory.md §6).
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/ltp/linear_periodic_system.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/blade/reduction.hpp"

namespace bladestab {

// The blade's LTP system, stated in modal form (`modal`: ω_k, Ĝ, Ĉ) and Hamiltonian when the blade
// is undamped, on `kept_modes` modes of a Ritz model of `all_modes` dofs.
struct PeriodicSystem : LinearPeriodicSystem {
  int kept_modes = 0, all_modes = 0;
};

PeriodicSystem periodic_system(const ReducedSystem& reduced, const LoadSeries& load);

// The flops of building the system of a Ritz model of `dofs` dofs (periodic_system below): its
// assembly and the whole model's static-limit check and reduction, about three dense symmetric-definite
// eigensolves (dsygvx, ≈ (8/3) n³ each for a few vectors). Measured 2.5–3 n³ at the CLI's dense rate
// (4e9 flops/s) on 300–720 dofs: an upper bound there.
inline double periodic_system_flops(double dofs) { return 8 * dofs * dofs * dofs; }

// The blade reduced by `reduction` for this load.
PeriodicSystem periodic_system(const BladeModel& model, double speed_rad_s, const Eigen::MatrixXd& damping,
                               const LoadSeries& load, const ReductionSpec& reduction = {});

// The same at the scene's speed with the scene's damping.
PeriodicSystem periodic_system(const BladeModel& model, const Scene& scene, const LoadSeries& load,
                               const ReductionSpec& reduction = {});

// Whether the true pulse train is analysed on the whole Ritz model `whole` (its system unreduced)
// rather than on an automatic reduction (`stability` and `crosscheck` alike): the train is
// integrated only through its contacts, so the whole model is cheap while a contact needs at most
// 4096 Magnus steps (h‖A‖ ≤ 2), and only the whole model resolves the pulse's high harmonics, on
// which the train's thin tongues depend (the paper blade with 5 pulses a revolution at F̄ = 5 is
// stable, max|ρ| = 1, where 3 vectors per load level show a tongue of 1.017 per period).
bool true_train_on_whole_model(const PeriodicSystem& whole, const PulseTrain& train);

// Modes per load level of an automatic reduction that holds every region of instability of order
// n ≤ max_order with θ ≤ theta_max (θ ≈ 2ω/n): the unloaded modes of `scene` at its speed with
// ω < max_order·θ_max — twice the highest ω such a region sits at, since the load lowers the
// frequencies it couples — and never fewer than two. Take the slowest speed of a range, where the
// modes are lowest.
int tongue_vectors(const BladeModel& model, const Scene& scene, double theta_max, int max_order);

}  // namespace bladestab
