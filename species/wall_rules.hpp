#pragma once
// Particle-wall collision rules as plain functions on plain data. `inward` is +1 for a lower wall
// (the gas lies at larger coordinates) and -1 for an upper wall; v is the particle velocity, `axis`
// the wall normal. Every rule leaves the particle moving away from the wall (or at rest on it).
#include <cmath>

#include "libgran/random.hpp"
#include "libgran/vec.hpp"

namespace gran {

struct WallParams {
    double restitution = 1;          // normal restitution against the wall
    double temperature = 1;          // thermal wall temperature T0 [energy]
    double velocity = 0;             // sawtooth wall speed v0 [velocity]
    bool redraw_tangential = false;  // thermal wall: also redraw tangential components
};

// Static wall: v_n' = -e v_n.
template <int D>
inline void static_wall_rule(Vec<D>& v, int axis, double /*inward*/, const WallParams& w,
                             Rng& /*rng*/, double /*mass*/) {
    v[axis] = -w.restitution * v[axis];
}

// Sawtooth vibrating wall (Barrat & Trizac 2002, Sec. III A): an infinitely massive wall met with
// velocity v0 directed into the gas at a fixed position. Relative normal velocity reversed and
// scaled by e: v_n' - u = -e (v_n - u) with u = inward * v0, i.e. v_n' = 2 u - v_n for e = 1 (the
// paper's rule).
template <int D>
inline void sawtooth_wall_rule(Vec<D>& v, int axis, double inward, const WallParams& w,
                               Rng& /*rng*/, double /*mass*/) {
    const double u = inward * w.velocity;
    v[axis] = (1.0 + w.restitution) * u - w.restitution * v[axis];
}

// Thermal wall at temperature T0 (Barrat & Trizac 2002, Sec. III A; Grossman, Zhou & Ben-Naim
// 1997): the outgoing normal speed is drawn from the flux distribution P(v) = (m v / T0) exp(-m v^2
// / (2 T0)), v > 0, by inversion v = sqrt(-2 T0 ln(1 - U) / m); tangential components are kept (the
// paper's rule) or redrawn from the Maxwellian at T0.
template <int D>
inline void thermal_wall_rule(Vec<D>& v, int axis, double inward, const WallParams& w, Rng& rng,
                              double mass) {
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
