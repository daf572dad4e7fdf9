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

// The vibrated demo's 500 disks at packing fraction 1e-12: about 8e6 cell crossings per collision
// (a Knudsen gas), 4e13 events, weeks of work for 5e6 collisions. Refused naming the box; 1e-10
// (8.6e5 crossings per collision, a few days) is still a run one may want.
Scene vibrated_disks(const std::string& phi) {
    return parse_scene(YAML::Load(R"(
dimension: 2
seed: 1
particles: 500
species: [{name: a, mass: 1, diameter: 1, number_fraction: 1}]
interactions: {law: constant_restitution, alpha: 0.85}
box: {packing_fraction: )" + phi + R"(, aspect: [1, 1], periodic: [true, false]}
run: {unit: collisions_per_particle, equilibration: 100, measurement: 20000, sample_interval: 2}
)"),
                       "knudsen.yaml");
}

TEST(EventDrivenCost, KnudsenGasOfMillionsOfCellCrossingsPerCollisionIsRefusedNamingTheBox) {
    const Scene ok = vibrated_disks("1.0e-10");
    const EventEstimate e = estimate_events(ok, EngineDemands{});
    EXPECT_LT(e.crossings, kMaxCrossingsPerCollision * e.collisions);
    EXPECT_GT(e.events(), kLongRunEvents);  // long, yet accepted
    try {
        (void)vibrated_disks("1.0e-12");
        FAIL() << "a packing fraction of 1e-12 was accepted";
    } catch (const SceneError& err) {
        const std::string what = err.what();
        EXPECT_NE(what.find("knudsen.yaml:7"), std::string::npos) << what;
        EXPECT_NE(what.find("cell crossings per collision"), std::string::npos) << what;
        EXPECT_NE(what.find("raise box.packing_fraction"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace gran
