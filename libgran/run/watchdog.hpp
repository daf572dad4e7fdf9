#pragma once
// The run watchdog (issue 6): stops a run that would hang or silently produce NaN, with a message
// naming what happened, the simulated time and what to change. Plain checks on plain data, called
// by the run loop (libgran/run.cpp) between chunks of work, never per event:
//  - progress (event-driven engine), every `window` events:
//      stall:      the window did not advance the simulated time at all;
//      collapse:   the window's event rate (events per particle per unit simulated time) exceeds
//                  max_rate_growth times the rate of the run's first window (inelastic collapse:
//                  the rate diverges as the collision times shrink geometrically);
//      TC regime:  with the TC model on, more than max_events_per_tc events per particle within
//                  one window tc: the dynamics is made of the TC model's micro-collisions (a bed
//                  resting on a floor bounces every 2 tc), which the engine can only follow at
//                  about 1/tc events per particle per unit time.
//  - finiteness (both engines), at every sample and every window: positions, velocities and
//    angular velocities are finite.
#include <cmath>
#include <cstdint>
#include <string>

#include "libgran/core/species.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/scene/schedule.hpp"

namespace gran {

// One window of event-driven work: `events` events took the simulated time from t_begin to t_end.
struct ProgressWindow {
    std::uint64_t events = 0;
    double t_begin = 0;
    double t_end = 0;
    std::size_t particles = 1;
    double reference_rate = 0;  // events / (particle time) of the first window; 0: none yet
    double tc = 0;              // TC-model window; 0: the TC model is off
};

// Events per particle per unit simulated time of a window (+inf if the time did not advance).
double event_rate(const ProgressWindow& w);

// Empty if the window made progress; otherwise why the run must stop and what to change.
std::string check_progress(const WatchdogSettings& s, const ProgressWindow& w);

// Empty if every position, velocity and angular velocity is finite and so is the kinetic energy
// (velocities near 1e154 are finite but their squares are not); otherwise names the first
// particle (by its original index) and quantity that is not, the engine and the simulated time.
template <int D>
std::string check_finite(const EngineView<D>& view, const SpeciesTable& species);

}  // namespace gran
