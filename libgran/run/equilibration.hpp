// Was the measurement phase stationary? A warm-up check on one scalar series per run (the kinetic
// energy per particle at every measurement sample), cheap (O(samples)) and documented in
// docs/physics.md ("Error bars and equilibration").
//
// The truncation heuristic is MSER-5: K. P. White Jr., "An effective truncation heuristic for bias
// reduction in simulation output", Simulation 69, 323 (1997); K. P. White, M. J. Cobb &
// S. C. Spratt, Proc. Winter Simulation Conf. 2000, 755.
#pragma once

#include <cstddef>
#include <span>

#include "libgran/run/result_sink.hpp"
#include "libgran/scene/schedule.hpp"

namespace gran {

// MSER-5 batch length.
inline constexpr std::size_t kMserBatch = 5;
// Fewer batches than this: no truncation is searched (returns 0).
inline constexpr std::size_t kMserMinBatches = 10;
// The measurement is reported as still relaxing when dropping the MSER-truncated samples moves
// the mean by more than kRelaxingShift of its standard error: the transient biases the result
// beyond its error bar. The truncation fraction alone is not used: slow fluctuations make MSER
// truncate 10-20% of stationary series now and then (a heated gas with n_eff ~ 50: 1 seed in 8)
// without any effect on the mean. For stationary AR(1) series |shift_z| > 1 occurs in ~1% of
// seeds at n ~ 100-400 tau_int and in none at n >= 1000 tau_int (numpy prototype, 300 seeds).
// It needs a series long enough to tell a transient from a slow fluctuation: below
// kMinEffectiveSamplesForCheck effectively independent samples after the truncation, or without a
// blocking plateau (the error is a lower bound), false alarms reach 10-20% and the check is
// reported as inconclusive.
inline constexpr double kRelaxingShift = 1.0;
inline constexpr double kMinEffectiveSamplesForCheck = 50;

// MSER truncation point in samples: the series is cut into batches of `batch` samples (a remainder
// at the end is dropped) with means b_j, j < m, and d* minimises
//   MSER(d) = sum_{j>=d} (b_j - mean_{j>=d} b)^2 / (m - d)^2,
// the squared standard error of the mean of what is left after dropping d batches, over
// 0 <= d <= m / 2 (the second half is never dropped: there MSER is dominated by noise). Returns
// d* * batch; the smallest d on ties; 0 below kMserMinBatches batches. O(n).
std::size_t mser_truncation(std::span<const double> series, std::size_t batch = kMserBatch);

struct EquilibrationCheck {
    std::size_t samples = 0;         // measurement samples analysed
    std::size_t truncation = 0;      // MSER-5 truncation point in samples
    double truncation_fraction = 0;  // truncation / samples
    // Drift test: (mean of the second half - mean of the first half) / its standard error
    // (sqrt(2) times the blocking error of the second half); ~N(0, 1) for a stationary series.
    double drift_z = 0;
    // (mean of all samples - mean after the truncation) / blocking error of the latter.
    double shift_z = 0;
    double n_eff = 0;  // effectively independent samples after the truncation
    // n_eff >= kMinEffectiveSamplesForCheck and the blocking of the rest found a plateau
    bool conclusive = false;
    bool relaxing = false;  // conclusive and |shift_z| > kRelaxingShift
};

EquilibrationCheck check_equilibration(std::span<const double> series);

// Writes the group `equilibration` of /performance (HDF5 and summary); when the measurement was
// still relaxing and the scene is meant to reach a steady state (it has a driver injecting
// energy), logs a warning and writes it there too, with the run.equilibration that would have
// skipped the transient.
void report_equilibration(const EquilibrationCheck& check, const Schedule& schedule,
                          bool steady_state_expected, ResultGroup& performance);

}  // namespace gran
