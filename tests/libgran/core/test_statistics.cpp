// Tests of the error analysis of correlated time series (libgran/statistics.hpp). The reference
// values are analytic: sigma/sqrt(n) for independent samples, sqrt((1+phi)/(1-phi)/n) for an AR(1)
// process of unit variance (tau_int = (1+phi)/(2(1-phi))), and the delta method for ratios. Seeds
// are fixed (tests/support/random_series.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <stdexcept>
#include <vector>

#include "libgran/core/autocorrelation.hpp"
#include "libgran/core/statistics.hpp"
#include "tests/support/random_series.hpp"

namespace gran {
namespace {

using testing::ar1_series;
using testing::ar1_tau_int;
using testing::gaussian_series;

double ar1_standard_error(double phi, std::size_t n) {
    return std::sqrt((1 + phi) / (1 - phi) / static_cast<double>(n));
}

double plain_mean(std::span<const double> x) {
    return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

// sigma/sqrt(n) with the sample standard deviation: what one would report ignoring correlations.
double naive_error(std::span<const double> x) {
    const double m = plain_mean(x);
    double sq = 0;
    for (double v : x) sq += (v - m) * (v - m);
    const double n = static_cast<double>(x.size());
    return std::sqrt(sq / (n - 1) / n);
}

TEST(BlockAverage, IndependentSamplesGiveSigmaOverSqrtN) {
    const std::size_t n = 1 << 16;
    const double mu = 3.0, sigma = 2.0;
    const auto x = gaussian_series(n, mu, sigma, 12345);
    const Estimate e = block_average(x);
    const double expected = sigma / std::sqrt(static_cast<double>(n));
    EXPECT_NEAR(e.error, expected, 0.15 * expected);
    EXPECT_NEAR(e.value, plain_mean(x), 1e-12);
    EXPECT_LT(std::abs(e.value - mu), 4 * e.error);
}

TEST(BlockAverage, Ar1ErrorMatchesAnalyticWhileNaiveErrorIsFourTimesTooSmall) {
    const std::size_t n = 1 << 18;
    const double phi = 0.9;
    const auto x = ar1_series(n, phi, 2024);
    const double exact = ar1_standard_error(phi, n);

    const Estimate e = block_average(x);
    EXPECT_NEAR(e.error, exact, 0.20 * exact);
    EXPECT_LT(std::abs(e.value), 4 * exact);

    // sqrt((1+phi)/(1-phi)) = sqrt(19) = 4.36: the correlation must be what makes blocking matter.
    const double naive = naive_error(x);
    EXPECT_NEAR(exact / naive, std::sqrt(19.0), 0.4);
    EXPECT_GT(e.error / naive, 3.5);
}

// Calibration over many independent replicas: the reported error must be the actual scatter of
// the mean, so that about 68% of the replicas lie within one error of the true mean (0 here).
TEST(BlockAverage, ErrorsOfAr1ReplicasHaveNominalCoverage) {
    const std::size_t n = 1 << 14;
    const double phi = 0.9;
    const int replicas = 200;
    int within_one = 0, within_two = 0;
    double mean_ratio = 0;
    for (int r = 0; r < replicas; ++r) {
        const auto x = ar1_series(n, phi, 1000 + static_cast<std::uint64_t>(r));
        const Estimate e = block_average(x);
        within_one += std::abs(e.value) < e.error;
        within_two += std::abs(e.value) < 2 * e.error;
        mean_ratio += e.error / ar1_standard_error(phi, n) / replicas;
    }
    // Binomial sd of the fraction for p = 0.68 and 200 replicas is 0.033. Blocking is known to
    // be a few per cent low at n ~ 1700 tau_int (the plateau is declared once the residual
    // rise is within noise; ~0.95 here over many seeds), hence the asymmetric bounds on the ratio.
    EXPECT_NEAR(within_one / double(replicas), 0.683, 0.10);
    EXPECT_NEAR(within_two / double(replicas), 0.954, 0.06);
    EXPECT_GT(mean_ratio, 0.90);
    EXPECT_LT(mean_ratio, 1.05);
}

TEST(BlockAverage, FewerThanEightSamplesGiveNaNErrorAndPlainMean) {
    const std::vector<double> x{1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0};
    const Estimate e = block_average(x);
    EXPECT_DOUBLE_EQ(e.value, 127.0 / 7.0);
    EXPECT_TRUE(std::isnan(e.error));
    EXPECT_TRUE(std::isnan(e.tau_int));
    EXPECT_TRUE(std::isnan(e.n_eff));
    EXPECT_EQ(e.samples, 7u);

    const std::vector<double> eight{1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0};
    EXPECT_TRUE(std::isfinite(block_average(eight).error));
}

TEST(BlockAverage, EmptySeriesGivesNaN) {
    const Estimate e = block_average(std::span<const double>{});
    EXPECT_TRUE(std::isnan(e.value));
    EXPECT_TRUE(std::isnan(e.error));
}

TEST(BlockAverage, ConstantSeriesHasExactlyZeroError) {
    // 0.1 is not representable: a naive sum/n would leave rounding residue in the variance.
    const std::vector<double> x(1000, 0.1);
    const Estimate e = block_average(x);
    EXPECT_EQ(e.value, 0.1);
    EXPECT_EQ(e.error, 0.0);
    // No fluctuation, so no correlation to measure: tau_int and n_eff are undefined, not 1/2 and n.
    EXPECT_TRUE(std::isnan(e.tau_int));
    EXPECT_TRUE(std::isnan(e.n_eff));
    EXPECT_EQ(e.samples, 1000u);
}

TEST(BlockAverage, LargeOffsetDoesNotDestroyPrecision) {
    auto x = gaussian_series(1 << 12, 0.0, 1.0, 7);
    const double small = block_average(x).error;
    for (double& v : x) v += 1e9;
    EXPECT_NEAR(block_average(x).error, small, 1e-3 * small);
}

TEST(BlockMeans, DropsRemainderAtStartAndAveragesContiguousBlocks) {
    const std::vector<double> x{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    // Length 3 blocks from index 1: {1,2,3}, {4,5,6}, {7,8,9}.
    const auto m = block_means(x, 3);
    ASSERT_EQ(m.size(), 3u);
    EXPECT_DOUBLE_EQ(m[0], 2.0);
    EXPECT_DOUBLE_EQ(m[1], 5.0);
    EXPECT_DOUBLE_EQ(m[2], 8.0);

    const auto all = block_means(x, 10);
    for (std::size_t i = 0; i < all.size(); ++i) EXPECT_DOUBLE_EQ(all[i], x[i]);
    EXPECT_DOUBLE_EQ(block_means(x, 1)[0], 4.5);
}

TEST(BlockMeans, RejectsZeroBlocksAndMoreBlocksThanSamples) {
    const std::vector<double> x{1, 2, 3};
    EXPECT_THROW(block_means(x, 0), std::invalid_argument);
    EXPECT_THROW(block_means(x, 4), std::invalid_argument);
}

TEST(SuggestedBlocks, IsClampedToEightToSixtyFourAndToLength) {
    // Independent samples decorrelate at once: n blocks, clamped to 64.
    EXPECT_EQ(suggested_blocks(gaussian_series(4096, 0, 1, 3)), 64u);
    // Below 8 samples: one block per sample, never more blocks than samples.
    EXPECT_EQ(suggested_blocks(std::vector<double>{1, 2, 3, 4, 5}), 5u);
    // Too short for two levels of 16 blocks, so no plateau can be seen: the cautious 8 blocks.
    EXPECT_EQ(suggested_blocks(gaussian_series(12, 0, 1, 4)), 8u);
    // Correlation time ~1000 samples in 2^12 samples: no plateau, so the fewest blocks allowed.
    EXPECT_EQ(suggested_blocks(ar1_series(1 << 12, 0.999, 5)), 8u);
}

// Independent values each repeated 512 times: the blocks are exactly independent from level 9
// (blocks of 512) on, and strictly correlated below it, where each halving raises the error
// estimate by sqrt(2). The analysis must stop exactly there: 2^14 / 512 = 32 blocks, with the
// error of the 32 independent values.
TEST(SuggestedBlocks, FollowsTheDecorrelationLength) {
    const std::size_t repeat = 512, independent = 32;
    const auto values = gaussian_series(independent, 0.0, 1.0, 8);
    std::vector<double> x;
    for (double v : values) x.insert(x.end(), repeat, v);
    EXPECT_EQ(suggested_blocks(x), independent);
    EXPECT_NEAR(block_average(x).error, naive_error(values), 1e-12);
}

TEST(Jackknife, RatioOfIndependentMeansMatchesDeltaMethod) {
    const std::size_t n = 1 << 14;
    const double mu_a = 5.0, sigma_a = 1.0, mu_b = 2.0, sigma_b = 0.5;
    const auto a = gaussian_series(n, mu_a, sigma_a, 21);
    const auto b = gaussian_series(n, mu_b, sigma_b, 22);
    const Estimate r = ratio_of_means(a, b);

    const double ratio = mu_a / mu_b;
    EXPECT_LT(std::abs(r.value - ratio), 3 * r.error);
    // Delta method: var(A/B) = R^2 (var A / A^2 + var B / B^2) for independent A, B.
    const double nn = static_cast<double>(n);
    const double delta = ratio * std::sqrt(sigma_a * sigma_a / (mu_a * mu_a * nn) +
                                           sigma_b * sigma_b / (mu_b * mu_b * nn));
    EXPECT_NEAR(r.error, delta, 0.25 * delta);
    EXPECT_NEAR(r.value, plain_mean(a) / plain_mean(b), 1e-12);
}

// Same as above over many replicas, so that the mean reported error is pinned far tighter than the
// 25% a single jackknife with 64 blocks allows.
TEST(Jackknife, RatioErrorsAreCalibratedOverReplicas) {
    const std::size_t n = 1 << 12;
    const double mu_a = 5.0, sigma_a = 1.0, mu_b = 2.0, sigma_b = 0.5;
    const double ratio = mu_a / mu_b;
    const double nn = static_cast<double>(n);
    const double delta = ratio * std::sqrt(sigma_a * sigma_a / (mu_a * mu_a * nn) +
                                           sigma_b * sigma_b / (mu_b * mu_b * nn));
    const int replicas = 200;
    int within_one = 0;
    double mean_error = 0;
    for (int k = 0; k < replicas; ++k) {
        const auto seed = 100 + 2 * static_cast<std::uint64_t>(k);
        const Estimate r = ratio_of_means(gaussian_series(n, mu_a, sigma_a, seed),
                                          gaussian_series(n, mu_b, sigma_b, seed + 1));
        within_one += std::abs(r.value - ratio) < r.error;
        mean_error += r.error / replicas;
    }
    EXPECT_NEAR(mean_error, delta, 0.05 * delta);
    EXPECT_NEAR(within_one / double(replicas), 0.683, 0.10);
}

// With correlated samples the jackknife blocks must be long enough to be independent; then the
// jackknife error of f = identity is the blocking error of the mean.
TEST(Jackknife, CorrelatedSeriesUseDecorrelatedBlocks) {
    const std::size_t n = 1 << 18;
    const double phi = 0.9;
    const auto x = ar1_series(n, phi, 77);
    const Estimate e = jackknife({x}, [](std::span<const double> m) { return m[0]; });
    const double exact = ar1_standard_error(phi, n);
    EXPECT_NEAR(e.error, exact, 0.25 * exact);
}

// Kurtosis <v^4>/<v^2>^2 = 3 for a Gaussian: a nonlinear function of two strongly correlated
// means, whose error only the joint leave-one-out captures.
TEST(Jackknife, GaussianKurtosisIsThreeWithinErrors) {
    const std::size_t n = 1 << 16;
    const auto v = gaussian_series(n, 0.0, 1.5, 31);
    std::vector<double> v2(n), v4(n);
    for (std::size_t i = 0; i < n; ++i) {
        v2[i] = v[i] * v[i];
        v4[i] = v2[i] * v2[i];
    }
    const Estimate k =
        jackknife({v2, v4}, [](std::span<const double> m) { return m[1] / (m[0] * m[0]); });
    // Delta method with the Gaussian moments: var(kurtosis estimate) = 24/n.
    const double expected = std::sqrt(24.0 / static_cast<double>(n));
    EXPECT_NEAR(k.error, expected, 0.25 * expected);
    EXPECT_LT(std::abs(k.value - 3.0), 3 * k.error);
}

TEST(Jackknife, ValueIsFunctionOfFullMeansNotJackknifeMean) {
    const std::vector<double> x{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17};
    const Estimate e = jackknife(
        {x}, [](std::span<const double> m) { return m[0] * m[0]; }, 4);
    EXPECT_DOUBLE_EQ(e.value, 81.0);  // mean 9 over all 17 samples, not only the 16 in blocks
    EXPECT_GT(e.error, 0.0);
}

TEST(Jackknife, ExplicitBlockCountMatchesHandComputedLeaveOneOut) {
    // Blocks of 2 samples: means 1.5, 3.5, 5.5, 7.5. For f = identity the jackknife variance
    // (N-1)/N sum_b (f_b - mean f)^2 reduces to s^2/N of the block means, with s^2 = 20/3.
    const std::vector<double> x{1, 2, 3, 4, 5, 6, 7, 8};
    const Estimate e = jackknife(
        {x}, [](std::span<const double> m) { return m[0]; }, 4);
    EXPECT_NEAR(e.error, std::sqrt(20.0 / 3.0 / 4.0), 1e-12);
    EXPECT_DOUBLE_EQ(e.value, 4.5);
    // One sample per block: error^2 = s^2 / n = 6 / 8 = 0.75. tau_int = (5/3) / 0.75 / 2 = 10/9,
    // n_eff = 8 / (2 tau_int) = 3.6.
    EXPECT_NEAR(e.tau_int, 10.0 / 9.0, 1e-12);
    EXPECT_NEAR(e.n_eff, 3.6, 1e-12);
    EXPECT_EQ(e.samples, 8u);
    EXPECT_TRUE(e.converged);
}

TEST(Jackknife, FewerThanEightSamplesGiveNaNErrorAndFullValue) {
    const std::vector<double> a{1, 2, 3}, b{2, 2, 2};
    const Estimate r = ratio_of_means(a, b);
    EXPECT_DOUBLE_EQ(r.value, 1.0);
    EXPECT_TRUE(std::isnan(r.error));
}

TEST(Jackknife, ConstantSeriesHaveZeroError) {
    const std::vector<double> a(100, 0.3), b(100, 0.7);
    const Estimate r = ratio_of_means(a, b);
    EXPECT_DOUBLE_EQ(r.value, 0.3 / 0.7);
    EXPECT_EQ(r.error, 0.0);
    EXPECT_TRUE(std::isnan(r.tau_int));
    EXPECT_TRUE(std::isnan(r.n_eff));
}

TEST(Jackknife, RejectsMismatchedLengthsEmptyInputAndBadBlockCounts) {
    const std::vector<double> a(20, 1.0), b(19, 1.0);
    const auto f = [](std::span<const double> m) { return m[0]; };
    EXPECT_THROW(ratio_of_means(a, b), std::invalid_argument);
    EXPECT_THROW(jackknife({}, f), std::invalid_argument);
    EXPECT_THROW(jackknife({a}, f, 1), std::invalid_argument);
    EXPECT_THROW(jackknife({a}, f, 21), std::invalid_argument);
}

// --- integrated autocorrelation time and effective sample size -----------------------------------

// AR(1) with phi = 0.5, 0.9, 0.99: tau_int = 1.5, 9.5, 99.5 samples exactly. 2^20 samples are
// ~10^4 tau_int even for phi = 0.99, where blocking's plateau bias is a few per cent; the blocking
// tau_int has a relative noise of ~sqrt(2 / blocks) at the plateau level (~6% for 2^20 / 2^11
// blocks) and Sokal's ~sqrt(2 (2M+1) / n) (~5% for M = 6 tau). 20% is > 3 sigma of either for
// every seed, while a wrong convention (tau_int without the 1/2, or 2 tau_int) is off by 30-100%
// at phi = 0.5 and a naive estimate (tau_int = 1/2) by a factor 3-200.
class Ar1TauInt : public ::testing::TestWithParam<double> {};

TEST_P(Ar1TauInt, BlockingAndSokalWindowingAreWithinTwentyPercentOfExactForEachSeed) {
    const double phi = GetParam();
    const double exact = ar1_tau_int(phi);
    const std::size_t n = 1 << 20;
    for (std::uint64_t seed : {11u, 12u, 13u, 14u}) {
        const auto x = ar1_series(n, phi, seed);
        const Estimate e = block_average(x);
        EXPECT_TRUE(e.converged);
        EXPECT_NEAR(e.tau_int, exact, 0.20 * exact) << "blocking, seed " << seed;
        // n_eff is what makes error = sigma / sqrt(n_eff): n / (2 tau_int).
        EXPECT_EQ(e.samples, n);
        EXPECT_NEAR(e.n_eff, double(n) / (2 * e.tau_int), 1e-9 * e.n_eff);
        const double n_eff_exact = double(n) / (2 * exact);
        EXPECT_NEAR(e.n_eff, n_eff_exact, 0.25 * n_eff_exact) << "seed " << seed;

        const AutocorrelationTime sokal = integrated_autocorrelation_time(x);
        EXPECT_TRUE(sokal.converged);
        EXPECT_NEAR(sokal.tau_int, exact, 0.20 * exact) << "Sokal, seed " << seed;
        // The two estimators are independent methods on the same data: they must agree within
        // their combined noise (each < 7%: 20% is ~2.5 combined sigma at worst).
        EXPECT_NEAR(e.tau_int / sokal.tau_int, 1.0, 0.20) << "seed " << seed;
    }
}

INSTANTIATE_TEST_SUITE_P(Phi, Ar1TauInt, ::testing::Values(0.5, 0.9, 0.99));

TEST(BlockAverage, IndependentSamplesHaveTauIntOneHalfAndNEffN) {
    const std::size_t n = 1 << 16;
    const Estimate e = block_average(gaussian_series(n, 1.0, 2.0, 41));
    // Plateau at level 0: error = naive error exactly, so tau_int = 1/2 exactly or, if the
    // plateau is found one level later, within the ~1% noise of that level.
    EXPECT_NEAR(e.tau_int, 0.5, 0.05);
    EXPECT_NEAR(e.n_eff, double(n), 0.1 * double(n));
}

TEST(BlockAverage, SeriesTooShortForItsCorrelationTimeIsFlaggedNotConverged) {
    // tau_int ~ 1000 samples in 2^12: the blocks never decorrelate, the error is a lower bound.
    const Estimate e = block_average(ar1_series(1 << 12, 0.999, 5));
    EXPECT_FALSE(e.converged);
    EXPECT_LT(e.tau_int, ar1_tau_int(0.999));  // a lower bound, as documented
    const Estimate r =
        ratio_of_means(ar1_series(1 << 12, 0.999, 5), gaussian_series(1 << 12, 5, 1, 6));
    EXPECT_FALSE(r.converged);
    EXPECT_TRUE(block_average(ar1_series(1 << 16, 0.5, 5)).converged);
}

// The jackknife's tau_int compares the block jackknife with the leave-one-sample-out one. For
// the ratio of two independent AR(1) series of equal phi, linearisation gives the same
// autocorrelation rho_t = phi^t for the ratio as for each series, hence tau_int =
// (1+phi)/(2(1-phi)). With at most 64 blocks a single jackknife error has ~9% noise and its tau_int
// ~18% (observed seed to seed: 7-16 for an exact 9.5, as blocking's own tau_int of the two series
// at this length), so the test averages 16 seeds (~5%) and requires 15%.
TEST(Jackknife, TauIntOfRatioOfAr1SeriesMatchesExact) {
    const double phi = 0.9;
    const double exact = ar1_tau_int(phi);
    const std::size_t n = 1 << 16;
    double mean_tau = 0;
    const int seeds = 16;
    for (int k = 0; k < seeds; ++k) {
        auto a = ar1_series(n, phi, 500 + 2 * std::uint64_t(k));
        auto b = ar1_series(n, phi, 501 + 2 * std::uint64_t(k));
        for (double& v : a) v += 5;
        for (double& v : b) v += 2;
        const Estimate r = ratio_of_means(a, b);
        EXPECT_TRUE(r.converged);
        EXPECT_NEAR(r.n_eff, double(n) / (2 * r.tau_int), 1e-9 * r.n_eff);
        mean_tau += r.tau_int / seeds;
    }
    EXPECT_NEAR(mean_tau, exact, 0.15 * exact);
}

// The acceptance criterion for the error bars: over many independent replicas, the actual spread
// of the estimates must be the error each replica reports. 200 replicas pin the spread to
// 1/sqrt(2 * 199) = 5%, so 15% is 3 sigma; blocking's plateau bias at n ~ 1700 tau_int is ~5%.
TEST(BlockAverage, SpreadOfAr1ReplicaMeansAgreesWithReportedErrorWithinFifteenPercent) {
    const std::size_t n = 1 << 14;
    const double phi = 0.9;
    const int replicas = 200;
    std::vector<double> means;
    double mean_square_error = 0;
    for (int r = 0; r < replicas; ++r) {
        const Estimate e = block_average(ar1_series(n, phi, 7000 + std::uint64_t(r)));
        means.push_back(e.value);
        mean_square_error += e.error * e.error / replicas;
    }
    const double spread = std::sqrt(naive_error(means) * naive_error(means) * replicas);
    EXPECT_NEAR(std::sqrt(mean_square_error) / spread, 1.0, 0.15);
}

TEST(Jackknife, SpreadOfCorrelatedRatioReplicasAgreesWithReportedErrorWithinFifteenPercent) {
    const std::size_t n = 1 << 14;
    const double phi = 0.9;
    const int replicas = 200;
    std::vector<double> ratios;
    double mean_square_error = 0;
    for (int r = 0; r < replicas; ++r) {
        auto a = ar1_series(n, phi, 9000 + 2 * std::uint64_t(r));
        auto b = ar1_series(n, phi, 9001 + 2 * std::uint64_t(r));
        for (double& v : a) v = 5 + v;
        for (double& v : b) v = 2 + 0.5 * v;
        const Estimate e = ratio_of_means(a, b);
        ratios.push_back(e.value);
        mean_square_error += e.error * e.error / replicas;
    }
    const double spread = std::sqrt(naive_error(ratios) * naive_error(ratios) * replicas);
    EXPECT_NEAR(std::sqrt(mean_square_error) / spread, 1.0, 0.15);
}

TEST(Estimate, AffineMapScalesErrorAndKeepsCorrelationDiagnostics) {
    const Estimate e = block_average(ar1_series(1 << 12, 0.5, 3));
    const Estimate s = e.affine(-2.0, 1.0);
    EXPECT_DOUBLE_EQ(s.value, 1.0 - 2.0 * e.value);
    EXPECT_DOUBLE_EQ(s.error, 2.0 * e.error);
    EXPECT_EQ(s.tau_int, e.tau_int);
    EXPECT_EQ(s.n_eff, e.n_eff);
    EXPECT_EQ(s.samples, e.samples);
    EXPECT_EQ(s.converged, e.converged);
}

TEST(Series, AccumulatesValuesAndEstimatesByBlocking) {
    const auto x = ar1_series(1 << 12, 0.5, 9);
    Series s;
    s.reserve(x.size());
    EXPECT_EQ(s.size(), 0u);
    EXPECT_TRUE(std::isnan(s.estimate().error));
    for (double v : x) s.push(v);
    ASSERT_EQ(s.size(), x.size());
    EXPECT_TRUE(std::equal(x.begin(), x.end(), s.values().begin()));
    const Estimate direct = block_average(x), streamed = s.estimate();
    EXPECT_EQ(streamed.value, direct.value);
    EXPECT_EQ(streamed.error, direct.error);
}

}  // namespace
}  // namespace gran
