// Angular-velocity distribution: in equilibrium (elastic, perfectly rough spheres conserve energy
// and equipartition between translation and rotation) the rescaled angular velocities are
// Gaussian: kurtosis 3 and density 1/sqrt(2 pi) at 0. Smooth scenes record that they have none.
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "libgran/core/scene_error.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

TEST(AngularVelocityPdf, RoughElasticSpheresHaveGaussianAngularVelocities) {
    const YAML::Node s = testing::run_yaml(R"(
dimension: 3
seed: 5
species: [{name: a, count: 1000}]
interactions: {alpha: 1, beta: 1}
box: {packing_fraction: 0.1}
observables: [{type: angular_velocity_pdf, bins: 40, range: 4}]
run: {equilibration: 50, measurement: 300, sample_interval: 1}
)",
                                           "rough");
    const YAML::Node k = s["observables"]["angular_velocity_pdf"]["a"]["kurtosis"];
    EXPECT_NEAR(k["value"].as<double>(), 3.0, 3 * k["error"].as<double>() + 0.03);
    auto f = h5::File::open_read((testing::temp_dir() / "rough.h5").string());
    const auto d = f.root().read_doubles("observables/angular_velocity_pdf/a/x/scaled_density");
    ASSERT_EQ(d.size(), 40u);
    EXPECT_NEAR(0.5 * (d[19] + d[20]), 1 / std::sqrt(2 * M_PI), 0.02);
}

TEST(AngularVelocityPdf, SmoothParticlesRecordThatTheyHaveNoAngularVelocities) {
    const YAML::Node s = testing::run_yaml(R"(
dimension: 2
species: [{name: a, count: 10}]
box: {packing_fraction: 0.1}
observables: [{type: angular_velocity_pdf}]
run: {measurement: 1}
)",
                                           "smooth");
    EXPECT_TRUE(s["observables"]["angular_velocity_pdf"]["note"].IsDefined());
    EXPECT_FALSE(s["observables"]["angular_velocity_pdf"]["a"].IsDefined());
}

}  // namespace
}  // namespace gran
