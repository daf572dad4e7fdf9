// Wall waveforms (McNamara & Falcon 2005, Sec. II B: the parabolic piston; Barrat & Trizac 2002:
// the sawtooth wall) against independent forms. The contacts with moving walls:
// test_wall_contact.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <numbers>
#include <random>

#include "libgran/core/wall_motion.hpp"
#include "tests/support/wall_reference.hpp"

namespace gran {
namespace {

using namespace testing::wall;  // ld, kNever, kEps, kPi, PaperPiston

// ---------------------------------------------------------------------------------------------
// Waveforms

TEST(ParabolicPiston, IsThePapersPairOfParabolas) {
    const double A = 0.025, f = 20;  // the paper: A = 25 mm, 5 Hz <= f <= 50 Hz
    const double t0 = 1 / (4 * f);
    const WallMotion w = WallMotion::parabolic_piston(A, f);
    EXPECT_NEAR(w.position(0), -A / 2, 1e-17);  // lowest at the paper's time origin
    EXPECT_NEAR(w.position(t0), 0, 1e-17);
    EXPECT_NEAR(w.position(2 * t0), A / 2, 1e-17);  // highest
    EXPECT_NEAR(w.position(3 * t0), 0, 1e-17);
    EXPECT_NEAR(w.period(), 1 / f, 1e-16);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-t0, 3 * t0);
    for (int i = 0; i < 1000; ++i) {
        const double t = u(rng);
        const double z = t <= t0 ? A / (2 * t0 * t0) * (t * t - t0 * t0)
                                 : -A / (2 * t0 * t0) * ((t - 2 * t0) * (t - 2 * t0) - t0 * t0);
        ASSERT_NEAR(w.position(t), z, 1e-16) << t;
        for (int periods : {1, -3, 1000}) {
            // up to the rounding of t itself, times the speed (<= 4 A f)
            const double tp = t + periods / f;
            ASSERT_NEAR(w.position(tp), z, 1e-16 + 8 * kEps * std::abs(tp) * 4 * A * f)
                << t << " + " << periods << " T";
        }
    }
}

TEST(ParabolicPiston, PositionAndVelocityAreContinuousAtTheJoins) {
    const double A = 0.025, f = 37;
    const WallMotion w = WallMotion::parabolic_piston(A, f, 0.4);
    const double V = 4 * A * f, acc = 16 * A * f * f;  // V = 4 A f, |z''| = A / t0^2
    for (int j = -3; j < 6; ++j) {
        const double tj = w.piston_join(j);
        const double n = w.piston_index(tj - 1e-9), m = w.piston_index(tj + 1e-9);
        ASSERT_EQ(m, n + 1);
        // both parabolas evaluated exactly at the join
        const auto before = w.piston_parabola(n, tj), after = w.piston_parabola(m, tj);
        EXPECT_NEAR(before.z, 0, 1e-16);  // joins at the mean position
        EXPECT_NEAR(after.z, before.z, 1e-16);
        EXPECT_NEAR(after.dz, before.dz, 1e-14 * V);
        EXPECT_NEAR(std::abs(before.dz), V, 1e-14 * V);  // the fastest points
        EXPECT_NEAR(before.d2z, -after.d2z, 1e-12 * acc);
        EXPECT_NEAR(std::abs(before.d2z), acc, 1e-12 * acc);
    }
}

TEST(ParabolicPiston, PeakToPeakIsAAndTheMaximumVelocityIs4Af) {
    for (double f : {5.0, 20.0, 50.0}) {
        const double A = 0.025;
        const WallMotion w = WallMotion::parabolic_piston(A, f, 1.1);
        double zmin = kNever, zmax = -kNever, vmax = 0, vmin = 0;
        const int n = 200000;
        for (int i = 0; i <= n; ++i) {
            const double t = 3.0 + i / (n * f);
            zmin = std::min(zmin, w.position(t));
            zmax = std::max(zmax, w.position(t));
            vmax = std::max(vmax, w.velocity(t));
            vmin = std::min(vmin, w.velocity(t));
        }
        EXPECT_NEAR(zmax - zmin, A, 1e-9 * A);
        EXPECT_NEAR(zmax, A / 2, 1e-9 * A);
        // sampled at spacing T / n: within (A / t0^2) T / (2 n) = 2 V / n of V = 4 A f
        const double V = 4 * A * f;
        EXPECT_NEAR(vmax, V, 2 * V / n);
        EXPECT_NEAR(vmin, -V, 2 * V / n);
        EXPECT_LE(vmax, V * (1 + 4 * kEps));
        EXPECT_GE(vmin, -V * (1 + 4 * kEps));
        EXPECT_EQ(w.reach(), A / 2);
    }
}

TEST(ParabolicPiston, VelocityAndAccelerationAreDerivatives) {
    const WallMotion w = WallMotion::parabolic_piston(0.02, 13, 2.0);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    const double h = 1e-6;
    for (int i = 0; i < 1000; ++i) {
        const double t = u(rng);
        if (std::abs(t - w.piston_join(w.piston_index(t))) < 1e-4 ||
            std::abs(t - w.piston_join(w.piston_index(t) - 1)) < 1e-4) {
            continue;  // the acceleration jumps at the joins
        }
        ASSERT_NEAR(w.velocity(t), (w.position(t + h) - w.position(t - h)) / (2 * h), 1e-9);
        ASSERT_NEAR(w.acceleration(t), (w.velocity(t + h) - w.velocity(t - h)) / (2 * h), 1e-6);
    }
}

TEST(ParabolicPiston, PhaseShiftsTimeAndTheWaveformIsNearlySinusoidal) {
    const double A = 0.025, f = 20, omega = 2 * kPi * f;
    const WallMotion w0 = WallMotion::parabolic_piston(A, f);
    const WallMotion w = WallMotion::parabolic_piston(A, f, 0.7);
    const PaperPiston paper{A, f};
    double worst = 0;
    for (int i = 0; i < 10000; ++i) {
        const double t = i * 1e-5;
        ASSERT_NEAR(w.position(t), w0.position(t + 0.7 / omega), 1e-15);
        ASSERT_NEAR(w.position(t), static_cast<double>(paper.z(t + 0.7L / omega)), 1e-15);
        worst = std::max(worst, std::abs(w0.position(t) + A / 2 * std::cos(omega * t)));
    }
    // max |x^2 - 1 + cos(pi x / 2)| / 2 = 0.0280 for peak-to-peak 1
    EXPECT_LT(worst, 0.0281 * A);
    EXPECT_GT(worst, 0.0279 * A);
}

TEST(WallMotion, SinusoidFixedAndSawtooth) {
    const WallMotion s = WallMotion::sinusoid(0.01, 50, 0.3);
    for (double t : {0.0, 0.013, 7.1}) {
        EXPECT_DOUBLE_EQ(s.position(t), 0.01 * std::sin(50 * t + 0.3));
        EXPECT_DOUBLE_EQ(s.velocity(t), 0.5 * std::cos(50 * t + 0.3));
        EXPECT_DOUBLE_EQ(s.acceleration(t), -25 * std::sin(50 * t + 0.3));
        EXPECT_EQ(wall_velocity(s, -1, t), s.velocity(t));
    }
    EXPECT_EQ(s.reach(), 0.01);
    EXPECT_DOUBLE_EQ(s.period(), 2 * kPi / 50);
    const WallMotion fx = WallMotion::fixed();
    EXPECT_EQ(fx.position(3), 0);
    EXPECT_EQ(fx.velocity(3), 0);
    EXPECT_TRUE(fx.is_static());
    // Barrat & Trizac's virtual wall: fixed in place, always moving into the gas with speed v0
    const WallMotion saw = WallMotion::sawtooth(0.7);
    EXPECT_EQ(saw.position(3), 0);
    EXPECT_EQ(saw.velocity(3), 0.7);
    EXPECT_EQ(wall_velocity(saw, +1, 3), 0.7);   // lower wall
    EXPECT_EQ(wall_velocity(saw, -1, 3), -0.7);  // upper wall
    EXPECT_TRUE(saw.is_static());
}

// The real sawtooth (dem engine): rises from -A to A at v0 = 2 A f into the gas, jumps back once
// per period; the upper wall's mirrors it.
TEST(WallMotion, SawtoothRampRisesAtTwiceAmplitudeTimesFrequencyAndJumpsBackEachPeriod) {
    const double a = 0.2, f = 2.5, T = 1 / f;
    const WallMotion lo = WallMotion::sawtooth_ramp(a, f, 0, +1);
    const WallMotion up = WallMotion::sawtooth_ramp(a, f, 0, -1);
    EXPECT_FALSE(lo.is_static());
    EXPECT_DOUBLE_EQ(lo.reach(), a);
    EXPECT_DOUBLE_EQ(lo.period(), T);
    for (double t : {0.0, 0.1 * T, 0.5 * T, 0.9 * T, 3.25 * T}) {
        const double x = t / T - std::floor(t / T);
        EXPECT_NEAR(lo.position(t), a * (2 * x - 1), 1e-12) << t;
        EXPECT_NEAR(up.position(t), -lo.position(t), 1e-12) << t;
        EXPECT_DOUBLE_EQ(lo.velocity(t), 2 * a * f);
        EXPECT_DOUBLE_EQ(up.velocity(t), -2 * a * f);
    }
    // the position is the integral of the velocity within a period
    EXPECT_NEAR(lo.position(0.7 * T) - lo.position(0.2 * T), 0.5 * T * 2 * a * f, 1e-12);
}

}  // namespace
}  // namespace gran
