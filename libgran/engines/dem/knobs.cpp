// The DEM engine's fidelity knobs for `gran tradeoff` (libgran/study/knob.hpp): its time step
// as a fraction of the contact time, and the engine itself (the event-driven hard-sphere limit).
#include "libgran/scene/scene.hpp"
#include "libgran/study/knob.hpp"

namespace gran {
namespace {

KnobOutcome dt_over_tc(const KnobContext& c) {
    if (knobs::engine_type(c) != "dem") return "the event-driven engine has no time step";
    const YAML::Node eng = c.resolved["engine"];
    if (knobs::real_at(eng, "dt") > 0) return "engine.dt is set explicitly; use engine.dt_fraction";
    return knobs::scaled("dt_over_tc", "DEM time step as a fraction of the contact time t_c",
                         "engine.dt_fraction", knobs::real_at(eng, "dt_fraction", 0.02),
                         {4, 2, 1, 0.5}, 0.2);
}

KnobOutcome engine(const KnobContext& c) {
    if (knobs::engine_type(c) != "dem") return "the scene is event-driven already (the hard limit)";
    if (c.scene.contacts.rotating) {
        return "friction makes the soft-sphere model differ from the event-driven one (rough hard "
               "spheres have a tangential restitution instead)";
    }
    return Knob{"engine",
                "event-driven hard spheres: the k_n -> infinity, dt -> 0 limit",
                {{"dem", {}}, {"event_driven", {{"engine", "{type: event_driven}"}}}},
                0};
}

const bool registered_dt = register_knob(
    "dt_over_tc", 10, "DEM engine.dt_fraction x 4, 2, 1, 1/2 (never above 0.2)", dt_over_tc);
const bool registered_engine = register_knob(
    "engine", 30, "a frictionless DEM scene also runs on the event-driven engine (the hard limit)",
    engine);

}  // namespace
}  // namespace gran
