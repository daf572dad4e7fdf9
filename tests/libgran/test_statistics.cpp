// Tests of the error analysis of correlated time series (libgran/statistics.hpp). The reference
// values are analytic: sigma/sqrt(n) for independent samples, sqrt((1+phi)/(1-phi)/n) for an AR(1)
// process of unit variance, and the delta method for ratios. Seeds are fixed and the random
// numbers come from std::mt19937_64 with our own Box–Muller transform, so the samples are the same
// with every standard library.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include "libgran/statistics.hpp"

namespace gran {
namespace {

class Gaussian {
  public:
    explicit Gaussian(std::uint64_t seed) : rng_(seed) {}

    // Box–Muller; the second variate of each pair is cached.
    double operator()() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        // 53 random bits, shifted into (0, 1] so that the log is finite.
        const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;
        const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
        has_spare_ = true;
        return r * std::cos(2.0 * std::numbers::pi * u2);
    }

  private:
    std::mt19937_64 rng_;
    bool has_spare_ = false;
    double spare_ = 0;
};

std::vector<double> gaussian_series(std::size_t n, double mean, double sigma, std::uint64_t seed) {
    Gaussian g(seed);
    std::vector<double> x(n);
    for (double& v : x) v = mean + sigma * g();
    return x;
}

// x_{k+1} = phi x_k + sqrt(1 - phi^2) eps_k, started in the stationary state: unit variance,
// autocorrelation phi^t, so the variance of the mean is (1+phi)/(1-phi)/n for large n.
std::vector<double> ar1_series(std::size_t n, double phi, std::uint64_t seed) {
    Gaussian g(seed);
    std::vector<double> x(n);
    x[0] = g();
    const double kick = std::sqrt(1 - phi * phi);
    for (std::size_t k = 1; k < n; ++k) x[k] = phi * x[k - 1] + kick * g();
    return x;
}

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
}

TEST(Jackknife, RejectsMismatchedLengthsEmptyInputAndBadBlockCounts) {
    const std::vector<double> a(20, 1.0), b(19, 1.0);
    const auto f = [](std::span<const double> m) { return m[0]; };
    EXPECT_THROW(ratio_of_means(a, b), std::invalid_argument);
    EXPECT_THROW(jackknife({}, f), std::invalid_argument);
    EXPECT_THROW(jackknife({a}, f, 1), std::invalid_argument);
    EXPECT_THROW(jackknife({a}, f, 21), std::invalid_argument);
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
