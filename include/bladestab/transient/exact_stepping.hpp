#pragma once
// Exact stepping of the blade in load.mode = "force" (docs/theory.md §5.8): the equations of
// transient.hpp are linear there, and between contacts their state matrix is constant.
//
// Coordinates: the undamped modes of the whole Ritz model at speed Ω, K(Ω) φ = ω² M φ with
// Φᵀ M Φ = I (or those of a reduced model, reduction.hpp: the modes of Vᵀ K(Ω) V in the span of
// its basis V), about the rotating equilibrium f_eq, scaled so that ½|y|² is the vibration energy:
//
//   f = f_eq + Φ D⁻¹ y₁,  ḟ = Φ y₂,  D = diag(ω_k),  z = [y₁; y₂; 1],
//
//   ż = (A_free + F(t) B) z,   A_free = [[0, D, 0], [−D, −Ĉ, 0], [0, 0, 0]],
//                              B = [[0, 0, 0], [−Ĝ D⁻¹, 0, b], [0, 0, 0]],
//
// Ĉ = Φᵀ(C_D + C_G)Φ, Ĝ = Φᵀ G Φ, b = Φᵀ(p_u − G f_eq + μ cos β p_v): the tip load's axial push,
// its geometric stiffness at the equilibrium and the friction, all proportional to F. The
// friction is −μ|F| cos β · tanh(v_rel/ε) (transient.hpp) with tanh = 1: the tip slides past the
// casing at v_rel ≈ ΩR, so the sign never changes; the stepper checks v_rel ≥ 20ε (tanh = 1 to
// the unit roundoff) at every sample in contact and refuses otherwise.
//
// Free flight (F = 0) is stepped by e^{A_free h}, one exponential per distinct interval h, exact
// to rounding. A contact piece is integrated by the sixth-order Magnus propagator (ltp/magnus.hpp)
// with its steps doubled until the propagator has converged (ltp/step_doubling.hpp), once per
// distinct piece: an endless train reuses the propagators of its first pulse. Where the pulse is
// even about the middle c of its contact and the blade undamped, the contact reverses in time
// (ltp/reversing_symmetry.hpp) and only its first half is integrated: a piece past c is
// R P(2c − a, 2c − b)⁻¹ R of its mirror image (mirrored_contact.cpp).
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"
#include "bladestab/stability/periodic_load.hpp"

namespace bladestab {

struct ExactSteppingStatistics {
  int contact_pieces = 0;        // distinct contact pieces integrated
  long magnus_steps = 0;         // Magnus steps over every level of every ladder
  int free_exponentials = 0;     // distinct free-flight intervals
  long intervals = 0;            // intervals stepped
  double contact_error = 0;      // largest step-doubling bound of a piece propagator (relative)
};

class ExactStepper {
public:
  // `tolerance` bounds each contact piece's propagator, relative; `reduction`: on that reduced model
  // (for the load's range 0 … −F_max) instead of the whole one; `piece_work_flops`: what each
  // piece's step doubling may take (WorkLimitError past it). InputError where the pulses have no
  // frequency.
  ExactStepper(const BladeModel& model, const Scene& scene, double tolerance,
               const std::optional<ReductionSpec>& reduction = std::nullopt,
               double piece_work_flops = std::numeric_limits<double>::infinity());

  // Integrates the contact pieces of the intervals [t_k, t_{k+1}] of `landings` (absolute times)
  // that are not yet known, on up to `threads` threads (the pieces are independent; each comes out
  // the same on any number of threads). `progress` (optional) hears (pieces done, pieces to do)
  // after each piece, one call at a time; what it throws stops the pieces not yet started.
  void prepare(const std::vector<double>& landings, int threads,
               const std::function<void(int, int)>& progress = {});

  // z over [a, b] inside one pulse period, with no pulse edge inside (a contact piece or free
  // flight); `work` gains the damping's work in free flight (Van Loan's integral, exact). True
  // for a contact piece.
  bool step(double a, double b, Eigen::VectorXd& z, double& work);
  // z over h of free flight (F = 0) whatever the pulses do; `work` gains the damping's work.
  void free_flight(double h, Eigen::VectorXd& z, double& work);
  // The free-flight state matrix on y (A_free without its constant row and column).
  Eigen::MatrixXd free_matrix() const { return A_free_.topLeftCorner(dofs_, dofs_); }

  // [f; ḟ] of z, and z of [f; ḟ] (its M-orthogonal projection on the modes kept).
  Eigen::VectorXd physical(const Eigen::VectorXd& z) const;
  Eigen::VectorXd modal(const Eigen::VectorXd& x) const;

  // The tip's speed past the casing, ΩR + c v̇(L) (c = model.in_plane_share: cos β, or 1 with two planes), at the state z.
  double sliding_speed(const Eigen::VectorXd& z) const;
  // The pulse train; where its profile has a kink inside the contact (triangular: at t_c/2).
  const PulseTrain& pulses() const { return pulses_; }
  int modes() const { return n_; }
  const Eigen::MatrixXd& shapes() const { return Phi_; }        // Φ
  const Eigen::VectorXd& frequencies() const { return omega_; } // ω_k
  const Eigen::VectorXd& equilibrium() const { return equilibrium_; }  // f_eq
  std::vector<double> kinks() const;
  const ExactSteppingStatistics& statistics() const { return stats_; }

private:
  struct Piece {
    double start, end;  // offsets in the pulse, or (0, h) for free flight
    Eigen::MatrixXd map, work;
  };
  // The contact piece [start, end] of a pulse (offsets), from the cache or integrated now.
  const Piece& contact_piece(double start, double end);
  // A contact piece's propagator by step doubling, with its Magnus steps and error bound; touches
  // no member (prepare runs it side by side).
  struct Integrated {
    Piece piece;
    long steps = 0;
    double error = 0;
  };
  Integrated integrate_contact(double start, double end) const;
  // The same for ż = (A + F(t) B) z whose last `forcing` columns of B are the forcing (their
  // constants' rows and columns are zero in A).
  Integrated integrate(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int forcing, double start,
                       double end) const;
  // integrate over each of `intervals` (offsets), on up to `threads` threads; `progress` hears
  // (done, all) after each, one call at a time.
  std::vector<Integrated> integrate_side_by_side(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int forcing,
                                                 const std::vector<std::pair<double, double>>& intervals, int threads,
                                                 const std::function<void(int, int)>& progress) const;
  // The contact system with its forcing column split in two, the part on coordinates where the
  // reversing signature is −1 and the part where it is +1, and the signature that reverses it
  // (mirrored_contact.cpp); none where the pulse is not even or the blade damped.
  struct Mirror {
    Eigen::MatrixXd A, B;
    Eigen::VectorXd signature;
  };
  static std::optional<Mirror> contact_mirror(const Eigen::MatrixXd& A_free, const Eigen::MatrixXd& B,
                                              const PulseTrain& pulses, bool damped);
  // The contact pieces [start, end] (offsets) from their mirror images in the first half of the
  // contact, its segments integrated on up to `threads` threads.
  std::vector<Integrated> mirrored_pieces(const std::vector<std::pair<double, double>>& pieces, int threads,
                                          const std::function<void(int, int)>& progress) const;
  // The cached contact piece [start, end], if any.
  const Piece* cached_contact(double start, double end) const;
  // The contact piece offsets of [a, b] (absolute), if it lies in a contact.
  std::optional<std::pair<double, double>> contact_offsets(double a, double b) const;
  const Piece& keep(Integrated integrated);
  const Piece& free_piece(double h);

  int n_, dofs_;  // modes kept, and 2n_
  PulseTrain pulses_;
  double tolerance_, piece_work_flops_, in_plane_share_, mu_in_plane_, rim_speed_;
  bool damped_;
  Eigen::MatrixXd Phi_, PhiT_M_, A_free_, B_, Q_damping_;
  Eigen::VectorXd omega_, equilibrium_;
  Eigen::RowVectorXd tip_lateral_;
  std::vector<Piece> contact_, free_;
  std::optional<Mirror> mirror_;
  ExactSteppingStatistics stats_;
};

}  // namespace bladestab
