// Very stiff DEM springs (issue 6): k_n = 1e8 and 1e10 m g / d (contacts of 2.2e-4 and 2.2e-5
// sqrt(d/g)). With dt = t_c / 50 (the default) velocity Verlet resolves the contact at any
// stiffness, so the isolated head-on collision the run reports (libgran/dem_probe: the same law,
// parameters and dt) must give the requested restitution within 1% and the closed-form
// duration t_c = pi / omega_d within 2% (dt/t_c = 2% quantises it), and an elastic gas must keep
// its energy: the integrator's error is O((dt/t_c)^2) = 4e-4 of a pair's energy per contact, of
// random sign, ~1e-4 of the total over these runs; bound 1e-3. The kinetic energy sampled during
// a contact lacks the spring energy (up to a pair's share, a few % with 50 grains), so: no sample
// above the initial energy by more than 1e-3, and most samples (no contact in progress: a contact
// lasts t_c, ~0.1 contacts in progress on average) within 1e-3 of it. A stiffness that makes the
// run need more than 1e14 steps is refused with the reason.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "libgran/run/run.hpp"
#include "tests/support/contains.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

void check_stiff(double k, const std::string& tag) {
    // T = 100 (speeds ~10 d / sqrt(d/g)): a few collisions per grain in 0.3 time units.
    const YAML::Node s = testing::run_yaml(fmt::format(R"(
dimension: 2
seed: 2
species: [{{name: a, count: 50}}]
box: {{packing_fraction: 0.3}}
initial: {{temperature: 100}}
interactions: {{law: linear_dashpot, stiffness: {}}}
engine: {{type: dem}}
observables: [{{type: kinetic_energy}}, {{type: collision_statistics}}]
run: {{unit: time, measurement: 0.3, sample_interval: 0.01}}
)",
                                                       k),
                                           tag);
    ASSERT_EQ(s["status"].as<std::string>(), "completed");
    const YAML::Node iso = s["performance"]["isolated_collisions"]["a-a"];
    EXPECT_NEAR(iso["restitution"].as<double>(), 1.0, 0.01);
    EXPECT_NEAR(iso["measured_contact_time"].as<double>() / iso["contact_time"].as<double>(), 1.0,
                0.02);
    // Elastic linear spring: t_c = pi sqrt(m_eff / k_n), m_eff = m / 2.
    EXPECT_NEAR(iso["contact_time"].as<double>() / (M_PI * std::sqrt(0.5 / k)), 1.0, 1e-9);
    EXPECT_GT(s["performance"]["contacts"].as<double>(), 100) << "too few collisions to test";
    auto f = h5::File::open_read((testing::temp_dir() / (tag + ".h5")).string());
    const auto e = f.root().read_doubles("observables/kinetic_energy/energy_per_particle/value");
    std::size_t close = 0;
    for (double x : e) {
        EXPECT_LT(x / e.front(), 1 + 1e-3);
        close += std::abs(x / e.front() - 1) < 1e-3 ? 1 : 0;
    }
    EXPECT_GT(close, e.size() / 2) << "most samples should hold the initial energy";
}

TEST(StiffDem, StiffnessOf1e8KeepsRestitutionContactTimeAndEnergy) {
    check_stiff(1e8, "k1e8");
}
TEST(StiffDem, StiffnessOf1e10KeepsRestitutionContactTimeAndEnergy) {
    check_stiff(1e10, "k1e10");
}

// Restitution 0.9 at k_n = 1e10: the dashpot of Eq. A9 must still give e = 0.9 (the probe runs
// whatever the length of the run, so a short run suffices).
TEST(StiffDem, StiffnessOf1e10KeepsAnInelasticRestitution) {
    const YAML::Node s = testing::run_yaml(R"(
dimension: 3
species: [{name: a, count: 20}]
interactions: {law: linear_dashpot, restitution: 0.9, stiffness: 1.0e+10}
box: {packing_fraction: 0.1}
engine: {type: dem}
run: {unit: time, measurement: 1.0e-3, sample_interval: 1.0e-3}
)",
                                           "k1e10_e09");
    const YAML::Node iso = s["performance"]["isolated_collisions"]["a-a"];
    EXPECT_NEAR(iso["restitution"].as<double>(), 0.9, 0.009);
    EXPECT_NEAR(iso["measured_contact_time"].as<double>() / iso["contact_time"].as<double>(), 1.0,
                0.02);
}

TEST(StiffDem, StiffnessThatWouldNeedCenturiesOfStepsIsRefused) {
    const std::string yaml = R"(
dimension: 2
species: [{name: a, count: 50}]
box: {packing_fraction: 0.3}
interactions: {law: linear_dashpot, stiffness: 1.0e+300}
engine: {type: dem}
run: {unit: time, measurement: 1}
)";
    try {
        check_scene(parse_scene(YAML::Load(yaml), "stiff.yaml"));
        ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_TRUE(testing::contains(e.what(), "stiff.yaml:"));
        EXPECT_TRUE(testing::contains(e.what(), "steps"));
        EXPECT_TRUE(testing::contains(e.what(), "stiffness"));
        EXPECT_TRUE(testing::contains(e.what(), "interactions"));
    }
}

}  // namespace
}  // namespace gran
