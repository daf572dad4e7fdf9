#include "libgran/core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace gran {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Levels with fewer blocks than this have an error estimate uncertain by more than ~18%, too
// much to tell a plateau from noise or to trust as the fallback answer.
constexpr std::size_t kMinBlocksForLevel = 16;

// The jackknife needs enough blocks for its variance estimate to be usable, and gains nothing from
// more than a few dozen once they are decorrelated.
constexpr std::size_t kMinJackknifeBlocks = 8;
constexpr std::size_t kMaxJackknifeBlocks = 64;

// Mean and population variance (1/n normalisation, the c0 of Flyvbjerg & Petersen). Sums are of
// deviations from the first sample: this avoids cancellation when the mean is large compared with
// the spread, and makes a constant series give exactly its value and exactly zero variance.
struct Moments {
    double mean;
    double variance;
};

Moments moments(std::span<const double> x) {
    const double n = static_cast<double>(x.size());
    const double shift = x.front();
    double sum = 0;
    for (double v : x) sum += v - shift;
    const double mean = shift + sum / n;
    double sq = 0;
    for (double v : x) sq += (v - mean) * (v - mean);
    return {mean, sq / n};
}

// tau_int and n_eff from the error and the error the same estimate would have with independent
// samples: error^2 = 2 tau_int naive^2 (see Estimate). Undefined (NaN) when there is no
// fluctuation at all (naive error 0: a constant series) or no error.
void set_correlation(Estimate& e, double naive_error) {
    if (!(naive_error > 0) || !std::isfinite(e.error)) return;
    const double ratio = e.error / naive_error;
    e.tau_int = 0.5 * ratio * ratio;
    e.n_eff = static_cast<double>(e.samples) / (2 * e.tau_int);
}

struct BlockingLevel {
    std::size_t n_blocks;
    double error;        // sqrt(c0 / (n - 1)), c0 the population variance at this level
    double uncertainty;  // error / sqrt(2 (n - 1)): the estimate's own standard deviation
};

struct Blocking {
    Estimate estimate;
    std::size_t level;  // chosen level: blocks of 2^level samples
    bool plateau;       // false: the blocks never became independent
};

// Flyvbjerg–Petersen blocking transformation. Pairwise averaging x'_i = (x_{2i} + x_{2i+1}) / 2
// leaves the mean and its variance invariant while shortening the correlation time, so the naive
// error sigma/sqrt(n-1) grows with the level until the blocks are independent and then stays
// constant within its own statistical uncertainty.
Blocking blocking(std::span<const double> series) {
    Blocking result{{moments(series).mean, kNaN}, 0, false};
    result.estimate.samples = series.size();
    if (series.size() < kMinSamplesForError) return result;

    std::vector<BlockingLevel> levels;
    std::vector<double> x(series.begin(), series.end());
    while (x.size() >= 2) {
        const std::size_t n = x.size();
        const double n_minus_1 = static_cast<double>(n - 1);
        const double error = std::sqrt(moments(x).variance / n_minus_1);
        levels.push_back({n, error, error / std::sqrt(2 * n_minus_1)});
        // An odd sample is dropped from the start, as in block_means, to keep the newest data.
        const std::size_t offset = n % 2;
        const std::size_t half = n / 2;
        for (std::size_t i = 0; i < half; ++i) {
            x[i] = 0.5 * (x[offset + 2 * i] + x[offset + 2 * i + 1]);
        }
        x.resize(half);
    }

    // Plateau: the first level whose estimate agrees with the next one within the uncertainty of
    // the next (coarser, hence less certain) level. Only levels with enough blocks take part: at
    // the top, the uncertainties are so large that any two estimates "agree", which would declare a
    // plateau while the error is still growing.
    for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
        if (levels[i + 1].n_blocks < kMinBlocksForLevel) break;
        if (std::abs(levels[i + 1].error - levels[i].error) <= levels[i + 1].uncertainty) {
            result.estimate.error = levels[i].error;
            result.level = i;
            result.plateau = true;
            set_correlation(result.estimate, levels[0].error);
            return result;
        }
    }

    // No plateau: the correlation time is not much shorter than the series. The largest estimate
    // among the trustworthy levels is the best (still optimistic) lower bound; with fewer than 16
    // samples at level 0 only that level is left.
    result.estimate.error = levels[0].error;
    for (std::size_t i = 1; i < levels.size() && levels[i].n_blocks >= kMinBlocksForLevel; ++i) {
        if (levels[i].error > result.estimate.error) {
            result.estimate.error = levels[i].error;
            result.level = i;
        }
    }
    result.estimate.converged = false;
    set_correlation(result.estimate, levels[0].error);
    return result;
}

// Jackknife standard error of f(means) over n_blocks equal blocks (see jackknife()).
double jackknife_error(const std::vector<std::span<const double>>& series,
                       const std::function<double(std::span<const double>)>& f,
                       std::size_t n_blocks) {
    const std::size_t k = series.size();
    // Leave-one-block-out means from the block sums: O(k * n_blocks) instead of O(k * n) per
    // replica. All blocks have equal length, so means of block means are sample means.
    std::vector<std::vector<double>> blocks(k);
    std::vector<double> totals(k, 0.0);
    for (std::size_t j = 0; j < k; ++j) {
        blocks[j] = block_means(series[j], n_blocks);
        for (double m : blocks[j]) totals[j] += m;
    }
    const double nb = static_cast<double>(n_blocks);
    std::vector<double> replicas(n_blocks);
    std::vector<double> reduced(k);
    for (std::size_t b = 0; b < n_blocks; ++b) {
        for (std::size_t j = 0; j < k; ++j) reduced[j] = (totals[j] - blocks[j][b]) / (nb - 1);
        replicas[b] = f(reduced);
    }

    // Jackknife variance (Efron & Stein): (N-1)/N * sum_b (f_b - mean f)^2, the (N-1) undoing the
    // shrinking of the replica spread by leaving out only one block of N.
    const double spread = moments(replicas).variance;  // (1/N) sum_b (f_b - mean f)^2
    return std::sqrt((nb - 1) * spread);
}

// Jackknife pseudo-values y_t = f + (n - 1) (f - f_(t)) of the leave-one-sample-out replicas
// f_(t) = f(means without sample t): to first order y_t = f + grad f . (x_t - means), the series
// whose mean's error is the error of f (delta method). The reduced means are computed as
// m - (x_t - m) / (n - 1), which does not cancel for large n. O(k n) plus n evaluations of f.
std::vector<double> pseudo_values(const std::vector<std::span<const double>>& series,
                                  const std::function<double(std::span<const double>)>& f,
                                  std::span<const double> means, double full) {
    const std::size_t n = series.front().size();
    const double n_minus_1 = static_cast<double>(n - 1);
    std::vector<double> reduced(series.size());
    std::vector<double> y(n);
    for (std::size_t t = 0; t < n; ++t) {
        for (std::size_t j = 0; j < series.size(); ++j) {
            reduced[j] = means[j] - (series[j][t] - means[j]) / n_minus_1;
        }
        y[t] = full + n_minus_1 * (full - f(reduced));
    }
    return y;
}

}  // namespace

Estimate block_average(std::span<const double> series) {
    if (series.empty()) return {kNaN, kNaN};
    return blocking(series).estimate;
}

std::vector<double> block_means(std::span<const double> series, std::size_t n_blocks) {
    if (n_blocks == 0 || n_blocks > series.size()) {
        throw std::invalid_argument("block_means: need 1 <= n_blocks <= series length, got " +
                                    std::to_string(n_blocks) + " blocks for " +
                                    std::to_string(series.size()) + " samples");
    }
    const std::size_t length = series.size() / n_blocks;
    const std::size_t start = series.size() - length * n_blocks;
    std::vector<double> means(n_blocks);
    for (std::size_t b = 0; b < n_blocks; ++b) {
        means[b] = moments(series.subspan(start + b * length, length)).mean;
    }
    return means;
}

namespace {

// suggested_blocks() from the blocking analysis of a series of n samples.
std::size_t blocks_for(const Blocking& b, std::size_t n) {
    if (n < kMinSamplesForError) return n;
    // Without a plateau the decorrelation length is longer than any level could show, so even the
    // longest blocks tried are correlated: use as few (long) blocks as the jackknife tolerates.
    if (!b.plateau) return std::min(kMinJackknifeBlocks, n);
    const std::size_t block_length = std::size_t{1} << b.level;
    return std::min(std::clamp(n / block_length, kMinJackknifeBlocks, kMaxJackknifeBlocks), n);
}

}  // namespace

std::size_t suggested_blocks(std::span<const double> series) {
    return blocks_for(blocking(series), series.size());
}

Estimate jackknife(const std::vector<std::span<const double>>& series,
                   const std::function<double(std::span<const double>)>& f, std::size_t n_blocks) {
    if (series.empty()) throw std::invalid_argument("jackknife: no series given");
    const std::size_t n = series.front().size();
    for (const auto& s : series) {
        if (s.size() != n) {
            throw std::invalid_argument("jackknife: series lengths differ (" + std::to_string(n) +
                                        " vs " + std::to_string(s.size()) + ")");
        }
    }
    const std::size_t k = series.size();

    std::vector<double> means(k);
    for (std::size_t j = 0; j < k; ++j) means[j] = n == 0 ? kNaN : moments(series[j]).mean;
    Estimate result{f(means), kNaN};
    result.samples = n;
    if (n < kMinSamplesForError) return result;

    // The fluctuations of f(means) follow, to first order, the pseudo-value series: its blocking
    // analysis gives the decorrelation length of f itself (e.g. for T_1/T_2 the common slow
    // fluctuation of both temperatures cancels) and its level-0 error is the uncorrelated error.
    const std::vector<double> y = pseudo_values(series, f, means, result.value);
    const double naive_error = std::sqrt(moments(y).variance / static_cast<double>(n - 1));
    if (n_blocks == 0) {
        const Blocking b = blocking(y);
        n_blocks = blocks_for(b, n);
        result.converged = b.plateau;
    } else if (n_blocks < 2 || n_blocks > n) {
        throw std::invalid_argument("jackknife: need 2 <= n_blocks <= series length, got " +
                                    std::to_string(n_blocks) + " blocks for " + std::to_string(n) +
                                    " samples");
    }

    result.error = n_blocks == n ? naive_error : jackknife_error(series, f, n_blocks);
    // The jackknife with one sample per block treats every sample as independent: the ratio of
    // the two errors measures the correlation, as in blocking.
    set_correlation(result, naive_error);
    return result;
}

Estimate ratio_of_means(std::span<const double> a, std::span<const double> b) {
    return jackknife({a, b}, [](std::span<const double> m) { return m[0] / m[1]; });
}

}  // namespace gran
