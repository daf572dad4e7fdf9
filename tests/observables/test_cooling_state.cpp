// The `cooling_state` observable: the homogeneous cooling state of dilute inelastic disks against
// kinetic theory (cooling rate per collision, Sonine a2, the temperature ratio of a mixture), and
// the breakdown of homogeneity detected in a box large enough for the shear instability.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "libgran/core/h5.hpp"
#include "libgran/core/kinetic_theory.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

std::string free_cooling(int particles, double phi, const std::string& species) {
    return fmt::format(R"(
dimension: 2
seed: 5
particles: {}
species: {}
interactions: {{alpha: 0.9}}
box: {{packing_fraction: {}}}
observables: [{{type: cooling_state}}]
run: {{measurement: 400, sample_interval: 0.5}}
)",
                       particles, species, phi);
}

// 1000 disks, alpha = 0.9, packing fraction 0.01, 400 collisions per particle: the scaling state
// cools at zeta* = (1 - alpha^2) / 2 (1 + 3 a2 / 16) per collision per particle with a2 of the
// first Sonine approximation (-0.0269); tolerances 3 standard errors plus 0.5% (zeta*) and 0.01
// (a2). A cooling rate from the elastic collision count alone ((1 - alpha^2) / 2 = 0.095 without
// the Sonine factor) would be 0.5% off; a wrong dimension factor 2 / 3 instead of 1 / 2, 25%.
TEST(CoolingState, DiluteDisksCoolAtTheSonineCorrectedRatePerCollision) {
    const YAML::Node s =
        testing::run_yaml(free_cooling(1000, 0.01, "[{name: g, number_fraction: 1}]"),
                          "mono")["observables"]["cooling_state"];
    EXPECT_TRUE(s["homogeneous"].as<bool>());
    const YAML::Node z = s["scaling_state"]["cooling_rate"];
    const YAML::Node a2 = s["scaling_state"]["g/sonine_a2"];
    const double a2_theory = theory::hcs_sonine_a2(2, 0.9);
    const double z_theory = (1 - 0.81) / 2 * (1 + 3 * a2_theory / 16);
    RecordProperty("zeta", fmt::format("{:.5f} +- {:.5f} (theory {:.5f})", testing::value(z),
                                       testing::error(z), z_theory));
    RecordProperty("a2", fmt::format("{:.4f} +- {:.4f} (theory {:.4f})", testing::value(a2),
                                     testing::error(a2), a2_theory));
    EXPECT_NEAR(testing::value(z), z_theory, 3 * testing::error(z) + 0.005 * z_theory);
    EXPECT_LT(testing::error(z), 0.003 * z_theory);
    EXPECT_NEAR(testing::value(a2), a2_theory, 3 * testing::error(a2) + 0.01);
    EXPECT_LT(s["transient_end"]["value"].as<double>(), 50.0);
}

// A binary mixture (masses 3 and 1, equal sizes and numbers, alpha = 0.9, packing fraction 0.01):
// gamma = T_light / T_heavy in the scaling state against the Gaussian theory of Garzo & Dufty
// (1999), equal cooling rates of both species; 3 standard errors plus 1% (the Gaussian
// approximation).
TEST(CoolingState, MixtureTemperatureRatioMatchesGarzoDuftyInTheScalingState) {
    const YAML::Node s =
        testing::run_yaml(free_cooling(1000, 0.01,
                                       "[{name: heavy, mass: 3, number_fraction: 0.5}, {name: "
                                       "light, mass: 1, number_fraction: 0.5}]"),
                          "mixture")["observables"]["cooling_state"];
    EXPECT_TRUE(s["homogeneous"].as<bool>());
    theory::BinaryMixture mix{2, 3, 1, 1, 1, 0.5, 0.5, 0.9, 0.9, 0.9};
    const double theory = theory::hcs_temperature_ratio(mix);
    const YAML::Node g = s["scaling_state"]["light/gamma"];
    RecordProperty("gamma", fmt::format("{:.4f} +- {:.4f} (theory {:.4f})", testing::value(g),
                                        testing::error(g), theory));
    EXPECT_NEAR(testing::value(g), theory, 3 * testing::error(g) + 0.01 * theory);
    // The transient (gamma relaxing from 1) is found and excluded.
    EXPECT_GT(s["transient_end"]["value"].as<double>(), 0.5);
}

// 4000 disks at packing fraction 0.05 and alpha = 0.8: the box is long enough for the shear
// instability, the longest-wavelength momentum mode grows and the observable reports the
// breakdown (between 10 and 60 collisions per particle here) instead of averaging over it.
TEST(CoolingState, ShearInstabilityOfALargeBoxIsReportedAsTheBreakdown) {
    std::string scene = free_cooling(4000, 0.05, "[{name: g, number_fraction: 1}]");
    scene.replace(scene.find("alpha: 0.9"), 10, "alpha: 0.8");
    scene.replace(scene.find("measurement: 400"), 16, "measurement: 100");
    const YAML::Node s = testing::run_yaml(scene, "unstable")["observables"]["cooling_state"];
    EXPECT_FALSE(s["homogeneous"].as<bool>());
    const double at = s["breakdown"]["value"].as<double>();
    EXPECT_GT(at, 10.0);
    EXPECT_LT(at, 60.0);
    EXPECT_LE(s["scaling_state"]["to"]["value"].as<double>(), at);
}

// In the cooling state the collision frequency goes as sqrt(T), so the collisions per particle
// grow in proportion to the scaled time s = int sqrt(T / T_1) dt: tau(s) is a straight line whose
// slope is the collision frequency at the first sample's temperature T_1 (Enskog, Henderson's
// contact value), while tau against the plain time bends (Haff: ln(1 + t / t0)). Slopes over the
// first and second halves of the run agree within 1%; with the plain time they differ by a factor
// 1 + t / t0 (here about 5).
TEST(CoolingState, CollisionsPerParticleGrowLinearlyInTheScaledTime) {
    testing::run_yaml(free_cooling(1000, 0.01, "[{name: g, number_fraction: 1}]"), "scaled");
    auto f = h5::File::open_read((testing::temp_dir() / "scaled.h5").string());
    auto g = f.root().group("observables/cooling_state/series");
    const auto tau = g.read_doubles("collisions_per_particle/value");
    const auto s = g.read_doubles("scaled_time/value");
    const auto t = g.read_doubles("scaled_time/time");
    const auto T = g.read_doubles("T_mixture/value");
    ASSERT_GT(tau.size(), 100u);
    const std::size_t n = tau.size(), h = n / 2;
    const double first = (tau[h] - tau[0]) / (s[h] - s[0]);
    const double second = (tau[n - 1] - tau[h]) / (s[n - 1] - s[h]);
    EXPECT_NEAR(second / first, 1.0, 0.01);
    const double plain =
        ((tau[h] - tau[0]) / (t[h] - t[0])) / ((tau[n - 1] - tau[h]) / (t[n - 1] - t[h]));
    EXPECT_GT(plain, 2.0);
    // Slope against Enskog's frequency at T_1 (phi = 0.01, unit mass and diameter): 3%.
    const double density = 4 * 0.01 / std::numbers::pi;  // disks of unit diameter
    const double omega =
        theory::enskog_collision_frequency(2, density, 1, theory::contact_value(2, 0.01), T[0], 1);
    EXPECT_NEAR(first, omega, 0.03 * omega);
}

TEST(CoolingState, IsRefusedInADrivenScene) {
    std::string scene = free_cooling(100, 0.01, "[{name: g, number_fraction: 1}]");
    scene += "drivers: [{type: stochastic_thermostat}]\n";
    EXPECT_THROW(parse_scene(YAML::Load(scene), "driven.yaml"), SceneError);
}

}  // namespace
}  // namespace gran
