// Statistical errors of time series produced by a simulation.
//
// Successive samples of an observable (temperature, velocity moments, ...) are correlated, so the
// naive standard error sigma/sqrt(n) underestimates the true uncertainty by a factor
// sqrt(2 tau_int), tau_int being the integrated autocorrelation time in samples. The blocking
// method of Flyvbjerg & Petersen, J. Chem. Phys. 91, 461 (1989) removes the correlation by
// averaging over blocks long enough to be independent, without having to estimate the
// autocorrelation function. Nonlinear functions of several means (ratios, kurtoses) get their
// errors from a jackknife over the same kind of blocks.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "libgran/core/state_archive.hpp"

namespace gran {

// A value with one standard error and what the error rests on. `error` is NaN when it cannot be
// estimated (fewer than kMinSamplesForError samples).
//
// tau_int is the integrated autocorrelation time in samples, with the convention
// tau_int = 1/2 + sum_{k>=1} rho_k (Sokal 1997; Madras & Sokal 1988), so that
// error^2 = 2 tau_int sigma^2 / n: independent samples have tau_int = 1/2. It is inferred from the
// error itself, tau_int = (error / naive error)^2 / 2, the naive error being sigma/sqrt(n-1) of
// the same quantity with every sample treated as independent. n_eff = n / (2 tau_int) is the
// number of effectively independent samples: the error is that of n_eff independent ones.
// Both are NaN when unknown: too few samples, a constant series (error exactly 0, no fluctuation to
// correlate), or an estimate built from fixed blocks whose samples were never seen (profiles).
// converged is false when the blocking analysis found no plateau: the blocks never became
// independent, so error, tau_int are lower bounds and n_eff an upper bound (lengthen the run).
struct Estimate {
    double value = 0;
    double error = 0;
    double tau_int = std::numeric_limits<double>::quiet_NaN();
    double n_eff = std::numeric_limits<double>::quiet_NaN();
    std::size_t samples = 0;
    bool converged = true;

    // The same estimate of a*value + b: error scales with |a|; tau_int, n_eff, samples, converged
    // are unchanged (a linear map does not change correlations).
    Estimate affine(double a, double b = 0) const {
        Estimate e = *this;
        e.value = a * value + b;
        e.error = (a < 0 ? -a : a) * error;
        return e;
    }
};

// Below this many samples no error is reported: a blocking analysis needs a few levels to see a
// plateau, and a jackknife needs a few blocks for its variance to mean anything.
inline constexpr std::size_t kMinSamplesForError = 8;

// Mean of a correlated series with its standard error from Flyvbjerg–Petersen blocking: the series
// is repeatedly halved by pairwise averaging (which leaves the variance of the mean unchanged); at
// each level sigma/sqrt(n-1) estimates the error and has itself the relative uncertainty
// 1/sqrt(2(n-1)). The error returned is that of the first level where the estimate has reached a
// plateau (it agrees with the next level within that level's uncertainty); if there is no plateau,
// the largest estimate among the levels that still have at least 16 blocks (a lower bound: the
// series is too short for its correlation time). Only levels with at least 16 blocks are compared,
// so a plateau is never declared on the few-block levels whose noise hides a rising error. Like
// any plateau criterion this is biased low when the series is short compared with tau_int: by a
// few per cent at n ~ 2000 tau_int, ~10% at 400 tau_int, ~15-20% at 100 tau_int (AR(1) tests).
// The value is the plain mean of all samples.
// tau_int = (error / error of level 0)^2 / 2, n_eff = n / (2 tau_int), converged = plateau found.
// Fewer than 8 samples: error NaN. A constant series has error exactly 0 (tau_int, n_eff NaN).
Estimate block_average(std::span<const double> series);

// Splits the series into n_blocks contiguous blocks of equal length and returns the block means.
// The remainder (series.size() % n_blocks samples) is dropped at the START, so that the most
// recent, best-equilibrated data is kept. Throws std::invalid_argument unless 1 <= n_blocks <=
// size.
std::vector<double> block_means(std::span<const double> series, std::size_t n_blocks);

// Number of blocks to use for jackknife estimates: the series length divided by the decorrelation
// block length found by the blocking analysis of `series` (the level block_average picks), clamped
// to [8, 64] and to the series length. With fewer than 8 blocks the jackknife error is itself too
// noisy; beyond 64 it no longer improves and f is evaluated needlessly often. If the blocking
// analysis finds no plateau (correlation time too long to resolve), the answer is 8: the longest
// blocks allowed are the least correlated.
std::size_t suggested_blocks(std::span<const double> series);

// Jackknife estimate of f(mean(a_1), ..., mean(a_k)) from k equally long series (e.g. T2 and T1
// samples for the ratio T2/T1, or <v^2>, <v^4> for a kurtosis). f receives the k means in the
// order of `series`. The series are cut into n_blocks blocks with block_means (0 = suggested_blocks
// of the jackknife pseudo-values y_t = f + (n-1)(f - f_(t)), f_(t) leaving out sample t: to first
// order the series whose fluctuations f follows, so the blocks are as long as f's own correlation
// needs, not as long as that of the slowest input); the leave-one-block-out means keep the
// correlation between the series and, with decorrelated blocks, the correlation in time.
// Value = f of the full means (not the jackknife mean, whose bias correction only adds noise at
// the statistics we have); error = jackknife standard error, NaN below 8 samples.
// tau_int = (error / e1)^2 / 2 with e1 the jackknife error of the same f with one sample per
// block (leave-one-sample-out: the error f would have if all samples were independent; O(k n)
// plus n evaluations of f). converged is false when the blocking of the pseudo-values found no
// plateau; an explicit n_blocks is taken as given (true).
// Throws std::invalid_argument if `series` is empty, the lengths differ, or an explicit n_blocks is
// not in [2, length].
Estimate jackknife(const std::vector<std::span<const double>>& series,
                   const std::function<double(std::span<const double>)>& f,
                   std::size_t n_blocks = 0);

// Convenience: ratio mean(a)/mean(b) with jackknife error (a and b must be equally long).
Estimate ratio_of_means(std::span<const double> a, std::span<const double> b);

// Streaming accumulator used by observables: push values one at a time (amortised O(1)), then
// estimate(). The whole series is kept rather than only blocking sums, because jackknife estimates
// across several quantities need the raw samples anyway.
class Series {
  public:
    void push(double x) { v_.push_back(x); }
    std::size_t size() const { return v_.size(); }
    std::span<const double> values() const { return v_; }
    Estimate estimate() const { return block_average(v_); }
    void reserve(std::size_t n) { v_.reserve(n); }
    void checkpoint(StateArchive& ar) { ar.io(v_); }

  private:
    std::vector<double> v_;
};

}  // namespace gran
