#pragma once
// Shares of a threaded loop that follow the threads' measured speeds. A loop cut into equal
// shares runs at the pace of its slowest thread: on a shared machine one core may run the same
// code 1.4-1.7x slower than the other for minutes (docs/performance.md, "Which core"), and a
// contiguous cut may hold denser rows on one side. Each thread records the work it did and the
// wall-clock seconds it took; rebalance() moves each thread's fraction of the work half-way to
// its share of the summed speeds, so that the threads would finish together.
//
// Only a schedule: callers make their results independent of the cut (DemEngine's pair rows give
// the same bits for any cut), so the timings, which differ from run to run, never change a bit.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gran {

class ShareBalance {
  public:
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
    // Thread `part`'s work (any unit proportional to its cost, e.g. list entries) and the wall
    // seconds it took. Each thread writes only its own slot.
    void record(std::size_t part, double work, double seconds) {
        work_[part] += work;
        seconds_[part] += seconds;
    }
    // The new fractions from the work and seconds recorded since the last call, which are then
    // cleared. Unchanged unless every thread recorded positive work and time. Each fraction stays
    // at least a quarter of an equal share, so that no thread stops being measured.
    void rebalance() {
        const std::size_t n = fraction_.size();
        double total_speed = 0;
        bool measured = n > 1;
        for (std::size_t t = 0; t < n && measured; ++t) {
            measured = work_[t] > 0 && seconds_[t] > 0;
            if (measured) total_speed += work_[t] / seconds_[t];
        }
        if (measured) {
            const double floor = 0.25 / double(n);
            double sum = 0;
            for (std::size_t t = 0; t < n; ++t) {
                const double target = work_[t] / seconds_[t] / total_speed;
                fraction_[t] = std::max(floor, 0.5 * (fraction_[t] + target));
                sum += fraction_[t];
            }
            for (double& f : fraction_) f /= sum;
        }
        clear();
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
        work_.assign(fraction_.size(), 0.0);
        seconds_.assign(fraction_.size(), 0.0);
    }
    std::vector<double> fraction_, work_, seconds_;
};

}  // namespace gran
