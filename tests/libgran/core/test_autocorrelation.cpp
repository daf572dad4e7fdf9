// Sokal's automatic-windowing estimator of tau_int (libgran/autocorrelation.hpp). Its agreement
// with the exact AR(1) tau_int and with blocking is tested in test_statistics.cpp (Ar1TauInt);
// here: its conventions and edge cases.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "libgran/core/autocorrelation.hpp"
#include "tests/support/random_series.hpp"

namespace gran {
namespace {

TEST(IntegratedAutocorrelationTime, IndependentSamplesGiveOneHalfWithSmallWindow) {
    const auto x = testing::gaussian_series(1 << 16, 0.0, 1.0, 3);
    const AutocorrelationTime t = integrated_autocorrelation_time(x);
    ASSERT_TRUE(t.converged);
    // tau(M) stays ~1/2, so the first M >= 6 tau(M) is M = 3; the sum of 3 noisy rho_k has
    // standard deviation sqrt(3 / n) ~ 0.007.
    EXPECT_LE(t.window, 4u);
    EXPECT_NEAR(t.tau_int, 0.5, 0.03);
    EXPECT_NEAR(t.error, 0.5 * std::sqrt(2.0 * double(2 * t.window + 1) / double(1 << 16)), 1e-3);
}

TEST(IntegratedAutocorrelationTime, WindowIsSixTimesTauForAr1) {
    // phi = 0.9: tau_int = 9.5, so the window stops at the first M >= 6 tau(M), M ~ 57.
    const auto x = testing::ar1_series(1 << 18, 0.9, 8);
    const AutocorrelationTime t = integrated_autocorrelation_time(x);
    ASSERT_TRUE(t.converged);
    EXPECT_GE(double(t.window), kSokalWindowFactor * t.tau_int);
    EXPECT_LT(double(t.window - 1), kSokalWindowFactor * 1.2 * testing::ar1_tau_int(0.9));
    // The reported error is the actual scatter: within 4 of its own sigma of the exact value.
    EXPECT_NEAR(t.tau_int, testing::ar1_tau_int(0.9), 4 * t.error);
}

TEST(IntegratedAutocorrelationTime, SeriesShorterThanTheWindowNeedsIsNotConverged) {
    // tau_int ~ 1000 samples: 6 tau exceeds n / 4 = 1024.
    const auto x = testing::ar1_series(1 << 12, 0.999, 5);
    const AutocorrelationTime t = integrated_autocorrelation_time(x);
    EXPECT_FALSE(t.converged);
    EXPECT_EQ(t.window, (1u << 12) / 4);
}

TEST(IntegratedAutocorrelationTime, ConstantOrTooShortSeriesGiveNaN) {
    EXPECT_TRUE(std::isnan(integrated_autocorrelation_time(std::vector<double>(100, 0.1)).tau_int));
    EXPECT_TRUE(std::isnan(
        integrated_autocorrelation_time(std::vector<double>{1, 2, 3, 4, 5, 6, 7}).tau_int));
    EXPECT_FALSE(integrated_autocorrelation_time(std::vector<double>(100, 0.1)).converged);
}

}  // namespace
}  // namespace gran
