#pragma once
// The `run` section: the schedule (equilibration, measurement, sampling) and the watchdog's
// settings (libgran/run/watchdog.hpp applies them).
#include <cstdint>

namespace gran {

enum class ScheduleUnit { CollisionsPerParticle, Time };

struct Schedule {
    ScheduleUnit unit = ScheduleUnit::CollisionsPerParticle;
    double equilibration = 0;
    double measurement = 0;
    double sample_interval = 1;
};

struct WatchdogSettings {
    bool enabled = true;
    std::uint64_t window = 1000000;  // events (event-driven) or steps (dem) between checks
    double max_rate_growth = 1e6;    // stop when the event rate exceeds this x the first window's
    double max_events_per_tc = 0.1;  // stop when events per particle per tc exceed this
};

}  // namespace gran
