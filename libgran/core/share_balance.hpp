#pragma once
// Shares of a threaded loop that follow the threads' measured speeds. A loop cut into equal
// shares runs at the pace of its slowest thread: on a shared machine one core may run the same
// code 1.2-1.7x slower than the other for minutes (docs/performance.md, "Which core"). Each
// thread adds up the wall-clock seconds of its share in each step; the step's times become one
// sample per thread; at each rebalance() each thread's fraction of the work moves half-way to
// its share of the summed speeds (fraction over the median step time), so that the threads would
// finish together. The median, not the mean: a thread preempted by another process for a few
// milliseconds stalls the steps it is preempted in whatever its share, and such steps say
// nothing about its speed.
//
// Only a schedule: callers make their results independent of the cut (DemEngine's pair rows give
// the same bits for any cut), so the timings, which differ from run to run, never change a bit.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gran {

class ShareBalance {
  public:
    static constexpr std::size_t kSamples = 512;  // step times kept per thread (the latest)

    // Equal fractions for `parts` threads, nothing recorded.
    void reset(std::size_t parts) {
        fraction_.assign(parts, parts ? 1.0 / double(parts) : 0.0);
        clear();
    }
    // Given fractions (one per thread, summing to 1), nothing recorded.
    void fix(const std::vector<double>& fractions) {
        fraction_ = fractions;
        clear();
    }
    std::size_t parts() const { return fraction_.size(); }

    // Seconds thread `part` spent on its share in the current step; each thread writes only its
    // own slot.
    void add(std::size_t part, double seconds) { step_[part] += seconds; }
    // The end of a step (one thread): each thread's time of the step becomes a sample, if every
    // thread has one and the shares did not change during the step.
    void end_step() {
        bool whole = !mixed_;
        for (const double s : step_) whole = whole && s > 0;
        if (whole) {
            for (std::size_t t = 0; t < step_.size(); ++t)
                samples_[t * kSamples + taken_ % kSamples] = step_[t];
            ++taken_;
        }
        std::fill(step_.begin(), step_.end(), 0.0);
        mixed_ = false;
    }
    // The new fractions from the steps sampled since the last call, which are then cleared
    // (and the current step, cut by the old fractions in part, is not sampled). Unchanged unless
    // some step was sampled. Each fraction stays at least a quarter of an equal share before
    // the fractions are normalised, so that no thread stops being measured.
    void rebalance() {
        const std::size_t n = fraction_.size();
        const std::size_t m = std::min<std::size_t>(taken_, kSamples);
        if (n > 1 && m > 0) {
            std::vector<double>& speed = speed_;
            speed.resize(n);
            double total = 0;
            for (std::size_t t = 0; t < n; ++t) {
                double* s = samples_.data() + t * kSamples;
                std::nth_element(s, s + m / 2, s + m);
                speed[t] = fraction_[t] / s[m / 2];
                total += speed[t];
            }
            const double floor = 0.25 / double(n);
            double sum = 0;
            for (std::size_t t = 0; t < n; ++t) {
                fraction_[t] = std::max(floor, 0.5 * (fraction_[t] + speed[t] / total));
                sum += fraction_[t];
            }
            for (double& f : fraction_) f /= sum;
        }
        taken_ = 0;
        mixed_ = true;
    }
    // Thread t's fraction of the work (they sum to 1).
    double fraction(std::size_t t) const { return fraction_[t]; }
    // The fractions before thread t, summed: where t's share of the work begins.
    double begins(std::size_t t) const {
        double s = 0;
        for (std::size_t u = 0; u < t && u < fraction_.size(); ++u) s += fraction_[u];
        return s;
    }

  private:
    void clear() {
        step_.assign(fraction_.size(), 0.0);
        samples_.assign(fraction_.size() * kSamples, 0.0);
        taken_ = 0;
        mixed_ = false;
    }
    std::vector<double> fraction_, step_, samples_, speed_;
    std::size_t taken_ = 0;  // steps sampled since the last rebalance
    bool mixed_ = false;     // the current step began under other fractions
};

}  // namespace gran
