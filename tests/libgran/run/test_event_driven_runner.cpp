// The event-driven runner (libgran/run/event_driven_runner.cpp): the drivers' kicks are work like
// events, so a scene whose only events are kicks (one particle under a thermostat: no partner,
// and a box of fewer than four cells a side has no cell crossings) still ends its chunks of work,
// which `gran check`'s cost measurement (it hung on such a scene) and the run loop's progress
// and checkpoints rely on.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {
namespace {

Scene lone_particle_under_a_thermostat() {
    return parse_scene(YAML::Load(R"(
dimension: 2
seed: 3
particles: 1
species: [{name: a, diameter: 1, number_fraction: 1}]
interactions: {law: constant_restitution, alpha: 0.9}
box: {packing_fraction: 0.1}
drivers: [{type: stochastic_thermostat, strength: 0.1, interval: 0.2}]
run: {unit: time, measurement: 1.0e+9, sample_interval: 1.0e+8}
)"),
                       "lone.yaml");
}

TEST(EventDrivenRunner, KicksAreWorkSoAChunkEndsWhenKicksAreTheOnlyEvents) {
    Simulation sim(lone_particle_under_a_thermostat());
    ASSERT_EQ(sim.advance({.work = 1000}), Advance::Reached);
    EXPECT_EQ(sim.work(), 1000u);  // one particle: one update per kick
    EXPECT_EQ(sim.collisions(), 0u);
    EXPECT_NEAR(sim.time(), 1000 * 0.2, 1e-6);  // the 1000th kick, at 1000 intervals
}

}  // namespace
}  // namespace gran
