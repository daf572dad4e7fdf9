// Walls as drivers: the rules against their definitions (Barrat & Trizac 2002, Sec. III A) and a
// gas between two thermal walls relaxing to the wall temperature with Maxwellian velocities.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "libgran/core/wall_motion.hpp"
#include "species/wall_rules.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

TEST(SawtoothWall, LowerWallRuleIsTwiceWallSpeedMinusNormalVelocity) {
    Rng rng = make_rng(1, Stream::Driver);
    const WallParams w;
    const double u = wall_velocity(WallMotion::sawtooth(0.7), +1, 12.3);
    for (double vy : {-0.1, -1.0, -3.5}) {
        Vec<2> v(0.3, vy);
        impact_wall_rule<2>(v, 1, +1.0, u, w, rng, 1.0);
        EXPECT_EQ(v[1], 2 * 0.7 - vy);  // exactly, as the paper's rule
        EXPECT_EQ(v[0], 0.3);           // tangential untouched
    }
}

TEST(SawtoothWall, UpperWallRuleMirrorsTheLowerOne) {
    Rng rng = make_rng(1, Stream::Driver);
    const WallParams w;
    const double u = wall_velocity(WallMotion::sawtooth(0.7), -1, 0.0);
    Vec<3> v(0.3, 1.2, -0.4);
    impact_wall_rule<3>(v, 1, -1.0, u, w, rng, 1.0);
    EXPECT_EQ(v[1], -2 * 0.7 - 1.2);
    EXPECT_EQ(v[0], 0.3);
    EXPECT_EQ(v[2], -0.4);
}

TEST(SawtoothWall, WallRestitutionScalesTheRelativeVelocity) {
    Rng rng = make_rng(1, Stream::Driver);
    WallParams w;
    w.restitution = constant_impact_restitution(0.8);
    Vec<2> v(0.0, -2.0);
    impact_wall_rule<2>(v, 1, +1.0, 0.5, w, rng, 1.0);
    EXPECT_NEAR(v[1] - 0.5, -0.8 * (-2.0 - 0.5), 1e-15);
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
    Rng rng = make_rng(3, Stream::Driver);
    WallParams w;
    w.temperature = 2.0;
    const double m = 3.0;
    std::vector<double> out;
    for (int k = 0; k < 200000; ++k) {
        Vec<2> v(0.4, -1.0);
        thermal_wall_rule<2>(v, 1, +1.0, 0.0, w, rng, m);
        ASSERT_GT(v[1], 0.0);
        EXPECT_EQ(v[0], 0.4);  // tangential kept
        out.push_back(v[1]);
    }
    EXPECT_LT(ks_flux(out, 2.0, m), 1.63);
    // The same sample is not compatible with a wrong temperature: the test has power.
    EXPECT_GT(ks_flux(out, 2.2, m), 1.63);
}

TEST(ThermalWall, UpperWallSendsParticlesDownAndCanRedrawTangentialVelocity) {
    Rng rng = make_rng(4, Stream::Driver);
    WallParams w;
    w.temperature = 1.0;
    w.redraw_tangential = true;
    double sum2 = 0;
    const int n = 100000;
    for (int k = 0; k < n; ++k) {
        Vec<3> v(5.0, 1.0, 5.0);
        thermal_wall_rule<3>(v, 1, -1.0, 0.0, w, rng, 1.0);
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
