// Scene reading: values, derived inertia, overrides.
#include <catch2/catch.hpp>

#include "bladestab/base/input_error.hpp"
#include "support/scene_text.hpp"
#include "support/scenes.hpp"

using namespace bladestab;
using testing_support::paper_scene;

TEST_CASE("the paper scene reads with SPEC section 7 values", "[scene]") {
  const Scene s = paper_scene();
  CHECK(s.blade.length == 1.0);
  CHECK(s.blade.hub_radius == 0.5);
  CHECK(s.blade.area == 22.39e-4);
  CHECK(s.blade.inertia == Approx(0.01 * 0.01 * 22.39e-4).epsilon(1e-15));
  CHECK(s.blade.stagger_deg == -60);
  CHECK(s.model.basis == BasisKind::legendre);
  CHECK(s.operation.speed_rad_s == 300);
  CHECK(s.load.profile == PulseProfile::half_sine);
  CHECK(s.load.clearance == 0.003);
  CHECK_FALSE(s.load.pulse_frequency_hz.has_value());
}

TEST_CASE("overrides (--set) take TOML values and bare words", "[scene]") {
  const Scene s = paper_scene({"model.basis=sine", "model.terms=12", "operation.speed_rad_s=0",
                               "model.coriolis=false", "load.pulse_frequency_hz=47.5", "damping.model=modal",
                               "damping.ratio=0.01"});
  CHECK(s.model.basis == BasisKind::sine);
  CHECK(s.model.terms == 12);
  CHECK(s.operation.speed_rad_s == 0);
  CHECK_FALSE(s.model.coriolis);
  CHECK(s.load.pulse_frequency_hz.value() == 47.5);
  CHECK(s.damping.model == DampingModel::modal);
}

TEST_CASE("an inertia given directly replaces the slenderness", "[scene]") {
  const std::string text = R"(
[blade]
length = 2.0
hub_radius = 0.0
area = 1e-3
inertia = 4e-8
youngs_modulus = 2e11
density = 7800
poisson = 0.3
shear_coefficient = 0.85
stagger_deg = 0
)" + testing_support::legendre_model_section + R"([operation]
speed_rad_s = 0
[damping]
model = "rayleigh"
ratio = 0.02
frequencies_hz = [10, 100]
[load]
profile = "rectangular"
fmax_over_fcr = 0.5
contact_time_rev = 0.1
pulses_per_rev = 2
pulse_count = 1
approximation = "fourier"
mode = "clearance"
friction = 0.2
clearance = 0.001
intrusion = 0.0012
contact_stiffness = 5e9
)";
  const Scene s = parse_scene(text, "inline.toml");
  CHECK(s.load.intrusion == 0.0012);
  CHECK(s.load.contact_stiffness == 5e9);
  CHECK(s.blade.inertia == 4e-8);
  CHECK(s.damping.frequencies_hz == std::vector<double>{10, 100});
  CHECK(s.load.pulses_per_rev == 2);
  CHECK(s.load.mode == LoadMode::clearance);
  CHECK_THROWS_AS(parse_scene(text, "inline.toml", {"load.contact_time_rev=0.6"}), InputError);
}
