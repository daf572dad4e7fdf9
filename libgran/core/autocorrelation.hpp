// Integrated autocorrelation time of a time series by Sokal's automatic windowing, an estimator
// independent of the blocking analysis (libgran/statistics.hpp), used to cross-check it.
//
// A. D. Sokal, "Monte Carlo methods in statistical mechanics: foundations and new algorithms"
// (Cargèse lectures, 1996), Sec. 3; N. Madras & A. D. Sokal, J. Stat. Phys. 50, 109 (1988), App. C.
#pragma once

#include <cstddef>
#include <span>

namespace gran {

// tau_int in samples, with the convention of Estimate: tau_int = 1/2 + sum_{k>=1} rho_k, so that
// the variance of the mean of n samples is 2 tau_int sigma^2 / n.
struct AutocorrelationTime {
    double tau_int;      // NaN when it cannot be estimated (see integrated_autocorrelation_time)
    double error;        // Madras–Sokal: var(tau_int) ~ 2 (2M + 1) / n tau_int^2
    std::size_t window;  // M: rho_k summed for 1 <= k <= M
    bool converged;  // false: no window M <= n / 4 satisfied M >= c tau(M); tau is a lower bound
};

// Sokal's window constant: with rho_k ~ exp(-k / tau) the truncation misses a fraction ~exp(-c) of
// tau_int (0.25% at c = 6) while the noise of the sum grows only like sqrt(M).
inline constexpr double kSokalWindowFactor = 6.0;

// tau(M) = 1/2 + sum_{k=1}^{M} rho_k with rho_k = C(k) / C(0), C(k) = 1/(n-k) sum_t (x_t - mean)
// (x_{t+k} - mean); the window is the smallest M with M >= c tau(M). Cost O(n M): meant for tests
// and analysis, not for every observable. Fewer than 8 samples or a constant series: tau_int NaN.
AutocorrelationTime integrated_autocorrelation_time(std::span<const double> series,
                                                    double c = kSokalWindowFactor);

}  // namespace gran
