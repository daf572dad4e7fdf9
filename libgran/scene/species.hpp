#pragma once
// The `species` list of a scene: validated, number fractions resolved into counts.
#include <yaml-cpp/yaml.h>

#include <cstdint>

#include "libgran/core/params.hpp"
#include "libgran/core/species.hpp"

namespace gran {

Schema species_schema();

// Parses the `species` list. `total_particles` (> 0) resolves number_fraction entries; inertia
// factors left out are set from the dimension (1/2 disks, 2/5 spheres). The resolved list (counts,
// defaults) goes to `resolved`.
SpeciesTable read_species(const YAML::Node& species, std::int64_t total_particles, int dimension,
                          const Where& where, YAML::Node& resolved);

}  // namespace gran
