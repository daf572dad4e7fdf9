// Scene files: defaults, resolution and reproducibility of the resolved scene.
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

const char* kScene = R"(
dimension: 2
seed: 3
particles: 200
species:
  - {name: heavy, mass: 3, number_fraction: 0.5}
  - {name: light, mass: 1, number_fraction: 0.5}
interactions:
  alpha: 0.9
  pairs: [{between: [heavy, light], alpha: 0.8}]
box: {packing_fraction: 0.1}
drivers: [{type: stochastic_thermostat, interval: 0.5, strength: 0.1}]
observables: [{type: temperatures}, {type: velocity_pdf, bins: 20}]
run: {equilibration: 5, measurement: 20, sample_interval: 1}
)";

TEST(Scene, NumberFractionsResolveToCountsAndBoxFromPackingFraction) {
    const Scene s = parse_scene(YAML::Load(kScene), "s.yaml");
    ASSERT_EQ(s.species.size(), 2u);
    EXPECT_EQ(s.species.species[0].count, 100u);
    EXPECT_EQ(s.species.species[1].count, 100u);
    EXPECT_NEAR(s.packing_fraction, 0.1, 1e-12);
    EXPECT_DOUBLE_EQ(s.species.species[0].inertia_factor, 0.5);  // disks
    EXPECT_DOUBLE_EQ(s.contacts.nominal_restitution[s.contacts.pair_index(0, 1)], 0.8);
    EXPECT_DOUBLE_EQ(s.contacts.nominal_restitution[s.contacts.pair_index(1, 0)], 0.8);
    EXPECT_DOUBLE_EQ(s.contacts.nominal_restitution[s.contacts.pair_index(0, 0)], 0.9);
}

TEST(Scene, ResolvedSceneIsItselfAValidSceneThatRerunsIdentically) {
    const YAML::Node a = testing::run_yaml(kScene, "first");
    auto file = h5::File::open_read((testing::temp_dir() / "first.h5").string());
    const std::string resolved = file.root().read_string("parameters/scene");
    const YAML::Node b = testing::run_yaml(resolved, "second");
    const auto ga = a["observables"]["temperatures"]["ratios"]["light_over_heavy"]["gamma"]["value"]
                        .as<double>();
    const auto gb = b["observables"]["temperatures"]["ratios"]["light_over_heavy"]["gamma"]["value"]
                        .as<double>();
    EXPECT_EQ(ga, gb);
    EXPECT_EQ(a["performance"]["events"].as<std::uint64_t>(),
              b["performance"]["events"].as<std::uint64_t>());
}

TEST(Scene, OverrideChangesNestedKeysAndListEntries) {
    YAML::Node root = YAML::Load(kScene);
    apply_override(root, "species.1.mass=2.5");
    apply_override(root, "run.measurement=40");
    apply_override(root, "engine.tc=1e-5");
    const Scene s = parse_scene(root, "s.yaml");
    EXPECT_DOUBLE_EQ(s.species.species[1].mass, 2.5);
    EXPECT_DOUBLE_EQ(s.schedule.measurement, 40);
    EXPECT_DOUBLE_EQ(s.engine_settings.params.real("tc"), 1e-5);
    EXPECT_THROW(apply_override(root, "species.7.mass=1"), SceneError);
    EXPECT_THROW(apply_override(root, "novalue"), SceneError);
}

TEST(Scene, ErrorsNameFileLineColumnAndKey) {
    const std::string bad =
        "dimension: 2\nspecies:\n  - {name: a, mass: -1, count: 10}\nbox: {packing_fraction: "
        "0.1}\nrun: {measurement: 1}\n";
    try {
        parse_scene(YAML::Load(bad), "bad.yaml");
        FAIL() << "negative mass accepted";
    } catch (const SceneError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("bad.yaml:3:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("species[0].mass"), std::string::npos) << msg;
        EXPECT_NE(msg.find("> 0"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace gran

namespace gran {
namespace {

// Frames: H5MD time series {step, time, value} of shape (frames, N, D), a box with dimension and
// boundary attributes, and particles in their original order although the engine re-sorts its
// storage (a permuted order would show jumps of half a box between consecutive frames).
TEST(Results, TrajectoryFramesFollowH5mdLayoutWithOriginalParticleOrder) {
    const char* scene = R"(
dimension: 3
seed: 4
species: [{name: a, count: 100}]
interactions: {alpha: 1}
box: {packing_fraction: 0.1, periodic: [true, true, false]}
initial: {placement: lattice}
run: {measurement: 60, sample_interval: 0.5}
output: {frames: 120}
)";
    testing::run_yaml(scene, "frames");
    auto file = h5::File::open_read((testing::temp_dir() / "frames.h5").string());
    auto g = file.root().group("particles/all");
    const auto shape = g.shape("position/value");
    ASSERT_EQ(shape.size(), 3u);
    EXPECT_EQ(shape[0], 120u);
    EXPECT_EQ(shape[1], 100u);
    EXPECT_EQ(shape[2], 3u);
    EXPECT_EQ(g.read_doubles("position/time").size(), 120u);
    EXPECT_EQ(g.read_int64s("position/step").size(), 120u);
    auto box = g.group("box");
    EXPECT_EQ(box.read_attr_double("dimension"), 3.0);
    const auto edge_vectors = box.read_doubles("edges/value");  // frames x 3 x 3, diagonal
    const double edges[3] = {edge_vectors[0], edge_vectors[4], edge_vectors[8]};
    const auto x = g.read_doubles("position/value");
    double worst_mean = 0;
    for (std::size_t f = 0; f + 1 < shape[0]; ++f) {
        double sum = 0;
        for (std::size_t i = 0; i < 100; ++i) {
            double d2 = 0;
            for (std::size_t a = 0; a < 3; ++a) {
                double d = x[((f + 1) * 100 + i) * 3 + a] - x[(f * 100 + i) * 3 + a];
                if (a < 2) d -= edges[a] * std::round(d / edges[a]);
                d2 += d * d;
            }
            sum += std::sqrt(d2);
        }
        worst_mean = std::max(worst_mean, sum / 100);
    }
    EXPECT_LT(worst_mean, 1.0) << "particles change identity between frames";
}

}  // namespace
}  // namespace gran
