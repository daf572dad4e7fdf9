#pragma once
// What plugin factories may read about the scene they are built for. Engine-free: a plugin learns
// what the engine offers (binary collision records or not), never which engine runs.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/species.hpp"

namespace gran {

struct SceneInfo {
    int dimension = 2;
    std::uint64_t seed = 1;
    const SpeciesTable* species = nullptr;
    std::vector<double> box_length;
    std::vector<bool> periodic;
    double initial_temperature = 1;
    std::array<double, 3> gravity{0, 0, 0};
    // The contacts: whether grains carry angular velocities (some contact needs them), and the
    // nominal normal restitution of each species pair (for kinetic-theory estimates such as the
    // Enskog equation of state), stored per pair of contact classes (ContactTable, law.hpp).
    bool rotating = false;
    std::size_t contact_classes = 0;
    std::vector<std::uint32_t> contact_class;  // of each species
    std::vector<double> nominal_restitution;   // contact_classes x contact_classes
    double nominal_restitution_of(std::size_t a, std::size_t b) const {
        return nominal_restitution[std::size_t(contact_class[a]) * contact_classes +
                                   contact_class[b]];
    }
    // The engine produces binary collision records (instantaneous collisions); a soft-contact
    // engine has contacts of finite duration instead.
    bool binary_collisions = true;
    // Some driver injects energy (any driver but `none`): the run is meant to reach a steady
    // state. Without one the gas cools freely and time averages mix every temperature of the run.
    bool driven = false;
    // Largest speed of a moving wall (V_p = A omega of a vibrating base), 0 if none; known to the
    // observables (the drivers are built first).
    double peak_velocity = 0;
    double drive_period = 0;  // period of that wall's motion (0: none)
    // The room between the walls at t = 0, per axis: [room_lower, room_upper] (the walls' surfaces
    // then; [0, L] when every wall starts at its outermost position, and on periodic axes). The
    // initial placement puts the particles there (the drivers are built first).
    std::vector<double> room_lower, room_upper;
    std::size_t index = 0;  // position of the plugin in its list (distinct random streams)
};

}  // namespace gran
