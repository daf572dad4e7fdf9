// A DEM wall that slides in its own plane (DemEngine::set_wall_slide; the floor of a box vibrated
// as a whole, drivers/vibrating_box.cpp): friction drags a grain resting on it, a smooth floor
// does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "libgran/engines/dem/engine.hpp"
#include "tests/support/contacts.hpp"

namespace gran {
namespace {

constexpr double kPi = std::numbers::pi;

// Periodic along every axis but the last, which has static walls at 0 and `height`.
template <int D>
Box<D> bed_box(double length, double height) {
    Box<D> box;
    box.length = Vec<D>::Constant(length);
    box.periodic.fill(true);
    box.length[D - 1] = height;
    box.periodic[D - 1] = false;
    return box;
}

SpeciesTable one_grain(double q) {
    Species s;
    s.name = "a";
    s.mass = 1;
    s.diameter = 1;
    s.inertia_factor = q;
    s.count = 1;
    SpeciesTable t;
    t.species = {s};
    return t;
}

// A grain (I = q m R^2) resting on a floor that slides along x with u(t) = A omega sin(omega t),
// from rest. While friction holds the contact point to the floor (rolling without slipping), the
// torque and force of the one contact force F give m dv/dt = F and I dw/dt = -R F, and the
// contact point v - w R follows u: the centre moves at v(t) = q / (1 + q) u(t) (2/7 for spheres,
// 1/3 for disks). The largest force needed, m q / (1 + q) A omega^2 = 0.14-0.17, is below
// mu m g = 0.4: it never slips. Tolerance 1% of A omega: the tangential dashpot needs a slip
// velocity F / gamma_t = 3e-3 to pass the force on. A frictionless floor leaves the grain at rest.
template <int D>
void check_dragged_grain(const std::string& law, double q, double friction) {
    const double g = 1, k = 2e5, A = 0.5, omega = 1;
    const SpeciesTable t = one_grain(q);
    const ContactTable contacts =
        testing::contacts_of(t, "{law: " + law + ", stiffness: 2e5, restitution: 0.9, friction: " +
                                    std::to_string(friction) + ", tangential_damping: 50}");
    Particles<D> p;
    p.resize(1, false);
    p.r[0] = Vec<D>::Constant(2.5);
    p.r[0][D - 1] = 0.5 - g / k;  // resting overlap m g / k
    DemSettings settings;
    settings.gravity[std::size_t(D - 1)] = -g;
    DemEngine<D> e(bed_box<D>(5, 10), t, contacts, p, settings);
    // Velocity A omega cos(omega t - pi / 2) = A omega sin(omega t): at rest at t = 0.
    e.set_wall_slide(D - 1, 0, 0, WallMotion::sinusoid(A, omega, -kPi / 2));
    const double share = friction > 0 ? q / (1 + q) : 0.0;
    double worst = 0;
    for (int k_sample = 1; k_sample <= 40; ++k_sample) {
        const double time = k_sample * (4 * kPi / omega) / 40;  // two periods
        e.advance(time);
        const double expected = share * A * omega * std::sin(omega * e.now());
        worst = std::max(worst, std::abs(e.particles().v[0][0] - expected));
    }
    EXPECT_LT(worst, 0.01 * A * omega) << law << " D " << D << " friction " << friction;
    // The floor does not move along its normal: the grain stays on it.
    EXPECT_NEAR(e.particles().r[0][D - 1], 0.5, 1e-3);
}

TEST(DemSlidingWall, FrictionDragsARestingGrainIntoRollingAtQOverOnePlusQOfTheFloorVelocity) {
    for (const char* law : {"linear_dashpot", "cundall_strack"}) {
        check_dragged_grain<2>(law, 0.5, 0.4);
        check_dragged_grain<3>(law, 0.4, 0.4);
    }
}

TEST(DemSlidingWall, SmoothFloorSlidesUnderARestingGrainWithoutMovingIt) {
    check_dragged_grain<2>("linear_dashpot", 0.5, 0.0);
    check_dragged_grain<3>("linear_dashpot", 0.4, 0.0);
}

TEST(DemSlidingWall, RefusesASlideAlongTheWallNormalOrOnAMissingWall) {
    const SpeciesTable t = one_grain(0.4);
    const ContactTable contacts =
        testing::contacts_of(t, "{law: linear_dashpot, stiffness: 2e5, restitution: 0.9}");
    Particles<3> p;
    p.resize(1, false);
    p.r[0] = Vec<3>(2.5, 2.5, 2.5);
    DemEngine<3> e(bed_box<3>(5, 10), t, contacts, p, DemSettings{});
    EXPECT_THROW(e.set_wall_slide(2, 0, 2, WallMotion::sinusoid(0.5, 1)), std::invalid_argument);
    EXPECT_THROW(e.set_wall_slide(0, 0, 2, WallMotion::sinusoid(0.5, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace gran
