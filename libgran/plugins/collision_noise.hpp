#pragma once
// White-noise heating applied at collisions (the stochastic thermostat's `kicks: at_collisions`,
// drivers/stochastic_thermostat.cpp): a driver that owns a CollisionNoise hands it to the
// event-driven engine, which kicks both partners of every binary collision right after the
// collision rule, each with the noise accumulated since that particle's previous kick:
//   dv ~ N(0, rate_s * (t - t_last) * I_D),   rate_s the velocity variance per component and
// per unit time of species s (xi_s^2 of the Fokker-Planck term (xi_s^2 / 2) Laplacian_v f_s,
// van Noije & Ernst, Granular Matter 1, 57 (1998)).
// The injected variance per unit time is the white noise's exactly, whatever the collision
// sequence; only the instants of the kicks differ (the particle's own collisions, where its next
// event is predicted anyway, instead of a common clock that forces every prediction to be
// redone). The noise is plain data and the kick a plain function, so the engine's collision does
// not pay a virtual call.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "libgran/core/random.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/core/vec.hpp"

namespace gran {

struct CollisionNoise {
    std::vector<double> variance_rate;  // per species [velocity^2 / time], per component
    std::vector<double> mass;           // per species, for the energy and momentum sums
    Rng rng;
    double injected_energy = 0;        // sum of the kicks' kinetic energy changes
    std::array<double, 3> momentum{};  // sum of m dv since the drift was last removed
    std::uint64_t kicks = 0;

    void checkpoint(StateArchive& ar) {
        ar.io(rng);
        ar.io(injected_energy);
        ar.io(momentum);
        ar.io(kicks);
    }
};

// Kicks velocity v of a particle of species s that was last kicked dt ago.
template <int D>
inline void apply_collision_noise(CollisionNoise& noise, std::uint32_t s, double dt, Vec<D>& v) {
    const double sd = std::sqrt(noise.variance_rate[s] * dt);
    Vec<D> dv;
    for (int a = 0; a < D; ++a) dv[a] = sd * gaussian(noise.rng);
    const double m = noise.mass[s];
    noise.injected_energy += m * (v.dot(dv) + 0.5 * dv.squaredNorm());
    for (int a = 0; a < D; ++a) noise.momentum[std::size_t(a)] += m * dv[a];
    v += dv;
    ++noise.kicks;
}

}  // namespace gran
