#pragma once
// Particle-wall collision rules as plain functions on plain data. `inward` is +1 for a lower wall
// (the gas lies at larger coordinates) and -1 for an upper wall; v is the particle velocity, `axis`
// the wall normal, u the wall's velocity along it. Every rule leaves the particle moving away from
// the wall (or at rest on it).
#include <cmath>

#include "libgran/core/random.hpp"
#include "libgran/core/vec.hpp"
#include "species/impact_restitution.hpp"

namespace gran {

struct WallParams {
    // Normal restitution against the wall, possibly a function of the impact speed |v_n - u|
    // (species/impact_restitution.hpp); elastic by default.
    ImpactRestitution restitution = constant_impact_restitution(1.0);
    double temperature = 1;          // thermal wall temperature T0 [energy]
    bool redraw_tangential = false;  // thermal wall: also redraw tangential components
};

// A wall of infinite mass moving with velocity u along its normal (u = 0: a static wall; a
// sawtooth wall reports u = inward v0, Barrat & Trizac 2002, Sec. III A; a piston its waveform's
// velocity, McNamara & Falcon 2005, Sec. II B): the relative normal velocity is reversed and
// scaled, v_n' - u = -e (v_n - u), with e = e(|v_n - u|). For e = 1 and u = inward v0 this is the
// sawtooth rule v_n' = 2 u - v_n.
template <int D>
inline void impact_wall_rule(Vec<D>& v, int axis, double /*inward*/, double u, const WallParams& w,
                             Rng& /*rng*/, double /*mass*/) {
    const double e = restitution(w.restitution, v[axis] - u);
    v[axis] = (1.0 + e) * u - e * v[axis];  // exactly 2 u - v_n for e = 1
}

// Thermal wall at temperature T0 (Barrat & Trizac 2002, Sec. III A; Grossman, Zhou & Ben-Naim
// 1997): the outgoing normal speed is drawn from the flux distribution P(v) = (m v / T0) exp(-m v^2
// / (2 T0)), v > 0, by inversion v = sqrt(-2 T0 ln(1 - U) / m); tangential components are kept (the
// paper's rule) or redrawn from the Maxwellian at T0.
template <int D>
inline void thermal_wall_rule(Vec<D>& v, int axis, double inward, double /*u: a static wall*/,
                              const WallParams& w, Rng& rng, double mass) {
    const double u = uniform01(rng);
    v[axis] = inward * std::sqrt(-2.0 * w.temperature * std::log1p(-u) / mass);
    if (w.redraw_tangential) {
        const double sd = std::sqrt(w.temperature / mass);
        for (int a = 0; a < D; ++a) {
            if (a != axis) v[a] = sd * gaussian(rng);
        }
    }
}

}  // namespace gran
