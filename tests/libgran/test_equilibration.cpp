// Warm-up detection (libgran/equilibration.hpp): MSER-5 must find an injected transient where it
// ends and report nothing for stationary series.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "libgran/equilibration.hpp"
#include "tests/support/random_series.hpp"

namespace gran {
namespace {

// x_t = A exp(-t / tau) + unit white noise. MSER drops batch d when its squared deviation from the
// remaining mean exceeds ~2 sigma_b^2 (dropping one batch of m - d changes (m - d)^2 by a factor
// 1 - 2 / (m - d)); in expectation bias^2 + sigma_b^2 > 2 sigma_b^2, i.e. until the transient has
// decayed to the batch-mean noise sigma_b = 1 / sqrt(5): d* ~ tau ln(A sqrt(5)). For A = 5 that is
// 2.41 tau, for A = 20 3.80 tau. Over 200 seeds (a numpy prototype of the same estimator) d* stayed
// within [1.8, 3.7] tau and [3.1, 4.7] tau: +-1.3 tau holds every seed with margin, while a
// truncation at the e-folding time (1 tau) or none at all fails.
class MserTransient : public ::testing::TestWithParam<double> {};

TEST_P(MserTransient, TruncatesWhereTheTransientSinksIntoTheBatchNoise) {
    const double amplitude = GetParam();
    const double tau = 200;
    const std::size_t n = 20000;
    const double expected = tau * std::log(amplitude * std::sqrt(double(kMserBatch)));
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        auto x = testing::gaussian_series(n, 0.0, 1.0, seed);
        for (std::size_t t = 0; t < n; ++t) x[t] += amplitude * std::exp(-double(t) / tau);
        const std::size_t d = mser_truncation(x);
        EXPECT_NEAR(double(d), expected, 1.3 * tau) << "seed " << seed;
        EXPECT_EQ(d % kMserBatch, 0u);

        const EquilibrationCheck c = check_equilibration(x);
        EXPECT_EQ(c.truncation, d);
        EXPECT_DOUBLE_EQ(c.truncation_fraction, double(d) / double(n));
        // d* > 10% of the samples: reported as relaxing.
        EXPECT_EQ(c.relaxing, c.truncation_fraction > kRelaxingFraction);
        // The transient adds A tau / (n/2) = 0.02 A to the first half's mean; the difference of
        // the halves has error sqrt(2) sqrt(2/n) = 0.014: z ~ -7 (A = 5) and -28 (A = 20).
        EXPECT_LT(c.drift_z, -4.0) << "seed " << seed;
    }
}

INSTANTIATE_TEST_SUITE_P(Amplitude, MserTransient, ::testing::Values(5.0, 20.0));

TEST(Mser, LongTransientIsReportedAsRelaxing) {
    // tau = 1000 of 20000 samples, A = 20: d* ~ 3.8 tau = 19% of the measurement.
    auto x = testing::gaussian_series(20000, 3.0, 1.0, 9);
    for (std::size_t t = 0; t < x.size(); ++t) x[t] += 20 * std::exp(-double(t) / 1000);
    const EquilibrationCheck c = check_equilibration(x);
    EXPECT_TRUE(c.relaxing);
    EXPECT_GT(c.truncation_fraction, 0.15);
    EXPECT_LT(c.truncation_fraction, 0.25);
}

// Stationary series: white noise and AR(1) with tau_int = 9.5 (n ~ 2000 tau_int). In the numpy
// prototype over 200 seeds the 99th percentile of d*/n was 0.25% (white) and 0.6% (AR(1)); 2% is
// a margin of 3 and still 5 times below the relaxing threshold.
TEST(Mser, StationarySeriesAreNotTruncated) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        for (const auto& x : {testing::gaussian_series(20000, 1.0, 1.0, seed),
                              testing::ar1_series(20000, 0.9, 100 + seed)}) {
            const EquilibrationCheck c = check_equilibration(x);
            EXPECT_LT(c.truncation_fraction, 0.02) << "seed " << seed;
            EXPECT_FALSE(c.relaxing);
            EXPECT_LT(std::abs(c.drift_z), 4.0) << "seed " << seed;
        }
    }
}

TEST(Mser, SearchesOnlyTheFirstHalf) {
    // A step at 80%: the best truncation would be beyond the searched half, so d* <= n / 2.
    std::vector<double> x(1000, 0.0);
    for (std::size_t t = 800; t < x.size(); ++t) x[t] = 10.0 + 0.001 * double(t % 7);
    for (std::size_t t = 0; t < 800; ++t) x[t] = 0.001 * double(t % 5);
    EXPECT_LE(mser_truncation(x), x.size() / 2);
}

TEST(Mser, FewerThanTenBatchesAreNotSearched) {
    std::vector<double> x(49, 0.0);
    x[0] = 100;
    EXPECT_EQ(mser_truncation(x), 0u);
    x.push_back(0.0);  // 50 samples = 10 batches: the outlier batch is dropped
    EXPECT_EQ(mser_truncation(x), kMserBatch);
}

}  // namespace
}  // namespace gran
