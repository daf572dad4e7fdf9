#pragma once
// What the waveform tests (test_wall_motion.cpp) and the wall-contact tests
// (test_wall_contact.cpp) share: long double, their constants, and McNamara & Falcon's parabolic
// piston (2005, Sec. II B) written independently of libgran/core/wall_motion.hpp.
#include <cmath>
#include <limits>
#include <numbers>

namespace gran::testing::wall {

using ld = long double;
constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// The paper's piston, written independently: period 4 t0 = 1 / f, parabolas on [-t0, t0] and
// [t0, 3 t0] (with the 1 / t0^2 and the centring on 2 t0 that the printed formula lost).
struct PaperPiston {
    ld A, f;
    ld t0() const { return 1 / (4 * f); }
    ld reduce(ld t) const { return t - floorl((t + t0()) * f) / f; }  // into [-t0, 3 t0)
    ld z(ld t) const {
        const ld u = reduce(t), c = t0();
        return u <= c ? A / (2 * c * c) * (u * u - c * c)
                      : -A / (2 * c * c) * ((u - 2 * c) * (u - 2 * c) - c * c);
    }
    ld dz(ld t) const {
        const ld u = reduce(t), c = t0();
        return u <= c ? A * u / (c * c) : -A * (u - 2 * c) / (c * c);
    }
    ld d2z(ld t) const { return reduce(t) <= t0() ? A / (t0() * t0()) : -A / (t0() * t0()); }
};

}  // namespace gran::testing::wall
