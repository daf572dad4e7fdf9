#pragma once
// What plugin factories may read about the scene they are built for.
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
    std::size_t index = 0;  // position of the plugin in its list (distinct random streams)
};

}  // namespace gran
