#pragma once
// What a scene will cost on the event-driven engine, from kinetic theory at the initial
// temperature (`gran check` prints it; runs that could never finish are refused at load): the
// collisions the schedule asks for (Enskog collision frequency of the mixture), the cell crossings
// of free flight between them (mean speed over the cell width of the engine's grid), and the
// particle updates of kicks (a thermostat kick touches every particle). An order of magnitude:
// gravity, walls and clustering change the rates as the run goes on.
#include <string>

#include "libgran/plugins/engine.hpp"

namespace gran {

struct EventEstimate {
    double simulated_time = 0;  // to the end of the schedule
    double collisions = 0;
    double crossings = 0;
    double kick_updates = 0;  // kicks x particles
    double events() const { return collisions + crossings + kick_updates; }
};

// More events than this is a run that cannot finish: at 1e7 events per second, three years.
inline constexpr double kMaxEvents = 1e15;
// A gas so dilute that each collision costs over a million cell crossings (free flights across
// the box between collisions, a Knudsen gas) is refused too when the run is long (over 1e12
// events, a day at 1e7 events per second): the engine would spend it on bookkeeping. A packing
// fraction of 1e-12 for 500 disks is 8e6 crossings per collision (docs/reliability.md).
inline constexpr double kMaxCrossingsPerCollision = 1e6;
inline constexpr double kLongRunEvents = 1e12;

EventEstimate estimate_events(const Scene& sc, const EngineDemands& demands);

// SceneError naming the key to change when the estimate exceeds kMaxEvents or is not finite, or
// when a long run is almost only cell crossings (kMaxCrossingsPerCollision).
void refuse_endless_run(const Scene& sc, const EventEstimate& e);

// One line for `gran check`.
std::string describe(const EventEstimate& e);

}  // namespace gran
