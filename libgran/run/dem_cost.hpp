#pragma once
// What a scene will cost on the dem engine: the engine steps with a fixed time step through the
// schedule (in time: the dem engine refuses collisions per particle), every step moving every
// particle, so the work is particle-steps = particles x simulated time / dt. `gran check` prints it
// with the rate measured on this build (which already includes the contacts per particle of this
// packing); runs that could never finish are refused at load, naming the key to change.
#include <string>

#include "libgran/plugins/run_cost.hpp"

namespace gran {

struct Scene;

struct DemEstimate {
    double particles = 0;
    double simulated_time = 0;  // equilibration + measurement
    double dt = 0;              // the engine's time step (dem_time_step)
    double contact_time = 0;    // shortest contact duration t_c the step resolves
    // Time a grain takes to move its diameter at the fastest velocity of the scene (thermal
    // speed at the initial temperature, wall speed, free fall over a diameter): the physics' own
    // clock, against which a run is long or a contact short.
    double grain_time = 0;
    double steps() const { return simulated_time / dt; }
    double particle_steps() const { return particles * steps(); }
};

// More particle-steps than this is a run that cannot finish: at 1e7 particle-steps per second
// (dense frictional beds on one core), three years; even at the 1e8 of the bare gas
// (docs/performance.md: 7-11 ns per particle-step), four months.
inline constexpr double kMaxParticleSteps = 1e15;

// The estimate of a scene (schedule in time). Throws std::invalid_argument from dem_time_step when
// the time step is not usable.
DemEstimate estimate_particle_steps(const Scene& sc);

// SceneError naming the key to change when the estimate exceeds kMaxParticleSteps or is not
// finite: the factor furthest above its usual value (time step per contact, contact duration per
// grain time, run length in grain times, particles) names it.
void refuse_endless_run(const Scene& sc, const DemEstimate& e);

// One line for `gran check`, and the cost it stands for.
std::string describe(const DemEstimate& e);
RunCost run_cost(const DemEstimate& e);

}  // namespace gran
