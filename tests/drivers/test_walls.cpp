// Walls as drivers: the rules against their definitions (Barrat & Trizac 2002, Sec. III A) and a
// gas between two thermal walls relaxing to the wall temperature with Maxwellian velocities.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "libgran/core/wall_motion.hpp"
#include "libgran/engines/event_driven/collision_rules.hpp"
#include "libgran/plugins/driver.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

// The sawtooth wall's rule is the wall collision with the wall moving into the gas at v0
// (wall_velocity of the sawtooth motion) and e = 1.
TEST(SawtoothWall, LowerWallRuleIsTwiceWallSpeedMinusNormalVelocity) {
    const double u = wall_velocity(WallMotion::sawtooth(0.7), +1, 12.3);
    for (double vy : {-0.1, -1.0, -3.5}) {
        EXPECT_EQ(wall_collision(vy, u, 1.0), 2 * 0.7 - vy);  // exactly, as the paper's rule
    }
}

TEST(SawtoothWall, UpperWallRuleMirrorsTheLowerOne) {
    const double u = wall_velocity(WallMotion::sawtooth(0.7), -1, 0.0);
    EXPECT_EQ(wall_collision(1.2, u, 1.0), -2 * 0.7 - 1.2);
}

TEST(SawtoothWall, WallRestitutionScalesTheRelativeVelocity) {
    EXPECT_NEAR(wall_collision(-2.0, 0.5, 0.8) - 0.5, -0.8 * (-2.0 - 0.5), 1e-15);
}

// A thermal wall driver (axis y of a box periodic along the other axes) and its rule.
template <int D>
std::unique_ptr<Driver<D>> thermal_wall(double temperature, const char* tangential,
                                        std::uint64_t seed) {
    const auto* plugin = DriverRegistry::instance().find("thermal_wall");
    const YAML::Node node =
        YAML::Load(fmt::format("{{type: thermal_wall, axis: y, temperature: {}, tangential: {}}}",
                               temperature, tangential));
    SceneInfo info;
    info.dimension = D;
    info.seed = seed;
    info.periodic.assign(D, true);
    info.periodic[1] = false;
    info.box_length.assign(D, 10.0);
    return plugin->template make<D>(read_params(node, plugin->schema, {"test", ""}, {"type"}),
                                    info);
}

// Kolmogorov–Smirnov test of the outgoing normal speeds against the flux distribution
// F(v) = 1 - exp(-m v^2 / (2 T0)); critical value 1.63/sqrt(n) at the 1% level. A Maxwellian
// (non-flux) or wrongly scaled draw fails it by far (checked below).
double ks_flux(const std::vector<double>& speeds, double T0, double m) {
    std::vector<double> s = speeds;
    std::sort(s.begin(), s.end());
    double d = 0;
    const double n = double(s.size());
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double f = 1.0 - std::exp(-m * s[k] * s[k] / (2 * T0));
        d = std::max({d, std::abs(f - double(k) / n), std::abs(f - double(k + 1) / n)});
    }
    return d * std::sqrt(n);
}

TEST(ThermalWall, OutgoingNormalVelocitiesFollowTheFluxDistribution) {
    auto driver = thermal_wall<2>(2.0, "keep", 3);
    WallReflection<2>* rule = driver->walls().at(0).reflection;
    ASSERT_NE(rule, nullptr);  // the rule replaces the contact
    const double m = 3.0;
    std::vector<double> out;
    for (int k = 0; k < 200000; ++k) {
        Vec<2> v(0.4, -1.0);
        rule->reflect(v, 1, +1.0, 0.0, m);
        ASSERT_GT(v[1], 0.0);
        EXPECT_EQ(v[0], 0.4);  // tangential kept
        out.push_back(v[1]);
    }
    EXPECT_LT(ks_flux(out, 2.0, m), 1.63);
    // The same sample is not compatible with a wrong temperature: the test has power.
    EXPECT_GT(ks_flux(out, 2.2, m), 1.63);
}

TEST(ThermalWall, UpperWallSendsParticlesDownAndCanRedrawTangentialVelocity) {
    auto driver = thermal_wall<3>(1.0, "redraw", 4);
    WallReflection<3>* rule = driver->walls().at(1).reflection;
    double sum2 = 0;
    const int n = 100000;
    for (int k = 0; k < n; ++k) {
        Vec<3> v(5.0, 1.0, 5.0);
        rule->reflect(v, 1, -1.0, 0.0, 1.0);
        ASSERT_LT(v[1], 0.0);
        sum2 += v[0] * v[0] + v[2] * v[2];
    }
    EXPECT_NEAR(sum2 / (2 * n), 1.0, 0.02);  // tangential components at T0
}

// Elastic disks between two thermal walls at T0 = 1 (periodic x), starting at T = 3: the gas
// relaxes to T0 in both components, with Gaussian velocity distributions (kurtosis 3).
TEST(ThermalWall, ElasticGasBetweenTwoThermalWallsEquilibratesToWallTemperature) {
    const char* scene = R"(
dimension: 2
seed: 6
species: [{name: a, count: 1000}]
interactions: {alpha: 1}
box: {packing_fraction: 0.05, periodic: [true, false]}
initial: {temperature: 3}
drivers: [{type: thermal_wall, axis: y, side: both, temperature: 1}]
observables: [{type: temperatures}, {type: velocity_pdf}]
run: {equilibration: 100, measurement: 3000, sample_interval: 1}
)";
    const YAML::Node s = testing::run_yaml(scene, "thermal");
    const YAML::Node t = s["observables"]["temperatures"]["species"]["a"];
    for (const char* c : {"T_x", "T_y"}) {
        RecordProperty(c,
                       fmt::format("{:.4f} +- {:.4f}", testing::value(t[c]), testing::error(t[c])));
        EXPECT_NEAR(testing::value(t[c]), 1.0, 0.015)
            << c << " " << testing::value(t[c]) << " +- " << testing::error(t[c]);
        EXPECT_LT(testing::error(t[c]), 0.005);
    }
    for (const char* c : {"x", "y"}) {
        const YAML::Node k = s["observables"]["velocity_pdf"]["a"][c]["kurtosis"];
        EXPECT_NEAR(testing::value(k), 3.0, 0.05) << c << " kurtosis " << testing::value(k);
    }
    EXPECT_GT(s["drivers"]["thermal_wall"]["hits_lower"].as<std::uint64_t>(), 1000u);
}

}  // namespace
}  // namespace gran
