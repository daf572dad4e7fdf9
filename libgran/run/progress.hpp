#pragma once
// The progress line of a run: redrawn in place on a terminal (at most 5 times a second), or logged
// every `log_interval` seconds when stderr is a file (a log of a study's run).
#include <chrono>
#include <cstdint>

namespace gran {

class Progress {
  public:
    // unit: what the rate counts ("events", "steps").
    Progress(bool enabled, bool terminal, double log_interval, const char* unit);
    // fraction: of the whole schedule, in [0, 1]; work: events or steps so far (for the rate).
    void update(const char* phase, double fraction, std::uint64_t work, bool force = false);
    // Ends a redrawn line.
    void finish();
    double elapsed() const;  // wall-clock seconds since construction

  private:
    using Clock = std::chrono::steady_clock;
    bool enabled_;
    bool terminal_;
    double log_interval_;
    const char* unit_;
    Clock::time_point start_, last_draw_{}, last_log_;
    bool drawn_ = false;
};

}  // namespace gran
