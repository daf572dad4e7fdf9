// Soft-sphere DEM engine (libgran/engines/dem/engine.hpp), one or two grains: single collisions
// against the closed forms of the linear spring-dashpot (Bhateja, Sharma & Singh 2016, Eqs.
// A5-A9) and of Cundall-Strack and Hertz-Mindlin, walls (static, moving), friction and rotation
// (sliding to rolling). Many grains: test_dem_many_grains.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "species/contact_laws.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/dem_grains.hpp"

namespace gran {
namespace {

using namespace testing::dem;  // make_species, table_of, soft, duration, make_box, momentum, sci

template <int D>
Vec<D> axis_vector(int axis, double value = 1) {
    Vec<D> e = Vec<D>::Zero();
    e[axis] = value;
    return e;
}

// Linear interpolation of the time at which the overlap crosses zero between two steps.
double crossing(double t, double dt, double delta_before, double delta_after) {
    return t - dt * delta_after / (delta_after - delta_before);
}

struct Collision {
    double restitution = 0;
    double duration = 0;
    double expected_duration = 0;
};

// ----- head-on particle-particle collision -------------------------------------------------------

// Species 0 (m = 1, sigma = 1) hits species 1 (m = 3, sigma = 1.5) head on along the last axis in
// a periodic box, in the centre-of-mass frame at relative speed v; the contact starts a fraction
// `phase` of a step after t = 0. Contact duration from the interpolated zero crossings of delta.
template <int D>
Collision head_on_pair(const std::string& law, const std::string& keys, double v, double phase) {
    const SpeciesTable t =
        table_of({make_species("a", 1, 1, 0.4, 1), make_species("b", 3, 1.5, 0.4, 1)});
    const ContactTable contacts = soft(t, law, keys);
    const double t_c = duration(contacts, contacts.pair_index(0, 1)), sigma = 1.25;
    const double dt = t_c / 50;
    Particles<D> p;
    p.resize(2, false);
    p.species = {0, 1};
    const double gap = v * phase * dt;
    const Vec<D> centre = Vec<D>::Constant(5.0);
    const Vec<D> n = axis_vector<D>(D - 1);
    p.r[0] = centre + (0.5 * gap + 0.5) * n;
    p.r[1] = centre - (0.5 * gap + 0.75) * n;
    p.v[0] = -(v * 3.0 / 4.0) * n;
    p.v[1] = (v * 1.0 / 4.0) * n;
    DemSettings settings;
    settings.dt = dt;
    DemEngine<D> e(make_box<D>(10, true), t, contacts, p, settings);
    const auto overlap = [&] {
        const auto& ps = e.particles();
        return sigma - e.box().separation(ps.r[0], ps.r[1]).norm();
    };
    Collision out;
    double before = overlap(), t_in = 0, t_out = 0;
    bool touched = false;
    for (int s = 0; s < 100000; ++s) {
        e.step();
        const double delta = overlap();
        if (delta > 0 && before <= 0) {
            t_in = crossing(e.now(), dt, before, delta);
            touched = true;
        }
        if (delta <= 0 && before > 0) {
            t_out = crossing(e.now(), dt, before, delta);
            break;
        }
        before = delta;
    }
    EXPECT_TRUE(touched);
    EXPECT_EQ(e.counters().contacts, 1u);
    const auto& ps = e.particles();
    out.restitution = -(ps.v[0] - ps.v[1]).dot(n) / -v;
    out.duration = t_out - t_in;
    out.expected_duration = t_c;
    return out;
}

// The linear law gives e for every impact speed and t_c = pi / sqrt(k/m - (gamma/2m)^2) (closed
// forms of the damped oscillator). Tolerances: e within 0.5 % (the damping force jumps at both
// ends of a contact, which shifts one collision's e by up to 2 |ln e| dt / t_c = 0.42 % at
// e = 0.9, dt = t_c / 50, depending on where the contact starts within a step: several phases are
// tried); duration within 1 % (interpolated crossings, error O(dt^2 / t_c)).
template <int D>
void check_pair_collisions() {
    for (double phase : {0.0, 0.25, 0.5, 0.75}) {
        for (double v : {0.3, 3.0}) {
            const Collision c =
                head_on_pair<D>("linear_dashpot", "contact_time: 2e-3, restitution: 0.9", v, phase);
            EXPECT_NEAR(c.restitution, 0.9, 0.005 * 0.9) << "phase " << phase << " v " << v;
            EXPECT_NEAR(c.duration, 2e-3, 0.01 * 2e-3) << "phase " << phase << " v " << v;
            EXPECT_NEAR(c.expected_duration, 2e-3, 1e-12);
        }
    }
}

TEST(DemEngine, HeadOnPairCollisionHasTheRequestedRestitutionAndDuration2D) {
    check_pair_collisions<2>();
}

TEST(DemEngine, HeadOnPairCollisionHasTheRequestedRestitutionAndDuration3D) {
    check_pair_collisions<3>();
}

// The normal force of cundall_strack is the linear one; Hertz with Tsuji damping has a
// speed-independent e and t_c at the reference speed (tau_c(alpha) (m/k)^{2/5} v^{-1/5}).
// Same tolerances as above.
TEST(DemEngine, CundallStrackAndHertzMindlinHeadOnCollisionsMatchTheirClosedForms) {
    const std::string linear = "contact_time: 2e-3, restitution: 0.9";
    const std::string hertz = linear + ", reference_speed: 1.5";
    for (const auto& [law, keys] :
         {std::pair{"cundall_strack", linear}, {"hertz_mindlin", hertz}}) {
        const Collision c = head_on_pair<3>(law, keys, 1.5, 0.3);
        EXPECT_NEAR(c.restitution, 0.9, 0.005 * 0.9) << law;
        EXPECT_NEAR(c.duration, 2e-3, 0.01 * 2e-3) << law;
    }
    // Hertz: e does not depend on the impact speed, t_c scales as v^{-1/5}.
    const Collision slow = head_on_pair<3>("hertz_mindlin", hertz, 1.5 / 32, 0.3);
    EXPECT_NEAR(slow.restitution, 0.9, 0.005 * 0.9);
    EXPECT_NEAR(slow.duration, 2e-3 * 2.0, 0.01 * 4e-3);  // 32^{1/5} = 2
}

// ----- particle-wall collisions ------------------------------------------------------------------

// A particle (m = 2, sigma = 1) falls without gravity onto the static lower wall of the last axis
// with speed v; e_w = 0.92 is set separately from the pairs (e = 0.5). dt = t_c,wall / 50.
template <int D>
void check_wall_collision(double phase) {
    const SpeciesTable t = table_of({make_species("a", 2, 1, 0.4, 1)});
    const ContactTable contacts =
        soft(t, "linear_dashpot", "stiffness: 1e5, restitution: 0.5", "restitution: 0.92");
    const double t_c = duration(contacts, contacts.wall_index(0, 0));
    // Infinite wall mass: the contact's reduced mass is the grain's, m = 2.
    EXPECT_DOUBLE_EQ(
        t_c, linear_contact_duration(1e5, 2.0, linear_damping_from_restitution(1e5, 2.0, 0.92)));
    const double dt = t_c / 50, v = 1.3;
    Particles<D> p;
    p.resize(1, false);
    p.r[0] = Vec<D>::Constant(2.5);
    p.r[0][D - 1] = 0.5 + v * phase * dt;
    p.v[0] = axis_vector<D>(D - 1, -v);
    DemSettings settings;
    settings.dt = dt;
    DemEngine<D> e(make_box<D>(5, true, 10), t, contacts, p, settings);
    const auto overlap = [&] { return 0.5 - e.particles().r[0][D - 1]; };
    double before = overlap(), t_in = 0, t_out = 0;
    for (int s = 0; s < 100000; ++s) {
        e.step();
        const double delta = overlap();
        if (delta > 0 && before <= 0) t_in = crossing(e.now(), dt, before, delta);
        if (delta <= 0 && before > 0) {
            t_out = crossing(e.now(), dt, before, delta);
            break;
        }
        before = delta;
    }
    const double v_after = e.particles().v[0][D - 1];
    // Tolerances as for pairs: 2 |ln 0.92| / 50 = 0.33 % < 0.5 %; duration 1 %.
    EXPECT_NEAR(v_after / v, 0.92, 0.005 * 0.92) << "phase " << phase;
    EXPECT_NEAR(t_out - t_in, t_c, 0.01 * t_c) << "phase " << phase;
    EXPECT_EQ(e.wall_hits()[2 * (D - 1)], 1u);
    EXPECT_EQ(e.wall_hits()[2 * (D - 1) + 1], 0u);
    // The wall's impulse, sum of F_n dt, is the momentum change m (v' + v) (to O(dt) of a step's
    // force: 0.5 %).
    EXPECT_NEAR(e.wall_impulse()[2 * (D - 1)], 2 * (v_after + v), 0.005 * 2 * (v_after + v));
}

TEST(DemEngine, WallCollisionHasTheWallRestitutionAndDuration2D) {
    for (double phase : {0.0, 0.4, 0.8}) check_wall_collision<2>(phase);
}

TEST(DemEngine, WallCollisionHasTheWallRestitutionAndDuration3D) {
    for (double phase : {0.0, 0.4, 0.8}) check_wall_collision<3>(phase);
}

// A sinusoidal floor A sin(omega t) (surface at A + A sin(omega t)) meets a particle at rest: the
// particle leaves with (1 + e_w) u, u the floor velocity at the contact. Tolerance 1 %: the floor
// accelerates during the contact, which changes u by about omega t_c tan(theta) = 1e-3 relative.
TEST(DemEngine, SinusoidalFloorLaunchesAParticleAtRestWithOnePlusETimesItsVelocity) {
    const SpeciesTable t = table_of({make_species("a", 1, 1, 0.4, 1)});
    const ContactTable contacts = soft(t, "linear_dashpot", "contact_time: 1e-3, restitution: 0.9");
    const double A = 1, omega = 1, theta = kPi / 6;  // contact when omega t = theta
    Particles<3> p;
    p.resize(1, false);
    p.r[0] = Vec<3>(2.5, 2.5, 0.5 + A + A * std::sin(theta));
    DemEngine<3> e(make_box<3>(5, true, 20), t, contacts, p, DemSettings{});
    e.set_wall(2, 0, WallMotion::sinusoid(A, omega), 0);
    EXPECT_DOUBLE_EQ(e.wall_position(4, 0.0), A);
    e.advance(theta / omega + 0.01);  // 10 contact durations after the contact
    const double u = A * omega * std::cos(theta);
    EXPECT_NEAR(e.particles().v[0][2], 1.9 * u, 0.01 * 1.9 * u);
    EXPECT_EQ(e.wall_hits()[4], 1u);
    EXPECT_NEAR(e.wall_impulse()[4], e.particles().v[0][2], 0.005 * 1.9 * u);
}

// ----- friction and rotation ---------------------------------------------------------------------

// A grain resting on a rough floor under gravity, launched sliding at v0 without spin: friction
// acts at the contact point, so the angular momentum about it, m v R + I w, is conserved, and the
// grain ends rolling at v0 / (1 + q) (I = q m R^2; 5/7 for spheres, 2/3 for disks) whatever the
// tangential law. Tolerance 1e-3: the contact point is at R - delta (delta / R = 1e-4 here) while
// the paper's lever arm is R (Eq. A3), and the dashpot's g_t decays exponentially (time m_t /
// gamma_t = 6e-3, run 300 times longer).
template <int D>
void check_rolling(const std::string& law, double q) {
    const double g = 1, v0 = 1, k = 2e5;
    const SpeciesTable t = table_of({make_species("a", 1, 1, q, 1)});
    const ContactTable contacts =
        soft(t, law, "stiffness: 2e5, restitution: 0.9, friction: 0.4, tangential_damping: 50");
    Particles<D> p;
    p.resize(1, false);
    p.r[0] = Vec<D>::Constant(2.5);
    p.r[0][D - 1] = 0.5 - g / k;  // resting overlap m g / k
    p.v[0] = axis_vector<D>(0, v0);
    DemSettings settings;
    settings.gravity[std::size_t(D - 1)] = -g;
    DemEngine<D> e(make_box<D>(5, true, 10), t, contacts, p, settings);
    ASSERT_TRUE(e.particles().rotating());
    e.advance(2.0);  // sliding ends at v0 q / (mu g (1 + q)) < 0.4
    const auto& ps = e.particles();
    EXPECT_NEAR(ps.v[0][0] / v0, 1 / (1 + q), 1e-3) << law << " D " << D;
    // Rolling without slip: the contact point is at rest (to 1e-3 v0).
    const Vec<D> slip = contact_velocity<D>(ps.v[0], Vec<D>::Zero(), ps.w[0], ang_zero<D>(), 0.5,
                                            0.0, axis_vector<D>(D - 1));
    EXPECT_NEAR(slip[0], 0.0, 1e-3 * v0);
}

TEST(DemEngine, SlidingGrainEndsRollingAtOneOverOnePlusQ) {
    for (const char* law : {"linear_dashpot", "cundall_strack"}) {
        check_rolling<2>(law, 0.5);
        check_rolling<3>(law, 0.4);
    }
}

}  // namespace
}  // namespace gran
