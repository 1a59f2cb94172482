// Coulomb friction at the tip (load.friction = μ > 0, docs/theory.md §1 and §5) in the transient, against an
// independent integration of the friction law written out in tests/reference/blade_transient.hpp
// (Boost.Odeint, Dormand–Prince 5(4), exact sign), and the law's sign and size sample by sample.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "bladestab/transient/transient.hpp"
#include "reference/blade_transient.hpp"
#include "reference/pulse_profiles.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

namespace {

struct FrictionRun {
  Scene scene;
  BladeModel model;
  TransientResult result;
  reference::TipHistory reference;
};

// The paper's endless half-sine train (F̄ = 5, t̄_c = 0.01) with friction μ on a small blade: four
// Euler–Bernoulli terms for v and u (no 46 kHz rotation modes, so the explicit reference is quick),
// run by the library at rtol 1e-9 and by the reference at 1e-10, sampled at the same times.
FrictionRun friction_run(double mu, double revolutions) {
  const Scene s = paper_scene({"model.theory=euler-bernoulli", "model.terms=4", "load.friction=" + std::to_string(mu)});
  BladeModel m = assemble_model(s);
  TransientOptions o;
  o.revolutions = revolutions;
  o.tolerance = 1e-9;
  TransientResult r = run_transient(m, s, o);
  std::vector<double> times;
  for (const TransientSample& p : r.samples) times.push_back(p.time_s);
  const reference::PulseTrainReference pulses = reference::scene_pulses(s);
  const double speed = s.operation.speed_rad_s;
  reference::BladeLoadCase load{speed, m.gyroscopic(speed), [pulses](double t) { return pulses.force(t); },
                                pulses.edges(times.back()), mu};
  reference::TipHistory h = reference::odeint_tip_history(m, load, rotating_equilibrium(m, speed), times);
  return {s, std::move(m), std::move(r), std::move(h)};
}

std::vector<double> field(const TransientResult& r, double TransientSample::*member) {
  std::vector<double> out;
  for (const TransientSample& p : r.samples) out.push_back(p.*member);
  return out;
}

}  // namespace

TEST_CASE("friction mu = 0.2: the transient matches an independent integration of the Coulomb law to 1e-6 of the peak",
          "[transient][friction][long_under_sanitizers]") {
  const FrictionRun with = friction_run(0.2, 2);
  const std::vector<double> lateral = field(with.result, &TransientSample::tip_lateral_m);
  const std::vector<double> axial = field(with.result, &TransientSample::tip_axial_m);
  REQUIRE(with.reference.lateral.size() == lateral.size());
  const double d_lateral = reference::relative_history_difference(with.reference.lateral, lateral);
  const double d_axial = reference::relative_history_difference(with.reference.axial, axial);
  // Without friction the lateral motion is another one altogether: the test can tell the law apart.
  const FrictionRun without = friction_run(0, 2);
  const double friction_effect =
      reference::relative_history_difference(with.reference.lateral, field(without.result, &TransientSample::tip_lateral_m));
  INFO("lateral difference " << d_lateral << " of the peak, axial " << d_axial << "; μ = 0 differs by "
                             << friction_effect);
  // The library's rtol 1e-9 grows to 1e2–1e3 times that over a run's many oscillations.
  CHECK(d_lateral < 1e-6);
  CHECK(d_axial < 1e-6);
  CHECK(friction_effect > 0.5);
}

TEST_CASE("friction: the force is mu|F| cos(beta), against the sliding, only in contact, its work is the reference's",
          "[transient][friction][long_under_sanitizers]") {
  const FrictionRun run = friction_run(0.2, 2);
  const double mu = 0.2, cos_beta = std::cos(run.scene.blade.stagger_deg * 3.14159265358979323846 / 180);
  const double rim_speed = run.scene.operation.speed_rad_s * (run.scene.blade.hub_radius + run.scene.blade.length);
  const reference::PulseTrainReference pulses = reference::scene_pulses(run.scene);
  int in_contact = 0;
  for (const TransientSample& p : run.result.samples) {
    const double F = pulses.force(p.time_s);  // docs/theory.md §3, written out in the reference
    INFO("t = " << p.time_s << " s: F = " << p.axial_force_n << " N (reference " << F << "), friction "
                << p.friction_force_n << " N");
    CHECK(p.axial_force_n == Approx(F).margin(1e-9 * pulses.peak));
    if (p.axial_force_n == 0) {
      CHECK(p.friction_force_n == 0);
      continue;
    }
    ++in_contact;
    // docs/theory.md §1: size μ|F| cos β along ê_n, and against the tip's sliding past the casing
    // (ΩR + cos β · v̇(L) > 0: the casing slides backwards past the tip).
    const double sliding = rim_speed + cos_beta * p.tip_lateral_velocity_m_s;
    CHECK(std::abs(p.friction_force_n) == Approx(mu * std::abs(p.axial_force_n) * cos_beta).epsilon(1e-12));
    CHECK(p.friction_force_n * sliding < 0);
  }
  CHECK(in_contact >= 2);  // 200 samples a revolution, 2 per contact window of 0.01 revolution
  // The energy balance: the library's blade energy E(t) − E(0) (from its state) equals the work of
  // the tip load and the friction along the reference trajectory (integrated there, from the law).
  const TransientSample& first = run.result.samples.front();
  const TransientSample& last = run.result.samples.back();
  const double gained = last.total_energy_j - first.total_energy_j;
  const double load_work = run.reference.load_work.back(), friction_work = run.reference.friction_work.back();
  INFO("blade energy gained " << gained << " J; reference work: tip load " << load_work << " J, friction "
                              << friction_work << " J; mismatch " << gained / (load_work + friction_work) - 1);
  CHECK(gained == Approx(load_work + friction_work).epsilon(1e-6));  // measured 8e-9
  // The casing slides past at ΩR = 450 m/s: its friction drives the blade's lateral vibration
  // (work into the blade, measured 7 % of the energy gained), it does not damp it.
  CHECK(friction_work > 0.01 * gained);
}
