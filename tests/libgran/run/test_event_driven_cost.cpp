// The event-driven cost estimate (libgran/run/event_driven_cost.hpp) against what the engine does:
// an elastic gas keeps its initial temperature, so kinetic theory at that temperature must give the
// simulated time (Enskog collision frequency) and the cell crossings of free flight; and the
// runs that could never finish are refused naming the key.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "libgran/core/scene_error.hpp"
#include "libgran/run/event_driven_cost.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {
namespace {

Scene elastic_gas(const std::string& phi, int dimension) {
    return parse_scene(YAML::Load("dimension: " + std::to_string(dimension) + R"(
seed: 4
particles: 2000
species: [{name: a, mass: 1, diameter: 1, number_fraction: 1}]
interactions: {law: constant_restitution, alpha: 1}
box: {packing_fraction: )" + phi + R"(}
run: {unit: collisions_per_particle, measurement: 20, sample_interval: 1}
)"),
                       "gas.yaml");
}

// Simulated time to 20 collisions per particle and cell crossings, estimated and measured.
void expect_estimate_matches_run(const std::string& phi, int dimension) {
    const Scene sc = elastic_gas(phi, dimension);
    const EventEstimate e = estimate_events(sc, EngineDemands{});
    Simulation sim(sc);
    sim.advance({.collisions = 20000});
    const double crossings = double(sim.work() - sim.collisions());  // no walls, no kicks
    SCOPED_TRACE("phi " + phi + ", " + std::to_string(dimension) + "D");
    EXPECT_NEAR(sim.time() / e.simulated_time, 1.0, 0.1);  // Enskog at low density: a few %
    EXPECT_NEAR(crossings / e.crossings, 1.0, 0.15);
    EXPECT_DOUBLE_EQ(e.collisions, 20000.0);
}

TEST(EventDrivenCost, DiluteElasticGasTakesTheEstimatedTimeAndCellCrossings) {
    expect_estimate_matches_run("0.01", 2);
    expect_estimate_matches_run("0.001", 3);
}

TEST(EventDrivenCost, BoxOf1e150ForAHundredDisksIsRefusedNamingTheBox) {
    YAML::Node root = YAML::Load(R"(
dimension: 2
species: [{name: a, count: 100}]
interactions: {law: constant_restitution, alpha: 0.9}
box: {lengths: [1.0e+150, 1.0e+150]}
run: {measurement: 100}
)");
    try {
        parse_scene(root, "big.yaml");
        FAIL() << "a box of 1e150 was accepted";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("big.yaml:5"), std::string::npos) << what;
        EXPECT_NE(what.find("raise box.packing_fraction"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace gran
