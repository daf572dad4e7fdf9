// The DEM step's opening pass (libgran/engines/dem/drift.hpp): the spheres' two-grain SSE2 form
// gives the same bits as the per-grain form, for a mixture of two species, with and without
// spins, with and without the previous step's closing kick, over grains that cross the periodic
// sides both ways (images counted), an odd count (the last grain by the per-grain form) and
// ranges that start at an odd grain (the threads' shares); and the per-grain form is the
// velocity Verlet update it claims to be.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "libgran/engines/dem/drift.hpp"

namespace gran {
namespace {

struct Grains {
    std::vector<Vec<3>> r, v, v_pred, f, disp, w, w_pred, tau;
    std::vector<std::array<std::int32_t, 3>> image;
    std::vector<std::uint32_t> species;
};

constexpr double kInvMass[2] = {1.3, 0.7}, kInvInertia[2] = {3.1, 2.2};
// Periodic x and y (length 5), bounded z: the vibrated bed's box.
const DriftStep<3> kStep{1e-3, Vec<3>(0, 0, -9.81), {5, 5, 0}};

Grains random_grains(std::size_t n, std::uint64_t seed) {
    Grains s;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto any = [&] { return Vec<3>(u(rng), u(rng), u(rng)); };
    for (std::size_t i = 0; i < n; ++i) {
        // Some grains start within one drift of a periodic side, on either side of it.
        const double edge = i % 5 == 0 ? 1e-4 * u(rng) : 2.5 + 2.4 * u(rng);
        s.r.push_back(Vec<3>(edge < 0 ? edge + 5 : edge, 2.5 + 2.4 * u(rng), 1 + u(rng)));
        s.v.push_back(30 * any());  // 3 cm per step: several grains cross a side every step
        s.v_pred.push_back(any());
        s.f.push_back(100 * any());
        s.disp.push_back(0.01 * any());
        s.w.push_back(any());
        s.w_pred.push_back(any());
        s.tau.push_back(any());
        s.image.push_back({0, 0, 0});
        s.species.push_back(std::uint32_t(rng() % 2));
    }
    return s;
}

DriftArrays<3> arrays(Grains& s) {
    return {s.r.data(),    s.v.data(),      s.v_pred.data(),  s.f.data(),
            s.disp.data(), s.image.data(),  s.species.data(), kInvMass,
            s.w.data(),    s.w_pred.data(), s.tau.data(),     kInvInertia};
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_bits(const Grains& a, const Grains& b) {
    EXPECT_TRUE(same_bytes(a.r, b.r));
    EXPECT_TRUE(same_bytes(a.v, b.v));
    EXPECT_TRUE(same_bytes(a.v_pred, b.v_pred));
    EXPECT_TRUE(same_bytes(a.f, b.f));
    EXPECT_TRUE(same_bytes(a.disp, b.disp));
    EXPECT_TRUE(same_bytes(a.w, b.w));
    EXPECT_TRUE(same_bytes(a.w_pred, b.w_pred));
    EXPECT_TRUE(same_bytes(a.tau, b.tau));
    EXPECT_TRUE(same_bytes(a.image, b.image));
}

// Steps both forms over [i0, n) with new forces and torques each step; returns how many
// periodic crossings the images counted, so a test can check that it met some.
template <bool Closing, bool Spins>
int compare_forms(std::size_t n, std::size_t i0, std::uint64_t seed) {
    Grains a = random_grains(n, seed), b = a;
    std::mt19937_64 rng(seed + 1);
    std::uniform_real_distribution<double> u(-100, 100);
    for (int step = 0; step < 40; ++step) {
        for (std::size_t i = 0; i < n; ++i) {
            a.f[i] = b.f[i] = Vec<3>(u(rng), u(rng), u(rng));
            a.tau[i] = b.tau[i] = Vec<3>(u(rng), u(rng), u(rng));
        }
        const double max_a = kick_drift_per_grain<3, Closing>(arrays(a), kStep, Spins, i0, n);
        const double max_b = kick_drift_pairs_3d<Closing, Spins>(arrays(b), kStep, i0, n);
        EXPECT_EQ(max_a, max_b) << "step " << step;
    }
    expect_same_bits(a, b);
    int crossings = 0;
    for (const auto& im : a.image) crossings += std::abs(im[0]) + std::abs(im[1]) + std::abs(im[2]);
    EXPECT_EQ(a.image.back()[2], 0);  // z is bounded: never wrapped
    return crossings;
}

TEST(DemDrift, SphereBlocksGiveThePerGrainBitsWithSpinsAndClosingKick) {
    EXPECT_GT((compare_forms<true, true>(101, 0, 1)), 20);
}

TEST(DemDrift, SphereBlocksGiveThePerGrainBitsWithoutSpinsOrClosingKick) {
    EXPECT_GT((compare_forms<false, false>(100, 0, 2)), 20);
    EXPECT_GT((compare_forms<true, false>(64, 0, 3)), 10);
    EXPECT_GT((compare_forms<false, true>(64, 0, 4)), 10);
}

TEST(DemDrift, SphereBlocksGiveThePerGrainBitsOnARangeThatStartsAtAnOddGrain) {
    EXPECT_GT((compare_forms<true, true>(100, 37, 5)), 10);
    compare_forms<true, false>(2, 1, 6);  // one grain: the per-grain tail alone
}

TEST(DemDrift, PerGrainFormIsTheVelocityVerletOpeningPass) {
    Grains s = random_grains(1, 7);
    s.r[0] = Vec<3>(1, 2, 3);
    s.v[0] = Vec<3>(0.5, -0.25, 1);
    s.f[0] = Vec<3>(2, 0, -1);
    s.disp[0] = Vec<3>(0.01, 0, 0);
    s.species[0] = 1;  // inverse mass 0.7
    const double h = 0.5e-3;
    const Vec<3> a = 0.7 * Vec<3>(2, 0, -1) + kStep.g;
    const Vec<3> v = Vec<3>(0.5, -0.25, 1) + 2 * h * a;  // closing and opening half kicks
    const double moved2 = kick_drift_per_grain<3, true>(arrays(s), kStep, false, 0, 1);
    const Vec<3> dr = 1e-3 * v;
    EXPECT_NEAR((s.v[0] - v).norm(), 0, 1e-15);
    EXPECT_NEAR((s.v_pred[0] - (v + h * a)).norm(), 0, 1e-15);
    EXPECT_NEAR((s.r[0] - (Vec<3>(1, 2, 3) + dr)).norm(), 0, 1e-15);
    EXPECT_NEAR(moved2, (Vec<3>(0.01, 0, 0) + dr).squaredNorm(), 1e-18);
    EXPECT_EQ(s.f[0], Vec<3>::Zero());
}

}  // namespace
}  // namespace gran
