// ShareBalance (libgran/core/share_balance.hpp): the threads' fractions of a loop's work follow
// their measured speeds, so that they would finish together.
#include <gtest/gtest.h>

#include <vector>

#include "libgran/core/share_balance.hpp"

namespace gran {
namespace {

// Rounds of a threaded loop on threads of the given speeds (work per second): in each of
// `steps` steps each thread adds the time its share of unit work took; then the shares are
// rebalanced.
void run_rounds(ShareBalance& b, const std::vector<double>& speed, int rounds, int steps = 20) {
    for (int r = 0; r < rounds; ++r) {
        for (int s = 0; s < steps; ++s) {
            for (std::size_t t = 0; t < speed.size(); ++t) b.add(t, b.fraction(t) / speed[t]);
            b.end_step();
        }
        b.rebalance();
    }
}

TEST(ShareBalance, StartsWithEqualFractions) {
    ShareBalance b;
    b.reset(4);
    ASSERT_EQ(b.parts(), 4u);
    for (std::size_t t = 0; t < 4; ++t) EXPECT_DOUBLE_EQ(b.fraction(t), 0.25);
    EXPECT_DOUBLE_EQ(b.begins(0), 0.0);
    EXPECT_DOUBLE_EQ(b.begins(2), 0.5);
}

TEST(ShareBalance, ThreadsOfEqualSpeedKeepEqualShares) {
    ShareBalance b;
    b.reset(3);
    run_rounds(b, {2.0, 2.0, 2.0}, 10);
    for (std::size_t t = 0; t < 3; ++t) EXPECT_NEAR(b.fraction(t), 1.0 / 3, 1e-12);
}

// Balanced, each thread's time is its fraction over its speed: equal when the fractions are in
// proportion to the speeds, 2/3 and 1/3 for a thread twice as fast as the other.
TEST(ShareBalance, AThreadHalfAsFastConvergesToAThirdOfTheWork) {
    ShareBalance b;
    b.reset(2);
    run_rounds(b, {1.0, 0.5}, 1);
    EXPECT_NEAR(b.fraction(0), 0.5 * (0.5 + 2.0 / 3), 1e-12) << "half-way after one round";
    run_rounds(b, {1.0, 0.5}, 30);
    EXPECT_NEAR(b.fraction(0), 2.0 / 3, 1e-6);
    EXPECT_NEAR(b.fraction(1), 1.0 / 3, 1e-6);
    EXPECT_NEAR(b.begins(1), 2.0 / 3, 1e-6);
    // The cores swap their speeds: the shares follow.
    run_rounds(b, {0.5, 1.0}, 30);
    EXPECT_NEAR(b.fraction(0), 1.0 / 3, 1e-6);
}

// A step is a sample only if every thread timed its share in it, and not the step in which the
// shares changed (cut partly by the old ones).
TEST(ShareBalance, SharesStayUnchangedUntilAStepTimedEveryThread) {
    ShareBalance b;
    b.reset(2);
    b.add(0, 1.0);  // thread 1 did not time its share: no sample
    b.end_step();
    b.rebalance();
    EXPECT_DOUBLE_EQ(b.fraction(0), 0.5);
    b.add(0, 1.0);  // the step of the rebalance: not a sample
    b.add(1, 3.0);
    b.end_step();
    b.rebalance();
    EXPECT_DOUBLE_EQ(b.fraction(0), 0.5);
    b.end_step();
    b.add(0, 1.0);
    b.add(1, 3.0);
    b.end_step();
    b.rebalance();
    EXPECT_NEAR(b.fraction(0), 0.5 * (0.5 + 0.75), 1e-12) << "speeds 0.5 / 1 and 0.5 / 3";
    ShareBalance one;
    one.reset(1);
    one.add(0, 1.0);
    one.end_step();
    one.rebalance();
    EXPECT_DOUBLE_EQ(one.fraction(0), 1.0);
}

// A thread preempted for a few steps (another process on its core) stalls those steps whatever
// its share: the median step time ignores them, the mean would not.
TEST(ShareBalance, AFewPreemptedStepsDoNotMoveTheShares) {
    ShareBalance b;
    b.reset(2);
    for (int s = 0; s < 20; ++s) {
        b.add(0, s % 5 == 0 ? 10.0 : 1.0);  // four of twenty steps ten times as long
        b.add(1, 1.0);
        b.end_step();
    }
    b.rebalance();
    EXPECT_DOUBLE_EQ(b.fraction(0), 0.5);
}

// More steps than samples kept: the latest kSamples decide.
TEST(ShareBalance, TheLatestStepsDecide) {
    ShareBalance b;
    b.reset(2);
    for (std::size_t s = 0; s < 3 * ShareBalance::kSamples; ++s) {
        const bool late = s >= 2 * ShareBalance::kSamples;
        b.add(0, late ? 2.0 : 1.0);
        b.add(1, 1.0);
        b.end_step();
    }
    b.rebalance();
    EXPECT_NEAR(b.fraction(0), 0.5 * (0.5 + 1.0 / 3), 1e-12);
}

// A nearly stalled thread keeps a share (a quarter of an equal one before the fractions are
// normalised), so that its speed is still measured when its core recovers.
TEST(ShareBalance, AStalledThreadKeepsASmallShare) {
    ShareBalance b;
    b.reset(2);
    run_rounds(b, {1.0, 1e-9}, 40);
    EXPECT_GT(b.fraction(1), 0.125 / 1.125 - 1e-12);
    EXPECT_LT(b.fraction(1), 0.12);
    EXPECT_NEAR(b.fraction(0) + b.fraction(1), 1.0, 1e-12);
    run_rounds(b, {1.0, 1.0}, 40);
    EXPECT_NEAR(b.fraction(1), 0.5, 1e-6) << "the recovered thread gets its share back";
}

TEST(ShareBalance, FixedFractionsAreKeptAsGiven) {
    ShareBalance b;
    b.reset(3);
    b.fix({0.2, 0.5, 0.3});
    EXPECT_DOUBLE_EQ(b.fraction(1), 0.5);
    EXPECT_DOUBLE_EQ(b.begins(2), 0.7);
}

}  // namespace
}  // namespace gran
