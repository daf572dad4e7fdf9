// The DEM opening pass (libgran/engines/dem/drift.hpp) in its two forms, timed alone on the
// same grains: kick_drift_per_grain<3> (one grain at a time on Eigen 3-vectors) and
// kick_drift_pairs_3d (two grains per block in three SSE2 registers). First checks that both
// give the same bits over 50 steps with new forces each step (periodic wraps and an odd count
// included), then prints the best of five rounds in nanoseconds per grain, rotating or not.
// g++ -std=c++20 -O3 -fno-math-errno -I. -I/usr/include/eigen3 bench/drift_forms.cpp -o /tmp/df_bin
// /tmp/df_bin 10000 3000     (N grains, steps per round)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "bench/drift_grains.hpp"
#include "libgran/engines/dem/drift.hpp"

namespace {

using gran::Vec;
using V3 = gran::Vec<3>;

using drift_bench::Grains;
using drift_bench::grains;
using drift_bench::same;

gran::DriftArrays<3> arrays(Grains& s, const double* inv_mass, const double* inv_inertia) {
    return {s.r.data(),    s.v.data(),      s.v_pred.data(),  s.f.data(),
            s.disp.data(), s.image.data(),  s.species.data(), inv_mass,
            s.w.data(),    s.w_pred.data(), s.tau.data(),     inv_inertia};
}

constexpr double kInvMass[2] = {1.3, 0.7}, kInvInertia[2] = {3.1, 2.2};
const gran::DriftStep<3> kStep{1e-3, V3(0, 0, -1), {50, 50, 0}};  // the vibrated bed's box

template <bool Closing, bool Rot>
__attribute__((noinline)) double per_grain(Grains& s) {
    return gran::kick_drift_per_grain<3, Closing>(arrays(s, kInvMass, kInvInertia), kStep, Rot, 0,
                                                  s.r.size());
}

template <bool Closing, bool Rot>
__attribute__((noinline)) double pairs(Grains& s) {
    return gran::kick_drift_pairs_3d<Closing, Rot>(arrays(s, kInvMass, kInvInertia), kStep, 0,
                                                   s.r.size());
}

}  // namespace

int main(int argc, char** argv) {
    const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10000;
    const int reps = argc > 2 ? std::atoi(argv[2]) : 3000;
    using Drift = double (*)(Grains&);
    const Drift forms[4] = {per_grain<true, true>, pairs<true, true>, per_grain<true, false>,
                            pairs<true, false>};
    const char* names[4] = {"per grain, spins", "pairs, spins", "per grain", "pairs"};
    for (int spins = 1; spins >= 0; --spins) {  // an odd count, new forces every step
        Grains a = grains(n + 1), b = a;
        double ma = 0, mb = 0;
        for (int t = 0; t < 50; ++t) {
            drift_bench::push(a, t);
            drift_bench::push(b, t);
            ma = std::max(ma, forms[2 * (1 - spins)](a));
            mb = std::max(mb, forms[2 * (1 - spins) + 1](b));
        }
        const bool bits = same(a, b) && ma == mb;
        std::printf("same bits%s: %s\n", spins ? " with spins" : " without spins",
                    bits ? "yes" : "NO");
        if (!bits) return 1;
    }
    std::printf("%18s %8s %10s\n", "form", "N", "ns/grain");
    double best[4] = {1e9, 1e9, 1e9, 1e9};
    for (int round = 0; round < 5; ++round) {
        for (int k = 0; k < 4; ++k) {
            Grains s = grains(n);
            double sink = 0;
            const auto t0 = std::chrono::steady_clock::now();
            for (int t = 0; t < reps; ++t) sink += forms[k](s);
            const double ns =
                std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0)
                    .count() /
                (double(n) * reps);
            if (sink < 0) std::printf("unreachable\n");  // keeps the loop
            best[k] = std::min(best[k], ns);
        }
    }
    for (int k = 0; k < 4; ++k) std::printf("%18s %8zu %10.2f\n", names[k], n, best[k]);
}
