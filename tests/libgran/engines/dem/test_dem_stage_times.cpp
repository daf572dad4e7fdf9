// The DEM engine's stage clock (DemEngine::time_stages, libgran/core/stage_clock.hpp): every
// stage of a step timed, nothing outside the steps counted, and no bit of the run changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "libgran/engines/dem/engine.hpp"
#include "tests/support/dem_beds.hpp"

namespace gran {
namespace {

using testing::Bed;
using testing::bed_engine;
using testing::dense_bed;
using testing::expect_same_state;

double wall_seconds_of(const auto& work) {
    const auto t0 = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(DemStageTimes, StayZeroUntilTimingIsSwitchedOn) {
    DemEngine<3> e = bed_engine<3>(dense_bed<3>(600), 1);
    e.steps(50);
    EXPECT_EQ(e.stage_times().total(), 0.0);
    EXPECT_EQ(e.stage_times().kicks_and_drift, 0.0);
}

// The dense bed rebuilds its list, touches its floor and has many contacts: every stage has work.
TEST(DemStageTimes, EveryStageOfABedIsTimedAndTheStagesMakeUpTheStepsWallTime) {
    for (int threads : {1, 2}) {
        DemEngine<3> e = bed_engine<3>(dense_bed<3>(2000), threads);
        e.time_stages(true);
        const std::uint64_t rebuilds = e.counters().rebuilds;
        const double wall = wall_seconds_of([&] { e.steps(300); });
        ASSERT_GT(e.counters().rebuilds, rebuilds) << "the comparison needs list builds";
        const DemStageTimes& t = e.stage_times();
        EXPECT_GT(t.kicks_and_drift, 0) << threads << " threads";
        EXPECT_GT(t.neighbour_list, 0) << threads << " threads";
        EXPECT_GT(t.pair_contacts, 0) << threads << " threads";
        EXPECT_GT(t.wall_contacts, 0) << threads << " threads";
        // Between the laps there are only counter updates: the stages are nearly all of it.
        EXPECT_LE(t.total(), wall) << threads << " threads";
        EXPECT_GT(t.total(), 0.8 * wall) << threads << " threads";
    }
}

// A pause between steps, and forces re-evaluated after it (set_wall): neither the pause nor any
// time before the re-evaluation is counted as a stage.
TEST(DemStageTimes, TimeBetweenStepsIsNotCounted) {
    DemEngine<3> e = bed_engine<3>(dense_bed<3>(600), 1);
    e.time_stages(true);
    const double first = wall_seconds_of([&] { e.steps(20); });
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    const double second = wall_seconds_of([&] {
        e.set_wall(2, 0, WallMotion::sinusoid(0.2, 10.0), 0);  // re-evaluates the forces
        e.steps(20);
    });
    EXPECT_LE(e.stage_times().total(), first + second);
    // Switched off: the times are kept and no longer grow.
    e.time_stages(false);
    const double kept = e.stage_times().total();
    EXPECT_GT(kept, 0);
    e.steps(20);
    EXPECT_EQ(e.stage_times().total(), kept);
}

TEST(DemStageTimes, TimingChangesNoBitOfTheRun) {
    const Bed<3> bed = dense_bed<3>(2000);
    DemEngine<3> plain = bed_engine<3>(bed, 1);
    DemEngine<3> timed = bed_engine<3>(bed, 1);
    DemEngine<3> timed_two = bed_engine<3>(bed, 2);
    timed.time_stages(true);
    timed_two.time_stages(true);
    plain.steps(200);
    timed.steps(200);
    timed_two.steps(200);
    EXPECT_GT(timed.stage_times().total(), 0);
    expect_same_state(plain, timed, "timed");
    expect_same_state(plain, timed_two, "timed, 2 threads");
}

// The tally of the threads' shares (DemEngine::thread_shares), checked against the list itself
// over one build: the halo grains of a two-thread cut are the grains from the second share's
// first row on that are partners of an earlier row (the row holding the middle entry starts the
// second share); the search imbalance is the largest share's work over the mean.
TEST(DemStageTimes, OnTwoThreadsTheHaloGrainsAreThePartnersOfTheFirstSharesRows) {
    DemEngine<3> e = bed_engine<3>(dense_bed<3>(2000), 2);
    e.steps(5);
    e.time_stages(true);
    const std::uint64_t rebuilds = e.counters().rebuilds;
    for (int k = 0; k < 2000 && e.counters().rebuilds == rebuilds; ++k) e.step();
    ASSERT_EQ(e.counters().rebuilds, rebuilds + 1) << "the comparison needs one list build";
    const DemThreadShares& s = e.thread_shares();
    ASSERT_EQ(s.splits, 1u);
    ASSERT_EQ(s.searches, 1u);

    const DemNeighbourList<3>& list = e.neighbour_list();
    const std::size_t n = e.particles().size();
    const std::size_t middle = (list.entries() + 1) / 2;
    const auto cut = std::size_t(
        std::lower_bound(list.start.begin(), list.start.end() - 1, std::uint32_t(middle)) -
        list.start.begin());
    std::vector<bool> halo(n, false);
    for (std::size_t i = 0; i < cut; ++i) {
        for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
            if (list.partner[k] >= cut) halo[list.partner[k]] = true;
        }
    }
    const auto expected = double(std::count(halo.begin(), halo.end(), true));
    EXPECT_GT(expected, 0) << "a dense bed cut in two has grains on both sides of the cut";
    EXPECT_EQ(s.halo_grains, expected);
    EXPECT_EQ(s.grains, double(n));

    const std::vector<std::uint64_t>& work = list.search_work();
    ASSERT_EQ(work.size(), 2u);
    const double mean = 0.5 * double(work[0] + work[1]);
    EXPECT_DOUBLE_EQ(s.search_imbalance, double(std::max(work[0], work[1])) / mean);

    DemEngine<3> one = bed_engine<3>(dense_bed<3>(2000), 1);
    one.time_stages(true);
    one.steps(300);
    EXPECT_EQ(one.thread_shares().splits, 0u) << "one thread cuts nothing";
    EXPECT_EQ(one.thread_shares().searches, 0u);
}

// The list search's seconds are tallied on any number of threads, once per build: on one
// thread the slowest thread is all of them; on two, the slowest is one of two positive times,
// so it is at least half their sum and below it.
TEST(DemStageTimes, TheListSearchIsTimedPerThreadAtEveryBuild) {
    for (const int threads : {1, 2}) {
        DemEngine<3> e = bed_engine<3>(dense_bed<3>(2000), threads);
        e.time_stages(true);
        const std::uint64_t before = e.counters().rebuilds;
        e.steps(300);
        const DemThreadShares& s = e.thread_shares();
        const std::uint64_t builds = e.counters().rebuilds - before;
        ASSERT_GT(builds, 2u);
        EXPECT_EQ(s.timed_searches, builds) << threads << " threads";
        EXPECT_GT(s.search_slowest, 0.0);
        if (threads == 1) {
            EXPECT_EQ(s.search_slowest, s.search_all);
        } else {
            EXPECT_GE(s.search_slowest, 0.5 * s.search_all);
            EXPECT_LT(s.search_slowest, s.search_all);
        }
        e.time_stages(false);
        e.time_stages(true);
        EXPECT_EQ(e.thread_shares().timed_searches, 0u) << "a new timing starts from zero";
    }
}

}  // namespace
}  // namespace gran
