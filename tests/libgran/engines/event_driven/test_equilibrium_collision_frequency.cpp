// Elastic hard disks/spheres in equilibrium: the collision frequency per particle is exactly
// omega = S n sigma^(d-1) g(sigma) sqrt(T/m) (S = 2 sqrt(pi) in 2D, 4 sqrt(pi) in 3D), with the
// contact value g(sigma) of Henderson (2D) or Carnahan-Starling (3D). Tolerance 3% (issue #2); the
// statistical error of each run is ~0.3%, the contact-value approximations are good to <1% here.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "libgran/core/h5.hpp"
#include "libgran/core/kinetic_theory.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

using gran::testing::error;
using gran::testing::run_yaml;
using gran::testing::value;

// Returns the neighbour shells' skin the run's engine used (0: cells).
double check_frequency(int d, double phi, int n) {
    const std::string yaml = fmt::format(R"(
dimension: {}
seed: 5
species: [{{name: a, mass: 1, diameter: 1, count: {}}}]
interactions: {{alpha: 1}}
box: {{packing_fraction: {}}}
initial: {{placement: lattice}}
observables: [{{type: temperatures}}, {{type: collision_statistics}}]
run: {{equilibration: 30, measurement: 200, sample_interval: 2}}
)",
                                         d, n, phi);
    const YAML::Node s = run_yaml(yaml, fmt::format("enskog_{}d_{}", d, phi));
    const double T = value(s["observables"]["temperatures"]["T_mixture"]);
    const YAML::Node w = s["observables"]["collision_statistics"]["frequency_per_particle"];
    const double vd = theory::unit_ball_volume(d);
    const double density = phi / vd;
    const double expected =
        theory::enskog_collision_frequency(d, density, 1.0, theory::contact_value(d, phi), T, 1.0);
    ::testing::Test::RecordProperty("measured",
                                    fmt::format("{:.5f} +- {:.5f}", value(w), error(w)));
    ::testing::Test::RecordProperty("enskog", fmt::format("{:.5f}", expected));
    EXPECT_LT(error(w) / value(w), 0.01) << "statistics too poor for the test to mean anything";
    EXPECT_NEAR(value(w) / expected, 1.0, 0.03)
        << fmt::format("d={} phi={}: measured {:.5f} +- {:.5f}, Enskog {:.5f}", d, phi, value(w),
                       error(w), expected);
    const auto file = h5::File::open_read(
        (testing::temp_dir() / fmt::format("enskog_{}d_{}.h5", d, phi)).string());
    return file.root().exists("performance/neighbour_skin")
               ? file.root().read_doubles("performance/neighbour_skin").at(0)
               : 0.0;
}

TEST(EquilibriumCollisionFrequency, MatchesEnskogHendersonForDisksAtPhi005) {
    check_frequency(2, 0.05, 2000);
}
TEST(EquilibriumCollisionFrequency, MatchesEnskogHendersonForDisksAtPhi030) {
    check_frequency(2, 0.30, 2000);
}
TEST(EquilibriumCollisionFrequency, MatchesEnskogCarnahanStarlingForSpheresAtPhi005) {
    check_frequency(3, 0.05, 2000);
}
TEST(EquilibriumCollisionFrequency, MatchesEnskogCarnahanStarlingForSpheresAtPhi020) {
    EXPECT_EQ(check_frequency(3, 0.20, 2000), 0.0);  // on cells
}
// A dense fluid (below freezing at 0.494), where the engine finds pairs through neighbour shells.
TEST(EquilibriumCollisionFrequency, MatchesEnskogCarnahanStarlingForSpheresAtPhi045OnShells) {
    EXPECT_EQ(check_frequency(3, 0.45, 2000), 0.5);
}

}  // namespace
}  // namespace gran
