// The RKF45 transient against an independent integration: Boost.Odeint's Dormand–Prince 5(4) at
// tight tolerances, on the same equations written out in tests/reference/blade_transient.hpp, with
// the pulse train of the SPEC's table (tests/reference/pulse_profiles.hpp), stepping between its edges.
#include <catch2/catch.hpp>

#include <vector>

#include "bladestab/transient/transient.hpp"
#include "reference/blade_transient.hpp"
#include "reference/pulse_profiles.hpp"
#include "support/scenes.hpp"

using namespace bladestab;

TEST_CASE("RKF45 at tolerance 1e-9 agrees with Odeint's Dormand-Prince to 1e-4 of the peak", "[transient][reference][long_under_sanitizers]") {
  for (const char* count : {"load.pulse_count=1", "load.pulse_count=0"}) {
    const Scene s = testing_support::paper_scene({"model.terms=4", count});
    const BladeModel m = assemble_model(s);
    TransientOptions o;
    o.revolutions = 2;
    o.tolerance = 1e-9;
    const TransientResult r = run_transient(m, s, o);
    std::vector<double> times, lateral, axial;
    for (const TransientSample& p : r.samples) {
      times.push_back(p.time_s);
      lateral.push_back(p.tip_lateral_m);
      axial.push_back(p.tip_axial_m);
    }
    const double W = s.operation.speed_rad_s;
    const reference::PulseTrainReference pulses = reference::scene_pulses(s);
    const reference::BladeLoadCase load{W, m.gyroscopic(W), [pulses](double t) { return pulses.force(t); },
                                        pulses.edges(times.back()), 0};
    const reference::TipHistory h = reference::odeint_tip_history(m, load, rotating_equilibrium(m, W), times, 1e-12);
    REQUIRE(h.lateral.size() == r.samples.size());
    const double d_lat = reference::relative_history_difference(h.lateral, lateral);
    const double d_ax = reference::relative_history_difference(h.axial, axial);
    INFO(count << ": lateral difference " << d_lat << " of the peak, axial " << d_ax);
    CHECK(d_lat < 1e-4);
    CHECK(d_ax < 1e-4);
  }
}
