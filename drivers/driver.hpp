#pragma once
// Energy injection and confinement. A driver may own global events (e.g. thermostat kicks): the run
// loop stops the engine at next_time(), synchronises all particles, and calls fire().
#include <yaml-cpp/yaml.h>

#include "libgran/event_driven_engine.hpp"
#include "libgran/h5.hpp"
#include "libgran/registry.hpp"
#include "libgran/scene_info.hpp"

namespace gran {

template <int D>
class Driver {
  public:
    virtual ~Driver() = default;
    // Called once the engine exists, before the run (e.g. to install wall rules).
    virtual void attach(EventDrivenEngine<D>& /*engine*/) {}
    // Time of the next global event of this driver (+inf: none).
    virtual double next_time() const { return kInf; }
    // Called with the engine synchronised at next_time(); must call engine.velocities_changed()
    // if it changed velocities.
    virtual void fire(EventDrivenEngine<D>& /*engine*/) {}
    // Its own statistics (e.g. injected energy) under /drivers/<name>, and lines for the summary.
    virtual void write(h5::Group& /*group*/, YAML::Node& /*summary*/) const {}
};

}  // namespace gran
