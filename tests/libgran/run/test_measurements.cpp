// What a Simulation has measured, written at any moment (libgran/run/measurements.hpp): the
// Python module's Simulation.results(). A run stopped early, with every sample in the first of the
// observables' blocks, must still be written (jackknife errors unknown, values finite).
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "libgran/run/measurements.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

const char* kVibratedMixture = R"(
dimension: 2
seed: 3
particles: 200
species:
  - {name: heavy, mass: 3, number_fraction: 0.5}
  - {name: light, mass: 1, number_fraction: 0.5}
interactions: {alpha: 0.9, walls: {alpha: 1}}
box: {packing_fraction: 0.02, periodic: [true, false]}
drivers: [{type: sawtooth_wall, axis: y, velocity: 1}]
observables:
  - {type: profiles, axis: y, bins: 10, middle_window: 0.2}
  - {type: temperatures}
run: {equilibration: 10, measurement: 1000, sample_interval: 1}
)";

TEST(Measurements, ObservablesAreWrittenMidRunWithTheSamplesTakenSoFar) {
    Simulation sim(load_scene_text(kVibratedMixture, "mixture.yaml"));
    for (int k = 1; k <= 30; ++k) {
        sim.advance({.time = 0.2 * k});
        sim.sample(true, 30);
    }
    const std::string path = (testing::temp_dir() / "measurements.h5").string();
    const YAML::Node summary = YAML::Load(write_measurements(sim, path));
    auto f = h5::File::open_read(path);
    const auto series =
        f.root().group("observables/temperatures/series/T_mixture").read_doubles("value");
    EXPECT_EQ(series.size(), 30u);
    const double T = summary["observables"]["temperatures"]["T_mixture"]["value"].as<double>();
    EXPECT_GT(T, 0.0);
    EXPECT_TRUE(std::isfinite(T));
}

TEST(Measurements, ProfilesOfARunStoppedInItsFirstBlockAreWrittenWithoutErrorBars) {
    Simulation sim(load_scene_text(kVibratedMixture, "mixture.yaml"));
    for (int k = 1; k <= 5; ++k) {  // 5 of the 1000 samples planned: all in the first block
        sim.advance({.time = 0.2 * k});
        sim.sample(true, 1000);
    }
    const std::string path = (testing::temp_dir() / "first_block.h5").string();
    const YAML::Node summary = YAML::Load(write_measurements(sim, path));
    const YAML::Node gamma =
        summary["observables"]["profiles"]["middle/ratios/light_over_heavy/gamma"];
    ASSERT_TRUE(gamma) << summary;
    EXPECT_TRUE(std::isfinite(gamma["value"].as<double>()));
    const YAML::Node p = summary["observables"]["profiles"]["middle/eos/P_enskog"];
    ASSERT_TRUE(p) << summary;
    EXPECT_TRUE(std::isfinite(p["value"].as<double>())) << p;
}

}  // namespace
}  // namespace gran
