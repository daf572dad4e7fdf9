#pragma once
// Initial placements as plugins (`initial.placement`): a placement puts the scene's particles in
// the box (positions and species; velocities are drawn afterwards). Registered like every plugin.
#include <functional>

#include "libgran/core/box.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/core/random.hpp"
#include "libgran/core/registry.hpp"
#include "libgran/core/species.hpp"

namespace gran {

struct PlacementPlugin : PluginInfo {
    std::function<Particles<2>(const Box<2>&, const SpeciesTable&, Rng&)> place2;
    std::function<Particles<3>(const Box<3>&, const SpeciesTable&, Rng&)> place3;

    template <int D>
    Particles<D> place(const Box<D>& box, const SpeciesTable& species, Rng& rng) const {
        if constexpr (D == 2) {
            return place2(box, species, rng);
        } else {
            return place3(box, species, rng);
        }
    }
};

using PlacementRegistry = Registry<PlacementPlugin>;

// Introduction of the placements in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kPlacementsDescription =
    R"md(
`initial.placement` chooses how the particles are put in the box; velocities are then drawn from
the Maxwellian at `initial.temperature` with zero total momentum (and angular velocities too on
the event-driven engine when some contact needs them).)md";

}  // namespace gran
