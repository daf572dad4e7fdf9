#include "libgran/scene/moved_keys.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "libgran/core/params.hpp"

namespace gran {

namespace {

struct Moved {
    const char* key;
    const char* now;  // where it lives now, with an example
};

// engine.<key>: the soft-contact keys are the keys of the contact law.
const std::vector<Moved> kEngineKeys{
    {"contact_law",
     "`interactions: {law: <name>}` (linear_dashpot, cundall_strack, "
     "hertz_mindlin; `gran list laws`)"},
    {"stiffness",
     "`interactions: {law: linear_dashpot, stiffness: <k_n>}` (per contact in "
     "`interactions.pairs`)"},
    {"contact_time", "`interactions: {law: linear_dashpot, contact_time: <t_c>}`"},
    {"friction", "`interactions: {friction: <mu>}` (per contact in `interactions.pairs`)"},
    {"tangential_damping", "`interactions: {tangential_damping: <c_t>}`"},
    {"tangential_damping_ratio", "`interactions: {tangential_damping_ratio: <c_t / c_n>}`"},
    {"tangential_stiffness_ratio", "`interactions: {tangential_stiffness_ratio: <k_t / k_n>}`"},
    {"reference_speed",
     "`interactions: {reference_speed: <v>}` (hertz_mindlin), and "
     "`engine.probe_speed` for the isolated test collisions of a dem run"},
    {"wall_friction", "`interactions: {walls: {friction: <mu_w>}}`"},
    {"wall_tangential_damping", "`interactions: {walls: {tangential_damping: <c_t>}}`"},
};

// drivers[k].<key>: a wall's restitution is the contact law of the grain-wall contact.
const std::vector<std::string> kWallKeys{"restitution", "restitution_law", "r0", "v0", "gamma"};

}  // namespace

void refuse_moved_keys(const YAML::Node& root, const Where& top) {
    const YAML::Node engine = child(root, "engine");
    for (const Moved& m : kEngineKeys) {
        const YAML::Node n = child(engine, m.key);
        if (n.IsDefined()) {
            fail(top.child("engine").child(m.key), n,
                 fmt::format("contact physics moved to `interactions`: write {} (`engine` keeps "
                             "the numerical settings only)",
                             m.now));
        }
    }
    const YAML::Node drivers = child(root, "drivers");
    if (!drivers.IsSequence()) return;
    for (std::size_t k = 0; k < drivers.size(); ++k) {
        for (const auto& key : kWallKeys) {
            const YAML::Node n = child(drivers[k], key);
            if (!n.IsDefined()) continue;
            const YAML::Node name = child(drivers[k], "name").IsDefined()
                                        ? child(drivers[k], "name")
                                        : child(drivers[k], "type");
            const std::string wall = name.IsScalar() ? name.Scalar() : "<driver name>";
            fail(top.child("drivers").item(k).child(key), n,
                 fmt::format("a wall's restitution is the law of its grain-wall contacts, in "
                             "`interactions`: `pairs: [{{between: [<species>, {}], alpha: <e>}}]` "
                             "for this wall (`restitution: <e>` with a soft-contact law, `law: "
                             "mcnamara_falcon` with r0, v0 for r(v)), or `walls: {{...}}` for "
                             "every wall",
                             wall));
        }
    }
}

}  // namespace gran
