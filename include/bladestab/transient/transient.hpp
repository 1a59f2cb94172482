#pragma once
// Time-domain response of the rotating blade to its tip rub (docs/theory.md §5, (47)–(52)):
//
//   M f̈ + C ḟ + (K(Ω) + F(t) G) f = Ω² P_cf + F_s p_u + F(t) p_u + R(t) p_v
//
// (F_s: a static tip force, operation.tip_compression_over_fcr, carried by the model in K(Ω) and
// in its steady load)
// with the tip load F ≤ 0 on the tip (axially, p_u = W_i(L), and through the geometric stiffness
// G): in load.mode = "force" the true pulse train F(t), in "clearance" the casing's penalty force
// F(t, f) (casing_contact.hpp), landing on every contact closing and opening. Coulomb friction R = −μ|F| cos β · tanh(v_rel/ε) on the lateral
// tip, v_rel = ΩR + cos β · v̇(L) the tip's speed past the casing (regularized sign, ε = 1 mm/s:
// the tip moves at ΩR ≈ 450 m/s, so the friction never sticks in practice). Integrated in first-
// order form x = [f; ḟ] by RKF45, adaptive or with the paper's fixed step (54), landing on every
// pulse edge. With the follower correction (docs/theory.md §5) the load turns with the tip slope ψ = v'(L):
// F cos ψ along the axis (and in the geometric stiffness), −F sin ψ on the lateral tip.
#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/stability/periodic_load.hpp"
#include "bladestab/transient/response_analysis.hpp"
#include "bladestab/ltp/rkf45.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/transient/exact_stepping.hpp"

namespace bladestab {

struct FixedStep {
  double step_s = 0;
  int steps_per_period = 8;
  double parasitic_growth = 1;  // |R(iω_maxΔt)|^steps: the stiffest mode's spurious amplification over the run
};

// How the transient is integrated: `fast` steps free flight exactly, each pulse by Magnus (force
// mode, exact_stepping.hpp) or each casing contact by RKF78 (clearance mode), without the follower
// correction; else it falls back to `rkf45` (the result says so), the paper's integrator above.
enum class TransientMethod { fast, rkf45 };

struct TransientOptions {
  TransientMethod method = TransientMethod::fast;
  // fast: check the history against RKF45 at rtol 1e-10 through the first contact and a stretch of
  // free flight after it (a NumericalError when they differ by more than the stated error).
  bool self_check = true;
  // fast: on this reduced model (reduction.hpp) instead of the whole Ritz model; without the
  // self-check (RKF45 runs the whole model).
  std::optional<ReductionSpec> reduction;
  int threads = 1;  // fast: the contact pieces integrated side by side
  double revolutions = 10;
  bool adaptive = true;
  int steps_per_period = 0;  // fixed mode: steps per period of the stiffest mode (≥ 8, (54)); 0 = choose
  double tolerance = 1e-8;   // rtol of the adaptive steps
  // fast: each contact piece's propagator, relative (its step doubling; exact_stepping.hpp; 128
  // Magnus steps per half contact of the scene as shipped at 1e-7); clearance: RKF78's rtol.
  double contact_tolerance = 1e-7;
  int samples_per_revolution = 200;
  double friction_velocity = 1e-3;              // ε of the regularized sign [m/s]
  // The small-deflection range: the run stops at the first sample whose lateral tip deflection
  // exceeds this fraction of the length (or whose axial tip deflection changes by more than
  // TransientChecks::max_axial_strain of it). Infinite: never stop (the linear equations' own
  // response, for growth rates).
  double max_lateral_over_length = 0.1;
  // fast, force mode: hold the friction's direction (tanh = 1) whatever the sliding speed: the linear
  // equations the Floquet multipliers belong to, for growth rates with max_lateral_over_length
  // infinite (crosscheck); else a contact state sliding slower than 20 ε is refused.
  bool hold_friction_direction = false;
  bool follower = false;  // the tip load follows the tip slope ψ = v'(L): F cos ψ axially, −F sin ψ laterally
  std::optional<Eigen::VectorXd> initial_state; // x = [f; ḟ]; default: the steady rotating equilibrium
  std::function<void(int, int)> progress;       // (revolutions done, total)
  // fast, force mode: (contact pieces integrated, their number) before the revolutions start, one
  // call at a time from the thread that finished the piece; what it throws stops the run.
  std::function<void(int, int)> contact_progress;
  // fast: the work each contact piece's step doubling may take, in eigensolver flops
  // (magnus_step_work); a piece not converged where its next level would pass it throws
  // WorkLimitError.
  double piece_work_flops = std::numeric_limits<double>::infinity();
};

struct TransientSample {
  double time_s, revolutions;
  double tip_lateral_m, tip_axial_m, tip_lateral_velocity_m_s, tip_axial_velocity_m_s;
  double axial_force_n, friction_force_n;  // the tip load F (an output in clearance mode) and μ|F| cos β
  double casing_overlap_m;  // clearance mode: g, how far the tip has passed the casing (> 0 in contact); else 0
  double strain_energy_j;   // ½ fᵀ K_E f: bending, shear and axial strain (55), (56) (K_E: elastic_stiffness())
  double kinetic_energy_j;  // ½ ḟᵀ M ḟ (57), (58)
  double total_energy_j;    // ½ ḟᵀ M ḟ + ½ fᵀ K(Ω) f − P_steadyᵀ f (+ ½k g₊² in clearance mode), conserved
                            // without pulses, damping and casing motion
  double work_j;            // W: the work of the tip load (the casing's too), the friction and the damping since
                            // the start, ∫ ḟᵀ(F_ax (p_u − G f) + F_lat p_v − D ḟ) dt, integrated with the state
  double energy_balance_error_j;  // E(t) − E(0) − W(t), E the total energy without the casing's ½k g₊²:
                                  // zero for the exact solution
  // The tip loads as the equations of motion apply them: along the span (also the tension of the
  // geometric stiffness), F, or F cos ψ with the follower correction; laterally the friction, and
  // with the follower correction −F sin ψ besides (ψ = v'(L) at the sample).
  double applied_axial_n, applied_lateral_n;
};

// Clearance mode: what the casing did, from the exact contact events.
struct ContactSummary {
  double stiffness_n_m = 0;     // the penalty k
  int closures = 0;             // contacts made
  double contact_time_s = 0;    // total time in contact
  double peak_force_n = 0;      // max k g (at the deepest overlap, ġ = 0)
  double max_overlap_m = 0;     // the wall's largest give, max g
};

// Where and why a run stopped before its end: the response left the small-deflection range.
struct TransientStop {
  double revolution = 0;
  std::string reason;
};

// The fast method's history against an independent integration at a much tighter tolerance over
// [0, until] (RKF78 of Boost.Odeint in force mode, RKF45 in clearance mode, whose contacts are
// RKF78's): the state at `until` in the energy norm, relative to the largest vibration
// (‖x − x_eq‖ in that norm) seen.
struct SelfCheck {
  double until_revolutions = 0;
  std::string reference;  // "rkf78" or "rkf45"
  double reference_tolerance = 0;
  double difference = 0, allowed = 0;
  double reference_part = 0;  // of `allowed`, the reference's: 10 rtol of the whole state (f_eq included)
  // `difference` is relative to the vibration, or, where there is none above the reference's
  // resolution (a tip at rest against the casing), to that resolution: rtol of the whole state.
  bool relative_to_resolution = false;
};

struct TransientResult {
  TransientMethod method = TransientMethod::rkf45;  // the one used
  std::string fallback;     // why rkf45 ran where fast was asked for; empty otherwise
  std::vector<TransientSample> samples;
  std::optional<TransientStop> stopped;
  ExactSteppingStatistics exact;       // fast
  std::optional<SelfCheck> self_check; // fast, when asked for
  Eigen::VectorXd final_state;         // [f; ḟ] at the last sample
  StepStatistics steps;
  FixedStep fixed;          // the fixed step, or in adaptive mode the cap on the step (same rule, n chosen)
  double static_tip_axial_m = 0;  // the rotating equilibrium's tip stretch
  double initial_vibration_energy_j = 0;  // E(0) − E at the rotating equilibrium
  // |P_steadyᵀ f_eq|, the size of the terms E sums at the rotating equilibrium (their rounding, a
  // few ε of it, is in every E(t) whatever the vibration)
  double energy_terms_j = 0;
  std::optional<ContactSummary> contact;  // clearance mode
  // ‖x((k+1)T) − x(kT)‖ for each whole revolution k, in the energy norm √(½Δfᵀ K(Ω) Δf + ½Δḟᵀ M Δḟ):
  // states at the ends of the integration, not interpolated, so independent of the output sampling.
  std::vector<double> revolution_change;
  // fast, force mode: the natural logarithms of the last resolved revolution_change carried on past
  // the run's end or stop (continue_change in growth_continuation.cpp) for growth_continuation
  // revolutions, to fit the growth on (a run may be too short for the other multipliers to fade).
  std::vector<double> continued_log_change;
  GrowthFit growth;  // of revolution_change (or continued_log_change): the growth per revolution, when meaningful
};

// Revolutions a fast force-mode run's last revolution change is carried on for its growth fit (a
// power iteration with matrix–vector products: ~20 ms at 16 terms): the other multipliers' share
// fades like (|ρ₂|/max|ρ|)^k, by e^38 where max|ρ| is 0.5 % above |ρ₂|.
constexpr int growth_continuation = 7680;
// Which of a run's revolution changes, taken in order, are resolved: one below 1e-12 of the largest
// before it is the difference of two states that agree to their rounding (a decaying change ends
// at exactly 0).
class ResolvedChanges {
public:
  // The next change's norm; true where it is resolved.
  bool add(double change) {
    largest_ = std::max(largest_, change);
    return change > 1e-12 * largest_;
  }

private:
  double largest_ = 0;
};

// The steady rotating equilibrium: K(Ω) f = Ω² P_cf + F_s p_u (steady_load(): a static tip force F_s
// included), ḟ = 0.
Eigen::VectorXd rotating_equilibrium(const BladeModel& model, double speed_rad_s);

// The fixed step (54): Δt = (1/n)(2π/ω_max), ω_max the stiffest mode of M f̈ + K f = 0, n ≥ 8 steps
// per its period (the paper's rule is Δt ≤ (1/8)(2π/ω_max)). RKF45 is weakly unstable on the
// imaginary axis (rkf45_stability_function), so a fixed step amplifies that undamped mode by
// |R(iω_maxΔt)| per step: ×1e4 over 5 revolutions of the paper's blade at n = 8. n = 0 picks the
// smallest n ≥ 8 that keeps this parasitic growth over `duration_s` below 1 %; that step also caps
// the adaptive steps.
FixedStep choose_fixed_step(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, double duration_s,
                            int steps_per_period = 0);

// The step of a run of `duration_s` as run_transient takes it: choose_fixed_step on the model's
// stiffest mode, with the casing's penalty wall in contact in clearance mode; the cap of the
// adaptive steps (options.adaptive) or the fixed step. Known before the run, for its cost.
FixedStep transient_step(const BladeModel& model, const Scene& scene, const TransientOptions& options,
                         double duration_s);

// Why the energy balance checks nothing in this run, or "": the fast method in force mode balances
// only its free flight (in contact the work is the energy's change), and a run in contact
// throughout has none.
std::string energy_balance_unchecked(const TransientResult& r);

TransientResult run_transient(const BladeModel& model, const Scene& scene, const TransientOptions& options);

}  // namespace bladestab
