// Strong gravity, weak driving (issue 6): a bed of 40 grains (4 layers in a cell 10 wide, periodic
// in x) settling on a floor under g = m = d = 1 must end AT REST: kinetic energy per grain
// << m g d, and its centre of mass near the height of a resting packing, between the densest
// (hexagonal rows: 0.5 + 1.5 sqrt(3)/2 = 1.80) and the square stacking (2.0), with 0.1 of slack
// for defects of a poured packing.
//  - event-driven: inelastic collapse against the floor is the classic failure. With the default
//    tc = 1e-6 the watchdog stops the run in the TC regime (tests/extremes/test_watchdog.cpp).
//    With tc = 1e-2 the TC model's elastic micro-collisions (rebound speeds ~ g tc,
//    docs/physics.md) ARE the rest state; measured: ~50 (static floor) and ~140 (vibrated) events
//    per grain per tc
//    (~1e7 events, seconds), so the run is allowed (run.watchdog.max_events_per_tc: 1000) and must
//    give a bed at rest, with a kinetic energy per grain of order m (g tc)^2 = 1e-4 m g d: bound
//    1e-3 m g d. Same on a floor vibrated at W = 4e-5 (Gamma = A omega^2 / g = 0.04 < 1: the bed
//    never leaves it).
//  - dem (k_n = 2e5 m g / d): at rest the floor carries the whole weight, so by statics
//    sum over floor contacts of k_n delta = N m g: checked to 2%, with the overlaps then of order
//    m g / k_n.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

struct BedState {
    std::vector<double> y, speed2;  // heights and squared speeds at the last frame
    YAML::Node summary;
};

// The bed's grains and its floor with restitution 0.5, the top of the box elastic.
const char* kEventDrivenContacts = "{alpha: 0.5, pairs: [{between: [g, box], alpha: 1}]}";
const char* kDemContacts =
    "{law: linear_dashpot, restitution: 0.5, stiffness: 2.0e+5, pairs: [{between: [g, box], "
    "restitution: 1}]}";

BedState run_bed(const std::string& engine, const std::string& contacts, const std::string& driver,
                 const std::string& tag) {
    // Ten samples: with fewer than eight the kinetic energy has no error bar and the status would
    // be `unreliable` instead of `completed`.
    const std::string yaml = fmt::format(R"(
dimension: 2
seed: 1
gravity: [0, -1]
box: {{lengths: [10, 40], periodic: [true, false]}}
species: [{{name: g, count: 40, mass: 1, diameter: 1}}]
interactions: {}
initial: {{placement: lattice, temperature: 0.01}}
engine: {}
drivers: [{}]
observables: [{{type: kinetic_energy}}]
output: {{frames: 1}}
run: {{unit: time, equilibration: 40, measurement: 5, sample_interval: 0.5,
      watchdog: {{max_events_per_tc: 1000}}}}
)",
                                         contacts, engine, driver);
    BedState b;
    b.summary = testing::run_yaml(yaml, tag);
    auto f = h5::File::open_read((testing::temp_dir() / (tag + ".h5")).string());
    const auto r = f.root().read_doubles("particles/all/position/value");
    const auto v = f.root().read_doubles("particles/all/velocity/value");
    for (std::size_t i = 0; i < 40; ++i) {
        b.y.push_back(r[2 * i + 1]);
        b.speed2.push_back(v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]);
    }
    return b;
}

void expect_at_rest(const BedState& b, double floor, double ke_bound) {
    EXPECT_EQ(b.summary["status"].as<std::string>(), "completed");
    double ke = 0, h = 0;
    for (std::size_t i = 0; i < b.y.size(); ++i) {
        ASSERT_TRUE(std::isfinite(b.y[i]) && std::isfinite(b.speed2[i]));
        ke += 0.5 * b.speed2[i] / 40;
        h += (b.y[i] - floor) / 40;
    }
    EXPECT_LT(ke, ke_bound) << "kinetic energy per grain in m g d";
    EXPECT_GT(h, 1.80 - 0.1) << "centre of mass below the densest packing";
    EXPECT_LT(h, 2.0 + 0.1) << "centre of mass above a resting packing";
}

TEST(GravityBed, EventDrivenBedComesToRestOnAStaticFloor) {
    const BedState b = run_bed("{tc: 1.0e-2}", kEventDrivenContacts,
                               "{type: static_wall, axis: y, side: lower}", "ed");
    expect_at_rest(b, 0.0, 1e-3);
}

TEST(GravityBed, EventDrivenBedStaysAtRestOnAWeaklyVibratedFloor) {
    // A = 1e-3 d, f = 1 / sqrt(d/g): W = (A omega)^2 / (g d) = 4e-5, Gamma = 0.04.
    const BedState b = run_bed(
        "{tc: 1.0e-2}", kEventDrivenContacts,
        "{type: vibrating_wall, axis: y, side: lower, waveform: sinusoid, amplitude: 1.0e-3, "
        "frequency: 1}",
        "ed_vibrated");
    // The floor's speed A omega = 6e-3 adds at most m (A omega)^2 / 2 = 2e-5: bound 1e-3 again.
    expect_at_rest(b, 1.0e-3, 1e-3);
}

TEST(GravityBed, DemBedRestsOnAStaticFloorWithTheWeightInItsContacts) {
    const BedState b =
        run_bed("{type: dem}", kDemContacts, "{type: static_wall, axis: y, side: lower}", "dem");
    expect_at_rest(b, 0.0, 1e-6);
    // Statics: the floor springs carry the whole weight N m g.
    double floor_force = 0;
    for (double y : b.y) floor_force += 2.0e5 * std::max(0.0, 0.5 - y);
    EXPECT_NEAR(floor_force / 40.0, 1.0, 0.02) << "floor force / (N m g)";
}

}  // namespace
}  // namespace gran
