#pragma once
// The initial state of a scene: its box, and the particles placed by the scene's placement with
// Maxwellian velocities (angular velocities too when some contact needs them and the engine starts
// rotating grains thermalised, EnginePlugin::thermal_initial_spin). Placement failures are
// SceneErrors naming the box.
#include "libgran/core/box.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

template <int D>
Box<D> make_box(const Scene& sc);

template <int D>
Particles<D> initial_particles(const Scene& sc);

}  // namespace gran
