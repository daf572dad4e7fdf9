#pragma once
// The wall-clock time of a loop's stages, summed per stage. Off unless switched on: a lap is
// then one predictable branch. On, a lap is one steady_clock read (a few tens of nanoseconds,
// against the microseconds of a DEM step from a hundred grains up).
//
// Why not a sampling profiler: perf's cpu-clock samples (the only ones on a machine without
// hardware counters) put 72% of a vibrated bed's step at N = 10^4 in the drift, where these
// clocks measure 57-58% (docs/performance.md, "Measured with clocks").
#include <chrono>

namespace gran {

class StageClock {
  public:
    void enable(bool on) { on_ = on; }
    bool enabled() const { return on_; }
    // The start of the next stage.
    void start() {
        if (on_) last_ = std::chrono::steady_clock::now();
    }
    // The stage since the last start or lap ends: its time is added to `seconds`.
    void lap(double& seconds) {
        if (!on_) return;
        const auto t = std::chrono::steady_clock::now();
        seconds += std::chrono::duration<double>(t - last_).count();
        last_ = t;
    }

  private:
    bool on_ = false;
    std::chrono::steady_clock::time_point last_{};
};

}  // namespace gran
