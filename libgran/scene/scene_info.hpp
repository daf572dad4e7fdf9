#pragma once
// What plugin factories may read about the scene they are built for.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "species/species.hpp"

namespace gran {

struct SceneInfo {
    int dimension = 2;
    std::uint64_t seed = 1;
    const SpeciesTable* species = nullptr;
    std::vector<double> box_length;
    std::vector<bool> periodic;
    double initial_temperature = 1;
    std::array<double, 3> gravity{0, 0, 0};
    std::string engine = "event_driven";  // engine.type
    // Largest speed of a moving wall (V_p = A omega of a vibrating base), 0 if none; known to the
    // observables (the drivers are built first).
    double peak_velocity = 0;
    double drive_period = 0;  // period of that wall's motion (0: none)
    std::size_t index = 0;    // position of the plugin in its list (distinct random streams)
};

}  // namespace gran
