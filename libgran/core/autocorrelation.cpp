#include "libgran/core/autocorrelation.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "libgran/core/statistics.hpp"

namespace gran {

AutocorrelationTime integrated_autocorrelation_time(std::span<const double> series, double c) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    const std::size_t n = series.size();
    AutocorrelationTime result{kNaN, kNaN, 0, false};
    if (n < kMinSamplesForError) return result;

    // Deviations from the first sample first: a constant series gives exactly zero variance.
    const double shift = series.front();
    double sum = 0;
    for (double x : series) sum += x - shift;
    const double mean = shift + sum / double(n);
    std::vector<double> d(n);
    for (std::size_t t = 0; t < n; ++t) d[t] = series[t] - mean;
    auto autocovariance = [&](std::size_t k) {
        double s = 0;
        for (std::size_t t = 0; t + k < n; ++t) s += d[t] * d[t + k];
        return s / double(n - k);
    };
    const double c0 = autocovariance(0);
    if (!(c0 > 0)) return result;

    // Beyond n/4 the autocovariance estimates are too noisy to sum, and a series that short
    // compared with its correlation time cannot give a useful estimate anyway.
    const std::size_t max_window = n / 4;
    double tau = 0.5;
    std::size_t m = 0;
    while (m < max_window) {
        ++m;
        tau += autocovariance(m) / c0;
        if (double(m) >= c * tau) {
            result.converged = true;
            break;
        }
    }
    result.tau_int = tau;
    result.window = m;
    result.error = tau * std::sqrt(2.0 * double(2 * m + 1) / double(n));
    return result;
}

}  // namespace gran
