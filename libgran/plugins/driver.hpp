#pragma once
// Energy injection and confinement. A driver may own global events (e.g. thermostat kicks): the run
// loop stops the engine at next_time(), synchronises all particles, and calls fire().
#include <yaml-cpp/yaml.h>

#include <string>

#include "libgran/core/h5.hpp"
#include "libgran/core/registry.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/scene_info.hpp"

namespace gran {

template <int D>
class Driver {
  public:
    virtual ~Driver() = default;
    // Called once the engine exists, before the run (e.g. to install wall rules).
    virtual void attach(EventDrivenEngine<D>& /*engine*/) {}
    // The same on the soft-sphere DEM engine (engine.type: dem), which has walls but no global
    // events. Returns an empty string, or why this driver cannot run there (the scene is refused
    // with that message at the driver's `dem_refusal_key()`).
    virtual std::string attach(DemEngine<D>& /*engine*/) {
        return "this driver is not available on the dem engine (engine.type: dem supports "
               "static_wall and vibrating_wall)";
    }
    virtual std::string dem_refusal_key() const { return "type"; }
    // Largest speed of a moving boundary (V_p = A omega of a vibrating wall), 0 if none: the
    // velocity scale of the vibrated-bed observables (W = V_p^2 / (d g)).
    virtual double peak_velocity() const { return 0; }
    // Period of that motion (0: none), for phase-resolved averages.
    virtual double drive_period() const { return 0; }
    // Time of the next global event of this driver (+inf: none).
    virtual double next_time() const { return kInf; }
    // Called with the engine synchronised at next_time(); must call engine.velocities_changed()
    // if it changed velocities.
    virtual void fire(EventDrivenEngine<D>& /*engine*/) {}
    // Its own statistics (e.g. injected energy) under /drivers/<name>, and lines for the summary.
    virtual void write(h5::Group& /*group*/, YAML::Node& /*summary*/) const {}
};

// Introduction of the drivers in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kDriversDescription =
    R"md(
Each entry of the scene's `drivers` list is `{type: <name>, ...parameters}`; an optional `name`
sets the result group name (default: the type).)md";

}  // namespace gran
