#include "libgran/scene/plugin_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "libgran/plugins/engine.hpp"
#include "libgran/scene/interactions.hpp"

namespace gran {

namespace {

// What every plugin reads: the scene without the drivers' and contacts' contributions yet.
SceneInfo base_info(const Scene& sc) {
    SceneInfo info;
    info.dimension = sc.dimension;
    info.seed = sc.seed;
    info.species = &sc.species;
    info.box_length = sc.box_length;
    info.periodic = sc.periodic;
    info.initial_temperature = sc.temperature;
    info.gravity = sc.gravity;
    info.binary_collisions = sc.engine->binary_collisions;
    info.driven = std::any_of(sc.drivers.begin(), sc.drivers.end(),
                              [](const PluginEntry& d) { return d.type != "none"; });
    return info;
}

// Narrows the room of the initial placement to a wall's surface at t = 0 (a wall of a vibrating
// box, or a vibrating wall started at another phase than its outermost position).
template <int D>
void note_room(SceneInfo& info, const WallSpec<D>& w) {
    const auto a = std::size_t(w.axis);
    if (info.room_lower.empty()) {
        info.room_lower.assign(std::size_t(D), 0.0);
        info.room_upper = info.box_length;
    }
    // How far inside its outermost position the surface starts (0 for a wall that starts there,
    // which keeps the room exactly [0, L]).
    const double inset = w.motion.reach() + (w.side == 0 ? 1 : -1) * w.motion.position(0.0);
    if (!(inset > 1e-12 * info.box_length[a])) return;
    if (w.side == 0) {
        info.room_lower[a] = std::max(info.room_lower[a], inset);
    } else {
        info.room_upper[a] = std::min(info.room_upper[a], info.box_length[a] - inset);
    }
}

// The drivers: built once; their walls (each side of an axis given by one driver at most) and
// kicks become the engine's demands, their wall partners the names of grain-wall contacts.
template <int D>
void check_drivers(Scene& sc, EngineDemands& demands, std::vector<std::string>& partners) {
    std::array<const PluginEntry*, 2 * D> owner{};
    for (std::size_t k = 0; k < sc.drivers.size(); ++k) {
        const PluginEntry& e = sc.drivers[k];
        auto driver =
            DriverRegistry::instance().find(e.type)->template make<D>(e.params, plugin_info(sc, k));
        for (const WallSpec<D>& w : driver->walls()) {
            const auto*& slot = owner[std::size_t(2 * w.axis + w.side)];
            if (slot) {
                e.params.fail("type",
                              fmt::format("the {} wall of axis {} is already given by "
                                          "driver '{}'",
                                          w.side == 0 ? "lower" : "upper", w.axis, slot->name));
            }
            slot = &e;
            note_room(sc.info, w);
            demands.walls.push_back(
                {k, w.partner, w.axis, w.side, w.motion, w.motion_key, w.reflection != nullptr});
            if (!w.reflection &&
                std::find(partners.begin(), partners.end(), w.partner) == partners.end()) {
                if (w.partner == "box") {
                    e.params.fail("name",
                                  "`box` names the walls no driver claims: give this "
                                  "driver another `name`");
                }
                partners.push_back(w.partner);
            }
        }
        if (driver->next_kick() < kInf) {
            demands.kick_drivers.push_back(k);
            demands.first_kicks.push_back(driver->next_kick());
        }
        if (driver->peak_velocity() > sc.info.peak_velocity) {
            sc.info.peak_velocity = driver->peak_velocity();
            sc.info.drive_period = driver->drive_period();
        }
    }
    // The walls of bounded axes that no driver claims (static walls at 0 and L).
    for (int a = 0; a < D; ++a) {
        if (!sc.periodic[std::size_t(a)]) {
            partners.push_back("box");
            break;
        }
    }
}

template <int D>
void check_observables(const Scene& sc, EngineDemands& demands) {
    for (std::size_t k = 0; k < sc.observables.size(); ++k) {
        const PluginEntry& e = sc.observables[k];
        auto observable = ObservableRegistry::instance().find(e.type)->template make<D>(
            e.params, plugin_info(sc, k));
        if (observable->collision_sink()) demands.collision_observables.push_back(k);
    }
}

}  // namespace

template <int D>
void check_plugins(Scene& sc, const YAML::Node& root, const Where& top, YAML::Node& res) {
    sc.info = base_info(sc);
    EngineDemands demands;
    std::vector<std::string> partners;
    check_drivers<D>(sc, demands, partners);
    const LawContext context{D, sc.temperature, sc.species.min_mass()};
    YAML::Node ri;
    sc.contacts =
        read_interactions(child(root, "interactions"), sc.species, partners, context, top, ri);
    res["interactions"] = ri;
    sc.info.rotating = sc.contacts.rotating;
    sc.info.contact_classes = sc.contacts.classes;
    sc.info.contact_class = sc.contacts.class_of;
    sc.info.nominal_restitution = sc.contacts.nominal_restitution;
    check_observables<D>(sc, demands);
    sc.engine->check(sc, demands);
    if (sc.engine->estimate) sc.cost = sc.engine->estimate(sc, demands);
}

template void check_plugins<2>(Scene&, const YAML::Node&, const Where&, YAML::Node&);
template void check_plugins<3>(Scene&, const YAML::Node&, const Where&, YAML::Node&);

}  // namespace gran
