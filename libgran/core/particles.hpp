#pragma once
// Particle state in structure-of-arrays form. Positions are lazy: r[i] is the position at the
// particle's own clock t[i]; the engine brings a particle up to date only when it takes part in an
// event (or when observables need positions).
#include <array>
#include <cstdint>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/core/vec.hpp"

namespace gran {

template <int D>
struct Particles {
    std::vector<Vec<D>> r;
    std::vector<Vec<D>> v;
    std::vector<double> t;
    std::vector<std::uint32_t> species;
    std::vector<AngVec<D>> w;  // empty unless some pair law needs rotation
    // Periodic images: how many times each particle crossed each periodic axis (+1 leaving at
    // L, -1 at 0), so r + image * L is its unwrapped position (trajectories, H5MD `image`).
    std::vector<std::array<std::int32_t, D>> image;

    std::size_t size() const { return r.size(); }
    void checkpoint(StateArchive& ar) {
        ar.section("particles");
        ar.io(r);
        ar.io(v);
        ar.io(t);
        ar.io(species);
        ar.io(w);
        ar.io(image);
    }
    bool rotating() const { return !w.empty(); }
    void resize(std::size_t n, bool with_rotation) {
        r.assign(n, Vec<D>::Zero());
        v.assign(n, Vec<D>::Zero());
        t.assign(n, 0.0);
        species.assign(n, 0);
        image.assign(n, {});
        if (with_rotation) {
            if constexpr (D == 2) {
                w.assign(n, 0.0);
            } else {
                w.assign(n, AngVec<D>::Zero());
            }
        } else {
            w.clear();
        }
    }
};

}  // namespace gran
