#pragma once
// The grains the drift benchmarks (bench/drift_forms.cpp, bench/drift_widths.cpp) time their
// forms on: random positions in the vibrated bed's box (periodic x and y, 50 wide), velocities
// fast enough that some grains cross the periodic sides, two species; a bitwise comparison of two
// sets, and the new forces and torques of step t of the same-bits checks.
#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "libgran/core/vec.hpp"

namespace drift_bench {

using V3 = gran::Vec<3>;

struct Grains {
    std::vector<V3> r, v, v_pred, f, disp, w, w_pred, tau;
    std::vector<std::array<std::int32_t, 3>> image;
    std::vector<std::uint32_t> species;
};

inline Grains grains(std::size_t n) {
    Grains s;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto any = [&] { return V3(u(rng), u(rng), u(rng)); };
    for (std::size_t i = 0; i < n; ++i) {
        s.r.push_back(V3(25 + 24.999 * u(rng), 25 + 24.999 * u(rng), 5 + u(rng)));
        s.v.push_back(30 * any());
        s.v_pred.push_back(any());
        s.f.push_back(any());
        s.disp.push_back(0.01 * any());
        s.w.push_back(any());
        s.w_pred.push_back(any());
        s.tau.push_back(any());
        s.image.push_back({0, 0, 0});
        s.species.push_back(std::uint32_t(rng() % 2));
    }
    return s;
}

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
    return std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

inline bool same(const Grains& a, const Grains& b) {
    return same(a.r, b.r) && same(a.v, b.v) && same(a.v_pred, b.v_pred) && same(a.f, b.f) &&
           same(a.disp, b.disp) && same(a.w, b.w) && same(a.w_pred, b.w_pred) &&
           same(a.tau, b.tau) && same(a.image, b.image);
}

// New forces and torques for step t (as a pair stage would leave them).
inline void push(Grains& s, int t) {
    for (std::size_t i = 0; i < s.r.size(); ++i) {
        s.f[i] = V3(double(i % 7) - 3, t % 5 - 2.0, 0.3 * double(i));
        s.tau[i] = V3(1, t, 0.1 * double(i));
    }
}

}  // namespace drift_bench
