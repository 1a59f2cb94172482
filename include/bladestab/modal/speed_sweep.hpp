#pragma once
// The lowest modes of one Ritz model at many rotor speeds: the work of a Campbell diagram.
//
// dense    every speed solved whole by solve_modes (any damping, any eigensolver); no error
//          against the Ritz model beyond the eigensolver's rounding.
//
// reduced  the undamped blade. Its gyroscopic problem (λ²M + λΩC_G1 + K(Ω)) q = 0 is real
//          symmetric in disguise: C_G1 couples only v with u, and M, K never couple u with θ or v,
//          so with q = D x, D = diag(1 on θ and v, i on u), and λ = iω it reads
//
//              Q(ω) x = (K(Ω) − ω Ĉ(Ω) − ω² M) x = 0,   Ĉ(Ω) = Ω J C_G1,  J = diag(1, 1, −1),
//
//          a hyperbolic quadratic eigenproblem (M > 0, K > 0) with real x whose n positive
//          eigenvalues are the natural frequencies ω. One basis V (Vᵀ M V = I) holds the whole
//          model's exact modes at a few sample speeds; at every speed the small problem Vᵀ Q(ω) V
//          is solved densely, and each Ritz frequency θ_j is bounded against the whole model:
//            - from above: for a hyperbolic problem Rayleigh–Ritz gives θ_j ≥ ω_j (Duffin's
//              min-max characterization, the Ritz basis being any subspace);
//            - from below: Kato–Temple on the Hermitian linearization in μ = 1/ω, where the low
//              modes are the extreme ones and the residual norm weighs the stiff components by
//              1/ω:  ε_j = ‖L_K⁻¹ Q(θ_j) x_j‖ / (θ_j (xⱼᵀK xⱼ + θ_j² xⱼᵀM xⱼ)^½)  (K = L_K L_Kᵀ),
//              μ_j − 1/θ_j ≤ ε_j² / (1/θ_j − a_j), a_j the top of the next mode's interval
//              [1/θ_{j+1} ± ε_{j+1}];
//            - no mode missed: the number of ω below σ is the number of negative eigenvalues of
//              Q(σ) (Sylvester's inertia, from an LDLᵀ factorization); it must equal the number
//              of Ritz intervals below σ, which must not overlap.
//          The relative bound (1/θ − μ)θ on each frequency is the reduction's part of its error.
//          Where it is above the wanted one, that speed's exact modes join the basis (so the
//          bound there becomes rounding) and the speeds that failed are solved again.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/modal/modes.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

// The `count` lowest modes of one model at one speed, by frequency.
struct SpeedModes {
  double speed_rad_s = 0;
  std::vector<double> frequency_hz;  // |Im λ| / 2π (0 for an overdamped pair)
  std::vector<double> natural_hz;    // |λ| / 2π, the same as frequency_hz without damping
  std::vector<double> damping_ratio;
  std::vector<double> bound;       // relative bound on |f − f_Ritz model| / f (0 when solved whole;
                                   // empty when not asked for)
  std::vector<double> rounding;    // relative rounding of f (frequency_rounding), with the bound
  std::vector<ModeFamily> family;
  Eigen::MatrixXcd shapes;         // unit columns in the sweep's coordinates: MAC(a, b) = |aᴴ b|²
};

// The reduced sweep cannot serve this model at some speed (its stiffness is not positive
// definite there); the dense sweep can.
struct ReducedSweepUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws ReducedSweepUnavailable where some of `modes`' bounds against the whole model are infinite.
void require_certified(const SpeedModes& modes);

class SpeedSweep {
public:
  virtual ~SpeedSweep() = default;
  // Modes with their bounds at every speed. The reduced sweep enriches its basis until every
  // bound meets the wanted one; all shapes returned share the sweep's coordinates after the call.
  // `progress(done, total)` after each speed of the first pass.
  virtual std::vector<SpeedModes> solve(const std::vector<double>& speeds,
                                        const std::function<void(int, int)>& progress = {}) = 0;
  // Modes at one more speed (bounds only when `certify`), in the current coordinates.
  virtual SpeedModes at(double speed_rad_s, bool certify) = 0;
  // The whole model's frequency [Hz] of the mode most like `shape` at this speed: a solve that
  // shares nothing with the reduction (for the reduced sweep; the dense one is whole already).
  virtual double whole_frequency(double speed_rad_s, const Eigen::VectorXcd& shape) = 0;
  // Coordinates c stand for the dofs q = dofs() · c, and ⟨dofs() · c, q⟩_M = cᴴ · metric() · q.
  virtual Eigen::MatrixXd dofs() const = 0;
  virtual Eigen::MatrixXd metric() const = 0;
  virtual EigenSolverKind solver() const = 0;
  virtual bool reduced() const = 0;
  virtual int vectors() const = 0;                   // size of the reduced basis (dofs when dense)
  virtual std::vector<double> sample_speeds() const = 0;  // where the basis was taken (none when dense)
};

// Whether the reduced sweep applies: no damping, and the coupling pattern above.
bool reduced_sweep_applies(const BladeModel& model, const DampingSpec& damping);

// The reduced sweep where it applies and `solver` is automatic, else the dense one. The reduced
// sweep takes its first samples at `speed_lo`, `speed_hi` and halfway, and bounds every
// frequency to `reduction_tolerance` (relative). The model must outlive the sweep.
std::unique_ptr<SpeedSweep> make_speed_sweep(const BladeModel& model, const DampingSpec& damping, int count,
                                             EigenSolverKind solver, double reduction_tolerance, double speed_lo,
                                             double speed_hi);

// The dense sweep regardless (the reference the reduced one is tested against).
std::unique_ptr<SpeedSweep> make_dense_speed_sweep(const BladeModel& model, const DampingSpec& damping, int count,
                                                   EigenSolverKind solver);

}  // namespace bladestab
