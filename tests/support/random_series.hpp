#pragma once
// Test helper: reproducible Gaussian and AR(1) series for the statistics tests. The random numbers
// come from std::mt19937_64 with our own Box–Muller transform, so the samples are the same with
// every standard library.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace gran::testing {

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

inline std::vector<double> gaussian_series(std::size_t n, double mean, double sigma,
                                           std::uint64_t seed) {
    Gaussian g(seed);
    std::vector<double> x(n);
    for (double& v : x) v = mean + sigma * g();
    return x;
}

// x_{k+1} = phi x_k + sqrt(1 - phi^2) eps_k, started in the stationary state: unit variance,
// autocorrelation rho_t = phi^t, so the variance of the mean is (1+phi)/(1-phi)/n for large n.
inline std::vector<double> ar1_series(std::size_t n, double phi, std::uint64_t seed) {
    Gaussian g(seed);
    std::vector<double> x(n);
    x[0] = g();
    const double kick = std::sqrt(1 - phi * phi);
    for (std::size_t k = 1; k < n; ++k) x[k] = phi * x[k - 1] + kick * g();
    return x;
}

// tau_int = 1/2 + sum_{k>=1} phi^k = (1 + phi) / (2 (1 - phi)) exactly.
inline double ar1_tau_int(double phi) {
    return (1 + phi) / (2 * (1 - phi));
}

}  // namespace gran::testing
