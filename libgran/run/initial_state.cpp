#include "libgran/run/initial_state.hpp"

#include "libgran/core/random.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/plugins/placement.hpp"
#include "libgran/scene/placement.hpp"

namespace gran {

template <int D>
Box<D> make_box(const Scene& sc) {
    Box<D> box;
    for (int a = 0; a < D; ++a) {
        box.length[a] = sc.box_length[std::size_t(a)];
        box.periodic[std::size_t(a)] = sc.periodic[std::size_t(a)];
    }
    return box;
}

template <int D>
Particles<D> initial_particles(const Scene& sc) {
    // The placement fills the room between the walls at t = 0 (SceneInfo::room_lower/upper):
    // a box of that size, shifted into place.
    Box<D> box = make_box<D>(sc);
    Vec<D> shift = Vec<D>::Zero();
    if (!sc.info.room_lower.empty()) {
        for (int a = 0; a < D; ++a) {
            if (box.periodic[std::size_t(a)]) continue;
            shift[a] = sc.info.room_lower[std::size_t(a)];
            box.length[a] = sc.info.room_upper[std::size_t(a)] - shift[a];
        }
    }
    Rng rng = make_rng(sc.seed, Stream::Placement);
    Particles<D> p;
    try {
        p = sc.placement->template place<D>(box, sc.species, rng);
    } catch (const PlacementError& e) {
        throw SceneError(sc.box_location + ": " + e.what());
    }
    if (!shift.isZero()) {
        for (auto& r : p.r) r += shift;
    }
    if (sc.contacts.rotating && sc.engine->thermal_initial_spin)
        p.w.assign(p.size(), ang_zero<D>());
    Rng vrng = make_rng(sc.seed, Stream::Velocities);
    maxwellian_velocities<D>(p, sc.species, sc.temperature, vrng);
    return p;
}

template Box<2> make_box<2>(const Scene&);
template Box<3> make_box<3>(const Scene&);
template Particles<2> initial_particles<2>(const Scene&);
template Particles<3> initial_particles<3>(const Scene&);

}  // namespace gran
