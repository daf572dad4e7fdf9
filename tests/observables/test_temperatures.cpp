// Error bars of the temperature ratio gamma = T_light / T_heavy on a real simulation: the
// acceptance test of the error analysis (issue 6). R independent replicas (seeds) of a heated
// binary mixture (studies/demo/binary-thermostat-2d.yaml scaled down) each report gamma with a
// jackknife error; the standard deviation of gamma over the replicas must agree with the
// root-mean-square reported error within a factor 1.5 either way. With R = 20 the sample standard
// deviation is itself uncertain by 1/sqrt(2 (R - 1)) = 16%, so a factor 1.5 is ~2.6 sigma of that
// noise. Samples are taken every 1/4 collision per particle, so that tau_int of gamma is several
// samples and an error bar that ignores the correlation in time (off by sqrt(2 tau_int)) fails:
// the test checks that it does. 20 runs of 200 disks, 1000 collisions per particle: ~10 s.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

std::string heated_mixture(int seed) {
    return "dimension: 2\nseed: " + std::to_string(seed) +
           "\nparticles: 200\n"
           "species:\n"
           "  - {name: heavy, mass: 3, diameter: 1, number_fraction: 0.5}\n"
           "  - {name: light, mass: 1, diameter: 1, number_fraction: 0.5}\n"
           "interactions: {law: constant_restitution, alpha: 0.85}\n"
           "box: {packing_fraction: 0.05, periodic: [true, true]}\n"
           "initial: {placement: random, temperature: 1}\n"
           "drivers:\n"
           "  - {type: stochastic_thermostat, noise: equal_velocity_variance, strength: 0.033, "
           "interval: 0.5}\n"
           "observables: [{type: temperatures}]\n"
           "run: {unit: collisions_per_particle, equilibration: 100, measurement: 1000, "
           "sample_interval: 0.25}\n";
}

TEST(TemperaturesErrorBars, ReplicaSpreadOfGammaAgreesWithReportedErrorWithinFactorOneAndAHalf) {
    const int replicas = 20;
    std::vector<double> gamma;
    double mean_square_error = 0, mean_square_naive = 0;
    for (int r = 0; r < replicas; ++r) {
        const YAML::Node s =
            testing::run_yaml(heated_mixture(1000 + r), "replica" + std::to_string(r));
        const YAML::Node g =
            s["observables"]["temperatures"]["ratios"]["light_over_heavy"]["gamma"];
        ASSERT_TRUE(g) << "no gamma in the summary";
        const double n_eff = g["n_eff"].as<double>();
        const double samples = 4000;  // measurement / sample_interval
        gamma.push_back(testing::value(g));
        mean_square_error += testing::error(g) * testing::error(g) / replicas;
        // The error gamma would have if the samples were independent: error / sqrt(2 tau_int).
        const double naive = testing::error(g) * std::sqrt(n_eff / samples);
        mean_square_naive += naive * naive / replicas;
        EXPECT_TRUE(!g["converged"]) << "replica " << r << ": no blocking plateau";
        std::printf("replica %2d: gamma = %.5f +- %.5f  n_eff = %.0f  tau_int = %.2f samples\n", r,
                    testing::value(g), testing::error(g), n_eff, samples / (2 * n_eff));
    }
    double mean = 0;
    for (double x : gamma) mean += x / replicas;
    double var = 0;
    for (double x : gamma) var += (x - mean) * (x - mean) / (replicas - 1);
    const double spread = std::sqrt(var), rms_error = std::sqrt(mean_square_error);
    std::printf("gamma = %.5f; spread over %d replicas %.5f, rms reported error %.5f, ratio %.3f\n",
                mean, replicas, spread, rms_error, spread / rms_error);
    EXPECT_LT(spread / rms_error, 1.5);
    EXPECT_GT(spread / rms_error, 1 / 1.5);
    // The test has the power to reject error bars that ignore the correlation in time.
    const double rms_naive = std::sqrt(mean_square_naive);
    std::printf("rms naive (uncorrelated) error %.5f: spread / naive %.2f\n", rms_naive,
                spread / rms_naive);
    EXPECT_GT(spread / rms_naive, 1.5);
}

}  // namespace
}  // namespace gran
