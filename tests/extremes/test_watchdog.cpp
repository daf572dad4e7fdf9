// The run watchdog (libgran/watchdog.hpp, issue 6): each condition is triggered deliberately, on
// the plain check and through the scene path, and the run stops with a message that names what
// happened, the simulated time and the key to change; `gran run` exits with status 1 and keeps
// what was measured. Without the watchdog the unguarded collapse below hangs (checked by hand:
// `timeout 10 gran run ... --set run.watchdog.enabled=false` is killed by the timeout).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "libgran/core/h5.hpp"
#include "libgran/run/watchdog.hpp"
#include "tests/support/contains.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/run_scene.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace gran {
namespace {

using testing::contains;

// --- the plain check ------------------------------------------------------------------------

ProgressWindow healthy_window() {
    ProgressWindow w;
    w.events = 1000;
    w.t_begin = 1.0;
    w.t_end = 2.0;
    w.particles = 100;       // 10 events per particle per unit time
    w.reference_rate = 5.0;  // first window: 5
    w.tc = 1e-6;             // 1e-5 events per particle per tc
    return w;
}

TEST(WatchdogCheck, AHealthyWindowPasses) {
    EXPECT_EQ(check_progress(WatchdogSettings{}, healthy_window()), "");
    EXPECT_DOUBLE_EQ(event_rate(healthy_window()), 10.0);
}

TEST(WatchdogCheck, AWindowThatLeavesTheTimeUnchangedIsAStall) {
    ProgressWindow w = healthy_window();
    w.t_end = w.t_begin;
    const std::string why = check_progress(WatchdogSettings{}, w);
    EXPECT_TRUE(contains(why, "simulated time stopped advancing at t = 1"));
    EXPECT_TRUE(contains(why, "engine.collapse_guard: tc"));
    WatchdogSettings off;
    off.enabled = false;
    EXPECT_EQ(check_progress(off, w), "");
}

TEST(WatchdogCheck, MoreEventsPerTcWindowThanTheLimitIsTheTcRegime) {
    ProgressWindow w = healthy_window();
    w.events = 100 * 200000;  // 2e5 events per particle per unit time: 0.2 per tc > 0.1
    const std::string why = check_progress(WatchdogSettings{}, w);
    EXPECT_TRUE(contains(why, "micro-collisions dominate at t = 2"));
    EXPECT_TRUE(contains(why, "run.watchdog.max_events_per_tc"));
    w.tc = 0;  // guard off: no TC regime, but 4e4 x the first window's rate is not yet 1e6
    EXPECT_EQ(check_progress(WatchdogSettings{}, w), "");
}

TEST(WatchdogCheck, ARateAboveMaxGrowthTimesTheFirstWindowsIsACollapse) {
    ProgressWindow w = healthy_window();
    w.tc = 0;
    WatchdogSettings s;
    s.max_rate_growth = 1.9;  // rate 10 = 2 x the reference 5
    EXPECT_TRUE(contains(check_progress(s, w), "event rate exploded at t = 2"));
    s.max_rate_growth = 2.1;
    EXPECT_EQ(check_progress(s, w), "");
}

// --- through the scene path -----------------------------------------------------------------

// A dense, strongly inelastic gas without the TC model: inelastic collapse (McNamara & Young,
// Phys. Fluids A 4, 496 (1992)): collision times shrink geometrically until the time stops moving.
std::string unguarded_collapse(double alpha, const std::string& watchdog) {
    return "dimension: 2\nseed: 2\nspecies: [{name: a, count: 200}]\ninteractions: {alpha: " +
           std::to_string(alpha) +
           "}\nbox: {packing_fraction: 0.3}\nengine: {collapse_guard: none}\n"
           "observables: [{type: kinetic_energy}]\n"
           "run: {unit: time, measurement: 100, sample_interval: 1, watchdog: " +
           watchdog + "}\n";
}

TEST(WatchdogRun, UnguardedInelasticCollapseStopsWhenTheTimeStalls) {
    const YAML::Node s = testing::run_yaml(
        unguarded_collapse(0.05, "{window: 10000, max_rate_growth: 1e300}"), "stall");
    EXPECT_EQ(s["status"].as<std::string>(), "stopped by the watchdog");
    EXPECT_TRUE(contains(s["error"].as<std::string>(), "simulated time stopped advancing"));
}

TEST(WatchdogRun, UnguardedInelasticCollapseStopsWhenTheEventRateExplodes) {
    // alpha = 0.3: the rate climbs over ~1e6 x the first window's before the time stalls; with
    // windows of 200 events the growth is seen first (limit lowered to 1e3 to see it early).
    const YAML::Node s =
        testing::run_yaml(unguarded_collapse(0.3, "{window: 200, max_rate_growth: 1e3}"), "rate");
    EXPECT_EQ(s["status"].as<std::string>(), "stopped by the watchdog");
    EXPECT_TRUE(contains(s["error"].as<std::string>(), "event rate exploded"));
    EXPECT_TRUE(contains(s["error"].as<std::string>(), "run.watchdog.max_rate_growth"));
}

// An inelastic bed settling on a static floor under gravity on the event-driven engine: at rest it
// is resolved by TC micro-bounces every ~2 tc (docs/physics.md), ~1e5 events per particle per unit
// time with tc = 1e-6: the run would take ~1e5 times longer than a gas of the same size.
const std::string kBedAtRest = R"(
dimension: 2
seed: 1
gravity: [0, -1]
box: {lengths: [10, 40], periodic: [true, false]}
species: [{name: g, count: 40, mass: 1, diameter: 1}]
interactions: {alpha: 0.5, pairs: [{between: [g, box], alpha: 1}]}
initial: {placement: lattice, temperature: 0.01}
drivers: [{type: static_wall, axis: y, side: lower}]
observables: [{type: barycentric_height}, {type: kinetic_energy}]
run: {unit: time, measurement: 50, sample_interval: 1}
)";

TEST(WatchdogRun, EventDrivenBedAtRestStopsInTheTcRegimeWithAdvice) {
    const YAML::Node s = testing::run_yaml(kBedAtRest, "bed");
    EXPECT_EQ(s["status"].as<std::string>(), "stopped by the watchdog");
    const std::string why = s["error"].as<std::string>();
    EXPECT_TRUE(contains(why, "micro-collisions dominate at t = "));
    EXPECT_TRUE(contains(why, "engine.type: dem"));
    // What was measured before the stop is kept: the bed settled for several time units.
    EXPECT_GT(s["performance"]["events"].as<double>(), 1e6);
}

// Gravity 1e300: velocities stay finite for a step or two, their squares do not.
TEST(WatchdogRun, DemRunWithOverflowingStateStopsInsteadOfWritingNaN) {
    const YAML::Node s = testing::run_yaml(R"(
dimension: 2
seed: 1
gravity: [0, -1e300]
box: {lengths: [10, 20], periodic: [true, false]}
species: [{name: g, count: 20, mass: 1, diameter: 1}]
interactions: {law: linear_dashpot, stiffness: 1e5}
engine: {type: dem}
observables: [{type: kinetic_energy}]
run: {unit: time, measurement: 1, sample_interval: 0.1, watchdog: {window: 100}}
)",
                                           "overflow");
    EXPECT_EQ(s["status"].as<std::string>(), "stopped by the watchdog");
    EXPECT_TRUE(contains(s["error"].as<std::string>(), "kinetic energy overflowed"));
    EXPECT_TRUE(contains(s["error"].as<std::string>(), "dem engine"));
}

// --- the command line -----------------------------------------------------------------------

class WatchdogCli : public testing::TempDirTest {};

TEST_F(WatchdogCli, StopExitsWithStatusOneAndWritesTheResultAsIncomplete) {
    const std::string scene = path("bed.yaml");
    {
        std::ofstream out(scene);
        out << kBedAtRest;
    }
    const std::string out = path("bed.h5");
    const testing::Outcome o = testing::run_gran({"run", scene, "-o", out, "-q"});
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_TRUE(contains(o.output, "gran: error: watchdog: the TC model's micro-collisions"));
    ASSERT_TRUE(std::filesystem::exists(out)) << o.output;
    auto file = h5::File::open_read(out);
    auto root = file.root();
    EXPECT_EQ(root.read_int64s("performance/completed"), std::vector<std::int64_t>{0});
    EXPECT_EQ(root.read_int64s("performance/interrupted"), std::vector<std::int64_t>{0});
}

}  // namespace
}  // namespace gran
