// The event-driven runner (libgran/run/event_driven_runner.cpp): a driver whose next kick is not
// after the kick it just made (an interval below the resolution of the time there, as late in a
// very long run) would freeze the simulated time; the runner stops with the watchdog's status and
// a message naming the key to change. And the drivers' kicks are work like events, so a scene
// whose only events are kicks (one particle under a thermostat: no partner, and a box of fewer
// than four cells a side has no cell crossings) still ends its chunks of work, which `gran
// check`'s cost measurement (it hung on such a scene) and the run loop's progress and checkpoints
// rely on.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <memory>
#include <string>

#include "libgran/plugins/engine.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {
namespace {

// A thermostat scene, drivers[0] being the one the runner names.
Scene thermostat_scene() {
    return parse_scene(YAML::Load(R"(
dimension: 2
seed: 2
species: [{name: a, count: 50}]
interactions: {law: constant_restitution, alpha: 0.9}
box: {packing_fraction: 0.1}
drivers: [{type: stochastic_thermostat}]
run: {unit: time, measurement: 10, sample_interval: 1}
)"),
                       "thermostat.yaml");
}

// Kicks at `first`, then every `interval`: with an interval far below the resolution of the time
// at `first` (1e-300 at 0.5), first + interval == first. A real thermostat gets there only after
// ~1e16 kicks; this one gets there at its first kick. After 1000 kicks it stops kicking, so that a
// runner without the guard ends (and fails the test) instead of kicking forever at t = first.
class KickClockBelowResolution final : public Driver<2> {
  public:
    KickClockBelowResolution(double first, double interval) : next_(first), interval_(interval) {}
    double next_kick() const override { return next_; }
    void kick(Particles<2>&, const SpeciesTable&) override {
        ++kicks;
        next_ = kicks < 1000 ? next_ + interval_ : kInf;
    }
    void checkpoint(StateArchive& ar) override { ar.io(next_); }
    int kicks = 0;

  private:
    double next_;
    double interval_;
};

TEST(EventDrivenRunner, KickTimeThatDoesNotAdvanceStopsTheRunNamingTheInterval) {
    const Scene sc = thermostat_scene();
    ASSERT_EQ(0.5 + 1e-300, 0.5);  // the premise: the time cannot resolve the interval there
    DriverList<2> drivers;
    drivers.push_back(std::make_unique<KickClockBelowResolution>(0.5, 1e-300));
    const auto* clock = static_cast<const KickClockBelowResolution*>(drivers[0].get());
    ObservableList<2> observables;
    auto runner = sc.engine->make<2>(sc, drivers, observables);
    EXPECT_EQ(runner->advance(10, UINT64_MAX, UINT64_MAX, nullptr), Advance::Watchdog);
    EXPECT_EQ(clock->kicks, 1);  // stopped at the first kick that froze the clock
    EXPECT_DOUBLE_EQ(runner->now(), 0.5);
    const std::string& why = runner->failure();
    EXPECT_NE(why.find("driver 'stochastic_thermostat'"), std::string::npos) << why;
    EXPECT_NE(why.find("increase drivers[0].interval"), std::string::npos) << why;
}

TEST(EventDrivenRunner, KickTimeThatAdvancesRunsToTheTarget) {
    // The same driver with an interval the time resolves: the guard does not fire.
    const Scene sc = thermostat_scene();
    DriverList<2> drivers;
    drivers.push_back(std::make_unique<KickClockBelowResolution>(0.5, 0.25));
    const auto* clock = static_cast<const KickClockBelowResolution*>(drivers[0].get());
    ObservableList<2> observables;
    auto runner = sc.engine->make<2>(sc, drivers, observables);
    EXPECT_EQ(runner->advance(2, UINT64_MAX, UINT64_MAX, nullptr), Advance::Reached);
    EXPECT_EQ(clock->kicks, 7);  // at 0.5, 0.75, ..., 2
    EXPECT_TRUE(runner->failure().empty()) << runner->failure();
}

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
