// The DEM drift with wider vectors: whether the opening pass of a step (DemEngine::kick_drift:
// closing and opening half kicks, predictor, drift, displacement tally, periodic wrap, and the
// same for the spins) gets faster when its arithmetic runs 2 or 4 grains' components at a time.
// A standalone copy, not the engine's code: `reference` is the engine's loop (Eigen 3-vectors,
// scalar on the baseline x86-64), `sse2` and `avx2` treat each array as 3N doubles, two grains
// (three 2-lane vectors) or four grains (three 4-lane vectors) per block, with the same
// operations in the same order (no FMA), so all three give the same bits, which the first line
// checks. Prints the best of five rounds of each, in nanoseconds per grain (docs/performance.md,
// "Measured with clocks").
// g++ -std=c++20 -O3 -fno-math-errno -I. -I/usr/include/eigen3 bench/drift_widths.cpp -o /tmp/dw_bin
// /tmp/dw_bin 10000 3000     (N grains, steps per round)
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "bench/drift_grains.hpp"

namespace {

using V3 = drift_bench::V3;

using drift_bench::Grains;
using drift_bench::grains;
using drift_bench::same;

constexpr double kInvMass[2] = {1.3, 0.7}, kInvInertia[2] = {3.1, 2.2};
constexpr double kPeriod[3] = {50, 50, 0};  // periodic x and y, bounded z: the vibrated bed
constexpr double kDt = 1e-3, kHalf = 0.5e-3;
const V3 kGravity(0, 0, -1);

void wrap(double& x, std::int32_t& image, double period) {
    if (period == 0) return;
    if (x < 0) {
        x += period;
        if (x >= period) x = 0;
        --image;
    } else if (x >= period) {
        x -= period;
        ++image;
    }
}

__attribute__((noinline)) double reference(Grains& s, std::size_t i0, std::size_t i1) {
    double moved2 = 0;
    for (std::size_t i = i0; i < i1; ++i) {
        const V3 ha = kHalf * (kInvMass[s.species[i]] * s.f[i] + kGravity);
        V3 vi = s.v[i];
        vi += ha;  // closing half kick of the previous step
        vi += ha;  // opening half kick
        s.f[i].setZero();
        s.v[i] = vi;
        s.v_pred[i] = vi + ha;
        const V3 dr = kDt * vi;
        V3 ri = s.r[i] + dr;
        const V3 di = s.disp[i] + dr;
        s.disp[i] = di;
        moved2 = std::max(moved2, di.squaredNorm());
        for (int k = 0; k < 3; ++k) wrap(ri[k], s.image[i][std::size_t(k)], kPeriod[k]);
        s.r[i] = ri;
    }
    for (std::size_t i = i0; i < i1; ++i) {
        const double ii = kInvInertia[s.species[i]];
        const V3 ti = s.tau[i];
        V3 wi = s.w[i];
        wi += (kHalf * ii) * ti;
        const V3 halpha = kHalf * (ii * ti);
        s.tau[i].setZero();
        wi += halpha;
        s.w[i] = wi;
        s.w_pred[i] = wi + halpha;
    }
    return moved2;
}

template <int W>
struct Lanes;
template <>
struct Lanes<2> {
    typedef double type __attribute__((vector_size(16), aligned(8)));
};
template <>
struct Lanes<4> {
    typedef double type __attribute__((vector_size(32), aligned(8)));
};

// Blocks of W grains (3 vectors of W lanes) over [i0, i1); returns where the blocks end.
template <int W>
inline __attribute__((always_inline)) std::size_t blocks(Grains& s, std::size_t i0, std::size_t i1,
                                                         double& moved2) {
    using vec = typename Lanes<W>::type;
    constexpr int K = 3;
    double* r = s.r.data()->data();
    double* v = s.v.data()->data();
    double* v_pred = s.v_pred.data()->data();
    double* f = s.f.data()->data();
    double* disp = s.disp.data()->data();
    vec g[K], period[K];
    for (int k = 0; k < K; ++k) {
        for (int l = 0; l < W; ++l) {
            g[k][l] = kGravity[(k * W + l) % 3];
            period[k][l] = kPeriod[(k * W + l) % 3];
        }
    }
    std::size_t i = i0;
    for (; i + W <= i1; i += W) {
        vec rr[K];
        double d2[K * W];
        bool crossed = false;
        for (int k = 0; k < K; ++k) {
            vec im;
            for (int l = 0; l < W; ++l)
                im[l] = kInvMass[s.species[i + std::size_t((k * W + l) / 3)]];
            const std::size_t o = 3 * i + std::size_t(k * W);
            const vec ha = kHalf * (im * *(vec*)(f + o) + g[k]);
            vec vi = *(vec*)(v + o);
            vi += ha;
            vi += ha;
            *(vec*)(f + o) = vec{};
            *(vec*)(v + o) = vi;
            *(vec*)(v_pred + o) = vi + ha;
            const vec dr = kDt * vi;
            rr[k] = *(vec*)(r + o) + dr;
            const vec di = *(vec*)(disp + o) + dr;
            *(vec*)(disp + o) = di;
            const vec sq = di * di;
            std::memcpy(d2 + k * W, &sq, sizeof sq);
            const auto out = (rr[k] < 0) | ((rr[k] >= period[k]) & (period[k] != 0));
            for (int l = 0; l < W; ++l) crossed |= out[l] != 0;
        }
        for (int b = 0; b < W; ++b)  // Eigen's order for a 3-vector: (x^2 + y^2) + z^2
            moved2 = std::max(moved2, (d2[3 * b] + d2[3 * b + 1]) + d2[3 * b + 2]);
        if (__builtin_expect(crossed, 0)) {
            for (int c = 0; c < 3 * W; ++c)
                wrap(rr[c / W][c % W], s.image[i + std::size_t(c / 3)][std::size_t(c % 3)],
                     kPeriod[c % 3]);
        }
        for (int k = 0; k < K; ++k) *(vec*)(r + 3 * i + std::size_t(k * W)) = rr[k];
    }
    double* w = s.w.data()->data();
    double* w_pred = s.w_pred.data()->data();
    double* tau = s.tau.data()->data();
    for (std::size_t j = i0; j < i; j += W) {
        for (int k = 0; k < K; ++k) {
            vec ii;
            for (int l = 0; l < W; ++l)
                ii[l] = kInvInertia[s.species[j + std::size_t((k * W + l) / 3)]];
            const std::size_t o = 3 * j + std::size_t(k * W);
            const vec ti = *(vec*)(tau + o);
            vec wi = *(vec*)(w + o);
            wi += (kHalf * ii) * ti;
            const vec halpha = kHalf * (ii * ti);
            *(vec*)(tau + o) = vec{};
            wi += halpha;
            *(vec*)(w + o) = wi;
            *(vec*)(w_pred + o) = wi + halpha;
        }
    }
    return i;
}

__attribute__((noinline)) double sse2(Grains& s, std::size_t i0, std::size_t i1) {
    double moved2 = 0;
    const std::size_t done = blocks<2>(s, i0, i1, moved2);
    return done < i1 ? std::max(moved2, reference(s, done, i1)) : moved2;
}

__attribute__((noinline, target("avx2"))) double avx2(Grains& s, std::size_t i0, std::size_t i1) {
    double moved2 = 0;
    const std::size_t done = blocks<4>(s, i0, i1, moved2);
    return done < i1 ? std::max(moved2, reference(s, done, i1)) : moved2;
}

}  // namespace

int main(int argc, char** argv) {
    const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10000;
    const int reps = argc > 2 ? std::atoi(argv[2]) : 3000;
    using Drift = double (*)(Grains&, std::size_t, std::size_t);
    const Drift drifts[3] = {reference, sse2, avx2};
    const char* names[3] = {"reference", "sse2", "avx2"};
    {  // an odd count, so the scalar tail runs too; new forces every step
        std::array<Grains, 3> s;
        s.fill(grains(n + 1));
        std::array<double, 3> moved2{};
        for (int t = 0; t < 50; ++t) {
            for (std::size_t k = 0; k < 3; ++k) {
                drift_bench::push(s[k], t);
                moved2[k] = std::max(moved2[k], drifts[k](s[k], 0, n + 1));
            }
        }
        const bool bits = same(s[0], s[1]) && same(s[0], s[2]) && moved2[0] == moved2[1] &&
                          moved2[0] == moved2[2];
        std::printf("same bits in all three: %s\n", bits ? "yes" : "NO");
        if (!bits) return 1;
    }
    std::printf("%10s %8s %12s\n", "drift", "N", "ns/grain");
    std::array<double, 3> best{1e9, 1e9, 1e9};
    for (int round = 0; round < 5; ++round) {
        for (std::size_t k = 0; k < 3; ++k) {
            Grains s = grains(n);
            double sink = 0;
            const auto t0 = std::chrono::steady_clock::now();
            for (int t = 0; t < reps; ++t) sink += drifts[k](s, 0, n);
            const double ns =
                std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0)
                    .count() /
                (double(n) * reps);
            if (sink < 0) std::printf("unreachable\n");  // keeps the loop
            best[k] = std::min(best[k], ns);
        }
    }
    for (std::size_t k = 0; k < 3; ++k) std::printf("%10s %8zu %12.2f\n", names[k], n, best[k]);
}
