// The transient in clearance mode by exact stepping (docs/theory.md §5.9). Between contacts the
// blade flies free: the equations are linear with a constant state matrix, stepped exactly as in
// force mode (exact_stepping.hpp). In contact the casing's penalty force −k g₊ (casing_contact.hpp)
// is nonlinear in f (g holds −½fᵀGf and acts through p_u − G f), so a contact is integrated by
// Boost.Odeint's Runge–Kutta–Fehlberg 7(8) on the whole equations (transient_system.hpp), from the
// closing to the opening. The events: a closing (g rising through 0) on the exact free flight, by
// halving cells the Lipschitz bound of g cannot clear and TOMS 748 in the first that changes sign;
// an opening (g falling through 0) and the deepest overlap (ġ = 0) inside a step, by TOMS 748 on
// steps of the same formula from the step's start.
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <optional>

#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>
#include <fmt/format.h>

#include "bladestab/base/numerical_error.hpp"
#include "bladestab/blade/damping.hpp"
#include "bladestab/transient/casing_contact.hpp"
#include "bladestab/transient/exact_stepping.hpp"
#include "bladestab/transient/transient_system.hpp"
#include "transient_parts.hpp"

namespace bladestab::detail {
namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::vector<double>;

// TOMS 748 on [a, b] with g(a) and g(b) of opposite signs (or one zero): the end of the final
// bracket on b's side, so the state there is on the far side of the event.
double event_time(const std::function<double(double)>& g, double a, double b, double ga, double gb) {
  std::uintmax_t iterations = 100;
  const auto close_enough = [](double lo, double hi) { return hi - lo <= 4 * std::numeric_limits<double>::epsilon() * std::abs(hi); };
  if (gb == 0) return b;
  if (ga == 0) return a;
  return boost::math::tools::toms748_solve(g, a, b, ga, gb, close_enough, iterations).second;
}

// The free flight's state y(τ) = Re(V e^{Λτ} V⁻¹ y₀) from the eigenvectors of A_free, at any τ for
// the price of a matrix–vector product: where the events are looked for (the state itself is
// stepped by the exponential).
class FreeOrbit {
public:
  explicit FreeOrbit(const Eigen::MatrixXd& A) {
    const Eigen::EigenSolver<Eigen::MatrixXd> eigen(A);
    V_ = eigen.eigenvectors(), lambda_ = eigen.eigenvalues();
    lu_.compute(V_);
    const Eigen::MatrixXd back = (V_ * lambda_.asDiagonal() * lu_.inverse()).real();
    if (eigen.info() != Eigen::Success || !((back - A).norm() <= 1e-9 * A.norm())) {
      throw NumericalError("exact stepping: the free-flight matrix has no well-conditioned eigenvectors to locate the "
                           "casing's contacts on; use the rkf45 method");
    }
  }
  void start(const Eigen::VectorXd& y) { w_ = lu_.solve(y.cast<std::complex<double>>()); }
  Eigen::VectorXd at(double tau) const {
    return (V_ * (lambda_.array() * tau).exp().matrix().cwiseProduct(w_)).real();
  }

private:
  Eigen::MatrixXcd V_;
  Eigen::VectorXcd lambda_, w_;
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu_;
};

// Where the casing's closings are looked for in free flight. From a start with vibration energy
// ½r² (|y| never grows in free flight: the damping takes energy, the Coriolis forces none), g is
// L-Lipschitz with L = a r + h r² + d max|ṡ|: a = ‖Φᵀ(p_u − G f_eq)‖ bounds the tip's axial speed,
// h = ‖D⁻¹ΦᵀGΦ‖_F the bending shortening's rate, d max|ṡ| the wall's speed. A cell [t₀, t₁] with
// ½(g₀ + g₁) + ½L(t₁ − t₀) ≤ 0 holds no closing (g would have to pass 0): a tip at rest against a
// still wall (clearance 0, no distortion: g = 0, L = 0) clears at once, not at every resolution step.
class ClosingSearch {
public:
  ClosingSearch(const ExactStepper& stepper, const CasingContact& casing, const BladeModel& model, double resolution)
      : stepper_(stepper), casing_(casing), orbit_(stepper.free_matrix()), resolution_(resolution) {
    const Eigen::MatrixXd& Phi = stepper.shapes();
    speed_bound_ = (Phi.transpose() * (model.tip_axial.transpose() - model.G * stepper.equilibrium())).norm();
    shortening_bound_ = (stepper.frequencies().cwiseInverse().asDiagonal() * Phi.transpose() * model.G * Phi).norm();
    wall_speed_ = casing.intrusion_m * casing.shape.max_force_rate();
  }

  // The earliest closing in (a, b] of the free flight from z at a, if any.
  std::optional<double> earliest(double a, double b, const Eigen::VectorXd& z) {
    orbit_.start(z.head(2 * stepper_.modes()));
    a_ = a;
    const double r = z.head(2 * stepper_.modes()).norm();
    lipschitz_ = speed_bound_ * r + shortening_bound_ * r * r + wall_speed_;
    return search(a, std::min(0.0, overlap(a)), b, overlap(b));
  }

private:
  double overlap(double t) const {
    Eigen::VectorXd z(2 * stepper_.modes() + 1);
    z << orbit_.at(t - a_), 1.0;
    const Eigen::VectorXd x = stepper_.physical(z);
    return casing_.overlap(t, x.head(x.size() / 2));
  }
  // Cells in time order, halved until cleared or as short as the resolution (as fine as RKF45's
  // steps look: only a touch shallower than ½L·resolution can pass between two looks).
  std::optional<double> search(double a, double ga, double b, double gb) const {
    if (0.5 * (ga + gb) + 0.5 * lipschitz_ * (b - a) <= 0) return std::nullopt;
    if (b - a <= resolution_) {
      if (!(ga <= 0 && gb > 0)) return std::nullopt;
      return event_time([this](double t) { return overlap(t); }, a, b, ga, gb);
    }
    const double m = 0.5 * (a + b), gm = overlap(m);
    if (std::optional<double> left = search(a, ga, m, gm)) return left;
    return search(m, gm, b, gb);
  }

  const ExactStepper& stepper_;
  const CasingContact& casing_;
  FreeOrbit orbit_;
  double resolution_, speed_bound_ = 0, shortening_bound_ = 0, wall_speed_ = 0, lipschitz_ = 0, a_ = 0;
};

// A contact, integrated by RKF78 on the whole equations: to the next landing or to the opening,
// with the deepest overlap and the contact time kept in the summary.
class ContactStepper {
public:
  ContactStepper(const TransientSystem& system, double rtol, double first_step, ContactSummary& summary)
      : system_(system), casing_(*system.casing()), n_(system.dofs()),
        stepper_(odeint::make_controlled(1e-6 * rtol, rtol, odeint::runge_kutta_fehlberg78<OdeState>())),
        dt_(first_step), summary_(summary) {}

  void close(double t) { ++summary_.closures, started_ = t, ++statistics_.event_landings; }
  void open(double t) { summary_.contact_time_s += t - started_, ++statistics_.event_landings; }

  // x from t toward `until`; true where the contact opened (t then the opening).
  bool advance(double& t, double until, Eigen::VectorXd& x) {
    OdeState s(x.data(), x.data() + x.size());
    bool opened = false;
    while (t < until && !opened) {
      const OdeState before = s;
      const double t_before = t;
      const bool landing = until - t <= dt_;
      double step = landing ? until - t : dt_;
      if (stepper_.try_step(rhs(), s, t, step) != odeint::success) {  // t += step on success; step: the next
        ++statistics_.rejected, dt_ = step;
        if (!(dt_ > 1e-16 * until)) throw NumericalError(fmt::format("a casing contact's steps underflowed at t = {:.6g} s", t));
        continue;
      }
      ++statistics_.accepted;
      if (landing) t = until;
      dt_ = landing ? std::max(dt_, step) : step;  // a step cut short to land keeps the step it had
      opened = settle(t_before, before, t, s);
    }
    x = Eigen::Map<const Eigen::VectorXd>(s.data(), static_cast<Eigen::Index>(s.size()));
    return opened;
  }
  const StepStatistics& statistics() const { return statistics_; }
  double overlap(double t, const Eigen::VectorXd& x) const { return casing_.overlap(t, x.head(n_)); }

private:
  std::function<void(const OdeState&, OdeState&, double)> rhs() {
    return [this](const OdeState& x, OdeState& dx, double t) {
      ++statistics_.evaluations;
      dx.resize(x.size());
      const Eigen::Map<const Eigen::VectorXd> in(x.data(), static_cast<Eigen::Index>(x.size()));
      Eigen::Map<Eigen::VectorXd> out(dx.data(), static_cast<Eigen::Index>(dx.size()));
      system_.derivative(t, in, out);
    };
  }
  // The state τ after t₀ by one step of the formula from s₀.
  OdeState from(double t0, const OdeState& s0, double tau) {
    OdeState s(s0.size());
    odeint::runge_kutta_fehlberg78<OdeState>().do_step(rhs(), s0, t0, s, tau);
    return s;
  }
  double gap(double t, const OdeState& s) const {
    return casing_.overlap(t, Eigen::Map<const Eigen::VectorXd>(s.data(), n_));
  }
  double gap_rate(double t, const OdeState& s) const {
    return casing_.overlap_rate(t, Eigen::Map<const Eigen::VectorXd>(s.data(), n_),
                                Eigen::Map<const Eigen::VectorXd>(s.data() + n_, n_));
  }
  // After the step [t₀, t] from s₀ to s: the deepest overlap in it, and the opening (s, t then
  // there); true where it opened.
  bool settle(double t0, const OdeState& s0, double& t, OdeState& s) {
    const double h = t - t0;
    const auto rate = [&](double tau) { return gap_rate(t0 + tau, from(t0, s0, tau)); };
    double deepest = gap(t, s);
    const double rate0 = gap_rate(t0, s0), rate1 = gap_rate(t, s);
    if (rate0 > 0 && rate1 <= 0) {
      const double tau = event_time(rate, 0, h, rate0, rate1);
      deepest = std::max(deepest, gap(t0 + tau, from(t0, s0, tau)));
    }
    summary_.max_overlap_m = std::max(summary_.max_overlap_m, deepest);
    summary_.peak_force_n = std::max(summary_.peak_force_n, casing_.stiffness_n_m * deepest);
    const double g1 = gap(t, s);
    if (g1 > 0) return false;
    // A graze that starts at zero overlap opens at the step's end.
    const auto g = [&](double tau) { return gap(t0 + tau, from(t0, s0, tau)); };
    const double g0 = gap(t0, s0), tau = g0 > 0 ? event_time(g, 0, h, g0, g1) : h;
    s = from(t0, s0, tau), t = t0 + tau;
    return true;
  }

  const TransientSystem& system_;
  const CasingContact& casing_;
  int n_;
  odeint::controlled_runge_kutta<odeint::runge_kutta_fehlberg78<OdeState>> stepper_;
  double dt_, started_ = 0;
  ContactSummary& summary_;
  StepStatistics statistics_;
};

// Refuses a damping whose modal matrix is not positive semidefinite: the closing search's bound
// needs |y| not to grow in free flight.
void require_dissipative(const BladeModel& model, const Scene& scene, const ExactStepper& stepper) {
  const Eigen::MatrixXd C = stepper.shapes().transpose() *
                            damping_matrix(model, scene.damping, scene.operation.speed_rad_s) * stepper.shapes();
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (C + C.transpose())).eigenvalues().minCoeff();
  if (!(lowest >= -1e-12 * std::max(1.0, C.norm()))) {
    throw NumericalError("exact stepping: the damping feeds energy into a mode, so free flight has no bound to find "
                         "the casing's contacts with; use the rkf45 method");
  }
}

}  // namespace

TransientResult run_fast_clearance_transient(const BladeModel& model, const Scene& scene, const TransientOptions& o,
                                             double check_time, Eigen::VectorXd& check_state) {
  const int n = model.layout.size();
  const TransientSystem system(model, scene, o);
  ExactStepper stepper(model, scene, o.contact_tolerance, std::nullopt, o.piece_work_flops);
  require_dissipative(model, scene, stepper);
  TransientResult result;
  result.method = TransientMethod::fast;
  RunStart begin = run_start(model, scene, system, o, result);
  const Recorder record = begin.recorder(model, system, o, result);
  result.fixed = transient_step(model, scene, o, begin.t_end);
  ContactSummary summary{system.casing()->stiffness_n_m};
  ClosingSearch closings(stepper, *system.casing(), model, result.fixed.step_s);
  ContactStepper contact(system, o.contact_tolerance, result.fixed.step_s, summary);
  Eigen::VectorXd x = begin.x, z;
  double t = 0;
  bool touching = contact.overlap(0, x) > 0;
  if (touching) contact.close(0);
  record(0, x);
  LandingLog log(model, system, record, o, result, x, check_state);
  for (const Landing& l : landings(stepper, begin, o, check_time)) {
    if (l.t <= t) continue;  // the start
    while (t < l.t) {
      if (touching) {
        if (contact.advance(t, l.t, x)) touching = false, contact.open(t);
        continue;
      }
      double work = x(2 * n);
      z = stepper.modal(x.head(2 * n));
      const std::optional<double> closing = closings.earliest(t, l.t, z);
      const double until = closing ? *closing : l.t;
      stepper.free_flight(until - t, z, work);
      t = until;
      x << stepper.physical(z), work;
      if (closing) touching = true, contact.close(t);
    }
    // A wall that jumps at a pulse edge (rectangular distortions) closes or opens there.
    const bool overlapping = contact.overlap(t, x) > 0;
    if (overlapping != touching) overlapping ? contact.close(t) : contact.open(t);
    touching = overlapping;
    if (log.sample(l, t, x)) break;
    log.revolution(l, x);
  }
  if (touching) contact.open(t);
  result.contact = summary;
  result.steps = contact.statistics();
  result.final_state = x.head(2 * n);
  result.exact = stepper.statistics();
  return result;
}

}  // namespace bladestab::detail
