// Long validation (`make validate`): the stochastic thermostat's kick interval is a speed/accuracy
// knob. Each kick re-predicts every event, so cost grows with kicks per collision; the temperature
// ratio must not depend on the interval once it is a fraction of the mean free time. Measured here
// for m1 = 3 m2, alpha = 0.85, disks at phi = 0.02, with intervals of 1/2, 1/8 and 1/32 of the
// Enskog mean free time: the three gammas must agree within 1% (about 4 standard errors) and with
// the Maxwellian theory within 3%.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "libgran/core/kinetic_theory.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

TEST(StochasticThermostatValidation, TemperatureRatioDoesNotDependOnTheKickInterval) {
    const double phi = 0.02, alpha = 0.85;
    const double density = phi / theory::unit_ball_volume(2);
    const double omega = theory::enskog_collision_frequency(2, density, 1.0, 1.0, 1.0, 1.0);
    const double strength = (1 - alpha * alpha) * omega / 2;
    theory::BinaryMixture mix{2, 3.0, 1.0, 1.0, 1.0, density / 2, density / 2, alpha, alpha, alpha};
    const double expected = theory::heated_mixture_temperature_ratio(
        mix, theory::NoiseConvention::EqualVelocityVariance);
    std::vector<double> gammas;
    for (const double fraction : {0.5, 0.125, 0.03125}) {
        const std::string yaml = fmt::format(R"(
dimension: 2
seed: 23
particles: 2000
species:
  - {{name: heavy, mass: 3, number_fraction: 0.5}}
  - {{name: light, mass: 1, number_fraction: 0.5}}
interactions: {{alpha: {}}}
box: {{packing_fraction: {}}}
drivers: [{{type: stochastic_thermostat, strength: {}, interval: {}}}]
observables: [{{type: temperatures}}]
run: {{equilibration: 100, measurement: 3000, sample_interval: 2}}
)",
                                             alpha, phi, strength, fraction / omega);
        const YAML::Node s = testing::run_yaml(yaml, fmt::format("kick_{}", fraction));
        const YAML::Node g =
            s["observables"]["temperatures"]["ratios"]["light_over_heavy"]["gamma"];
        gammas.push_back(testing::value(g));
        ::testing::Test::RecordProperty(
            fmt::format("gamma_interval_{}", fraction),
            fmt::format("{:.4f} +- {:.4f} (cpu {:.1f} s)", testing::value(g), testing::error(g),
                        s["performance"]["cpu_time"]["value"].as<double>()));
        EXPECT_NEAR(testing::value(g) / expected, 1.0, 0.03);
    }
    EXPECT_NEAR(gammas[0] / gammas[2], 1.0, 0.01);
    EXPECT_NEAR(gammas[1] / gammas[2], 1.0, 0.01);
}

}  // namespace
}  // namespace gran
