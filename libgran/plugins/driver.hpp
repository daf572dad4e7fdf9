#pragma once
// Energy injection and confinement, engine-free: a driver describes what it does and each engine
// translates it.
//  - walls(): the walls it puts on bounded axes (libgran/plugins/wall.hpp), each with a motion and
//    a partner name in `interactions` (or a rule replacing the contact, a thermal wall);
//  - next_kick() and kick(): global kick events (a thermostat): the run stops the engine at
//    next_kick(), brings every particle to that time, calls kick() on the velocities and tells the
//    engine they changed.
// Gravity is a scene key, not a driver.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "libgran/core/registry.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/plugins/scene_info.hpp"
#include "libgran/plugins/wall.hpp"
#include "libgran/run/result_sink.hpp"

namespace gran {

template <int D>
class Driver {
  public:
    virtual ~Driver() = default;
    // The walls this driver puts on bounded axes (called once, before the run).
    virtual std::vector<WallSpec<D>> walls() { return {}; }
    // Time of the next kick event (+inf: none), and the kick: every particle's velocity at that
    // time, in the engine's storage order (species from `species`).
    virtual double next_kick() const { return kInf; }
    virtual void kick(Particles<D>& /*particles*/, const SpeciesTable& /*species*/) {}
    // Once the engine runs: what the driver may read of it (e.g. the hits on its walls).
    virtual void observe(const EngineView<D>& /*view*/) {}
    // Largest speed of a moving boundary (V_p = A omega of a vibrating wall), 0 if none: the
    // velocity scale of the vibrated-bed observables (W = V_p^2 / (d g)).
    virtual double peak_velocity() const { return 0; }
    // Period of that motion (0: none), for phase-resolved averages.
    virtual double drive_period() const { return 0; }
    // Its own statistics (e.g. injected energy) under /drivers/<name> and the summary's
    // drivers.<name> (libgran/run/result_sink.hpp).
    virtual void write(ResultGroup& /*out*/) const {}
    // Every member that changes during the run (next kick, random streams, injected energy), in
    // one function for saving and loading (libgran/core/state_archive.hpp), wall reflections
    // included: a checkpoint restores it and the resumed run must continue bit for bit.
    virtual void checkpoint(StateArchive& ar) = 0;
};

using DriverRegistry = Registry<DimensionalPlugin<Driver>>;

// Introduction of the drivers in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kDriversDescription =
    R"md(
Each entry of the scene's `drivers` list is `{type: <name>, ...parameters}`; an optional `name`
sets the result group name (default: the type) and, for a wall driver, the name of its walls in
`interactions`.)md";

}  // namespace gran
