#pragma once
// Test helper: the contacts of a species table from an `interactions` section written as YAML
// text (libgran/scene/interactions.hpp), for tests that build an engine directly.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "libgran/core/particles.hpp"
#include "libgran/scene/interactions.hpp"

namespace gran::testing {

// `walls`: the wall partners (default: `box`, the walls of bounded axes no driver claims).
inline ContactTable contacts_of(const SpeciesTable& species, const std::string& interactions = "",
                                int dimension = 3, std::vector<std::string> walls = {"box"},
                                double temperature = 1) {
    YAML::Node resolved;
    const LawContext context{dimension, temperature, species.min_mass()};
    return read_interactions(YAML::Load(interactions.empty() ? "{}" : interactions), species, walls,
                             context, Where{"test", ""}, resolved);
}

// Angular velocities (zero) when the contacts need them and the particles have none.
template <int D>
void allocate_rotation(Particles<D>& p, const ContactTable& c) {
    if (c.rotating && !p.rotating()) p.w.assign(p.size(), ang_zero<D>());
}

}  // namespace gran::testing
