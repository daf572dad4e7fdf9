#pragma once
// Test helpers on a particle state: total kinetic energy (translational + rotational), momentum,
// and the brute-force O(N^2) closest approach (the smallest centre distance over contact distance:
// below 1 means two particles overlap, i.e. a collision was missed).
#include <algorithm>
#include <cmath>

#include "libgran/core/box.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/core/species.hpp"

namespace gran::testing {

template <int D>
double translational_energy(const Particles<D>& p, const SpeciesTable& t) {
    double e = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        e += 0.5 * t.species[p.species[i]].mass * p.v[i].squaredNorm();
    return e;
}

template <int D>
double rotational_energy(const Particles<D>& p, const SpeciesTable& t) {
    double e = 0;
    if (!p.rotating()) return e;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto& s = t.species[p.species[i]];
        e += 0.5 * s.inertia_factor * s.mass * s.diameter * s.diameter / 4 * ang_squared<D>(p.w[i]);
    }
    return e;
}

template <int D>
Vec<D> momentum(const Particles<D>& p, const SpeciesTable& t) {
    Vec<D> m = Vec<D>::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) m += t.species[p.species[i]].mass * p.v[i];
    return m;
}

template <int D>
double closest_approach(const Particles<D>& p, const SpeciesTable& t, const Box<D>& box) {
    double worst = kInf;
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            const double sig =
                0.5 * (t.species[p.species[i]].diameter + t.species[p.species[j]].diameter);
            worst = std::min(worst, box.separation(p.r[i], p.r[j]).norm() / sig);
        }
    }
    return worst;
}

}  // namespace gran::testing
