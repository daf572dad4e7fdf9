// Event-driven engine under gravity and with moving walls: energy conservation of a bouncing
// particle, every piston hit found (against a brute-force time-stepping reference), resting
// particles never stall the run, impact-speed dependent restitution used per collision, and many
// particles under gravity conserve energy with elastic walls.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "libgran/core/wall_motion.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/contacts.hpp"

namespace gran {
namespace {

SpeciesTable one_species(std::size_t count) {
    SpeciesTable t;
    Species s;
    s.name = "a";
    s.count = count;
    t.species.push_back(s);
    return t;
}

// Constant restitution `alpha` between grains, `floor` against the wall partner `floor` (index 1;
// the box's own walls, partner 0, are elastic).
constexpr std::size_t kFloor = 1;
ContactTable contacts(const SpeciesTable& t, double alpha = 1.0, double floor = 1.0) {
    return testing::contacts_of(
        t,
        fmt::format(
            "{{alpha: {}, walls: {{alpha: 1}}, pairs: [{{between: [a, floor], alpha: {}}}]}}",
            alpha, floor),
        2, {"box", "floor"});
}

Box<2> column(double width, double height) {
    Box<2> box;
    box.length = Vec<2>(width, height);
    box.periodic = {true, false};
    return box;
}

Particles<2> single(double x, double y, double vx, double vy) {
    Particles<2> p;
    p.resize(1, false);
    p.r[0] = Vec<2>(x, y);
    p.v[0] = Vec<2>(vx, vy);
    p.t[0] = 0;
    p.species[0] = 0;
    return p;
}

EngineSettings with_gravity(double g) {
    EngineSettings s;
    s.gravity = {0.0, -g, 0.0};
    return s;
}

TEST(Gravity, ElasticBounceOnAStaticFloorKeepsItsEnergyOverHundredThousandBounces) {
    const double g = 9.81;
    const auto t = one_species(1);
    EventDrivenEngine<2> e(column(10, 50), t, contacts(t), single(5.0, 3.7, 0.3, 0.0),
                           with_gravity(g));
    e.set_wall(1, 0, WallMotion::fixed(), kFloor);
    auto energy = [&] {
        const auto& p = e.particles();
        return 0.5 * p.v[0].squaredNorm() + g * p.r[0][1];
    };
    const double e0 = energy();
    // Bounce period 2 sqrt(2 h / g) for a drop from h = 3.2 above the contact height 0.5.
    const double period = 2 * std::sqrt(2 * (3.7 - 0.5) / g);
    e.advance(1e5 * period + 0.25 * period, ~0ull);
    e.synchronize();
    EXPECT_EQ(e.wall_hits()[2], 100000u);
    EXPECT_NEAR(energy() / e0 - 1.0, 0.0, 1e-10);
    EXPECT_EQ(e.counters().wall_lifts, 0u);
}

TEST(Gravity, InelasticParticleComesToRestOnTheFloorWithoutStallingTheRun) {
    const double g = 9.81;
    const auto t = one_species(1);
    EventDrivenEngine<2> e(column(10, 50), t, contacts(t, 1.0, 0.5), single(5.0, 3.0, 0.0, 0.0),
                           with_gravity(g));
    e.set_wall(1, 0, WallMotion::fixed(), kFloor);
    // The bounces form a geometric series (inelastic collapse at the wall, finite time); the
    // rebound is then held at g tc, micro-bounces of height g tc^2 / 2: time keeps advancing.
    const auto stop = e.advance(10.0, ~0ull);
    EXPECT_EQ(stop, EventDrivenEngine<2>::Stop::TimeLimit);
    e.synchronize();
    EXPECT_NEAR(e.particles().r[0][1], 0.5, 1e-9);
    EXPECT_GT(e.counters().wall_lifts, 0u);
}

// Brute-force reference for one particle above a moving floor: from each bounce the exact parabola
// is sampled every dt; the first sample below the wall is bisected back to the contact.
struct Reference {
    WallMotion wall;
    double base, g;
    std::vector<double> hits(double y0, double vy0, double t_end, double dt) const {
        std::vector<double> out;
        double tb = 0, yb = y0, vb = vy0;  // state at the last bounce
        auto gap = [&](double s) {
            return (yb + vb * s - 0.5 * g * s * s) - 0.5 - (base + wall.position(tb + s));
        };
        double s = dt;
        while (tb + s < t_end) {
            if (gap(s) > 0) {
                s += dt;
                continue;
            }
            double lo = s - dt, hi = s;
            for (int k = 0; k < 200 && hi - lo > 1e-15 * (1 + tb + s); ++k) {
                const double mid = 0.5 * (lo + hi);
                (gap(mid) > 0 ? lo : hi) = mid;
            }
            yb += vb * hi - 0.5 * g * hi * hi;
            vb -= g * hi;
            tb += hi;
            const double u = wall.velocity(tb);
            if (vb < u) vb = 2 * u - vb;
            out.push_back(tb);
            s = dt;
        }
        return out;
    }
};

std::size_t total_hits = 0;

void expect_every_hit_found(const WallMotion& motion, double g, double y0, double vy0) {
    const double L = 1e5;  // the lid is never reached
    const auto t = one_species(1);
    EventDrivenEngine<2> e(column(10, L), t, contacts(t), single(5.0, y0, 0.0, vy0),
                           with_gravity(g));
    e.set_wall(1, 0, motion, kFloor);
    const Reference ref{motion, motion.reach(), g};
    const double period = 2 * std::numbers::pi / motion.omega;
    const auto hits = ref.hits(y0, vy0, 20 * period, period * 1e-5);
    total_hits += hits.size();
    // The engine has exactly k hits just before the k-th reference hit and k + 1 just after; the
    // window is far wider than the reference's error and far narrower than the time between hits.
    const double tol = 1e-6 * period;
    for (std::size_t k = 0; k < std::min<std::size_t>(hits.size(), 12); ++k) {
        if (k > 0 && hits[k] - hits[k - 1] < 4 * tol) break;  // chattering: stop comparing
        e.advance(hits[k] - tol, ~0ull);
        ASSERT_EQ(e.wall_hits()[2], k) << "hit " << k << " at t = " << hits[k] << " came early";
        e.advance(hits[k] + tol, ~0ull);
        ASSERT_EQ(e.wall_hits()[2], k + 1) << "hit " << k << " at t = " << hits[k] << " missed";
    }
}

TEST(MovingWall, EveryParabolicPistonHitIsFoundAsByBruteForceTimeStepping) {
    Rng rng = make_rng(42, Stream::Driver);
    total_hits = 0;
    for (int c = 0; c < 16; ++c) {
        const double a = 0.5 + 2 * uniform01(rng), f = 0.2 + uniform01(rng);
        expect_every_hit_found(WallMotion::parabolic_piston(a, f, 6.28 * uniform01(rng)),
                               0.5 + 2 * uniform01(rng), 2 + 10 * uniform01(rng),
                               -3 * uniform01(rng));
    }
    EXPECT_GE(total_hits, 50u);
}

TEST(MovingWall, EverySinusoidalWallHitIsFoundAsByBruteForceTimeStepping) {
    Rng rng = make_rng(43, Stream::Driver);
    total_hits = 0;
    for (int c = 0; c < 16; ++c) {
        const double a = 0.3 + uniform01(rng), f = 0.2 + uniform01(rng);
        expect_every_hit_found(
            WallMotion::sinusoid(a, 2 * std::numbers::pi * f, 6.28 * uniform01(rng)),
            0.5 + 2 * uniform01(rng), 3 + 10 * uniform01(rng), -3 * uniform01(rng));
    }
    EXPECT_GE(total_hits, 50u);
}

TEST(Gravity, ElasticDisksUnderGravityBetweenElasticWallsConserveEnergy) {
    const double g = 2.0;
    const SpeciesTable t = one_species(400);
    Box<2> box = column(40, 60);
    Rng rng = make_rng(7, Stream::Placement);
    Particles<2> p = place_random<2>(box, t, rng);
    Rng vr = make_rng(7, Stream::Velocities);
    for (auto& v : p.v) v = Vec<2>(gaussian(vr), gaussian(vr));
    EventDrivenEngine<2> e(box, t, contacts(t), std::move(p), with_gravity(g));
    auto energy = [&] {
        e.synchronize();
        double s = 0;
        for (std::size_t i = 0; i < e.particles().size(); ++i)
            s += 0.5 * e.particles().v[i].squaredNorm() + g * e.particles().r[i][1];
        return s;
    };
    const double e0 = energy();
    e.advance(1e9, 200000);
    EXPECT_EQ(e.counters().collisions, 200000u);
    EXPECT_GT(e.counters().wall_hits, 1000u);
    EXPECT_NEAR(energy() / e0 - 1.0, 0.0, 1e-10);
}

TEST(ImpactRestitution, EngineAppliesMcNamaraFalconLawAtTheImpactSpeed) {
    // Head-on pair at relative speed 4 v0: r = r0 (4)^(-1/4) (McNamara & Falcon 2005, Eq. 1).
    const SpeciesTable t = one_species(2);
    const ContactTable c = testing::contacts_of(t, "{law: mcnamara_falcon, r0: 0.9, v0: 0.5}", 2);
    Box<2> box;
    box.length = Vec<2>(100, 100);
    box.periodic = {true, true};
    Particles<2> p;
    p.resize(2, false);
    p.r[0] = Vec<2>(10, 50);
    p.r[1] = Vec<2>(20, 50);
    p.v[0] = Vec<2>(1.0, 0);
    p.v[1] = Vec<2>(-1.0, 0);
    p.t = {0, 0};
    p.species = {0, 0};
    EventDrivenEngine<2> e(box, t, c, std::move(p), EngineSettings{});
    e.advance(1e9, 1);
    const double r = 0.9 * std::pow(4.0, -0.25);
    EXPECT_NEAR(std::abs(e.particles().v[0][0] - e.particles().v[1][0]), 2.0 * r, 1e-14);
}

}  // namespace
}  // namespace gran

namespace gran {
namespace {

TEST(MovingWall, ManyParticlesStayAboveThePistonAcrossTimeOriginShifts) {
    // 300 disks above a two-parabola piston under gravity, advanced in many short steps: the
    // engine moves its time origin every 16 N events; the stop time, the piston phase and every
    // particle position must stay consistent (a stale limit once ran far past the stop time).
    const SpeciesTable t = one_species(300);
    Box<2> box = column(100, 24);
    Rng rng = make_rng(3, Stream::Placement);
    Box<2> lower = box;
    lower.length[1] = 12;  // start in the lower half, above the piston's sweep
    Particles<2> p = place_random<2>(lower, t, rng);
    for (auto& r : p.r) r[1] += 8;
    EventDrivenEngine<2> e(box, t, contacts(t, 0.9), std::move(p), with_gravity(1.0));
    const WallMotion piston = WallMotion::parabolic_piston(6.0, 0.25);
    e.set_wall(1, 0, piston, kFloor);
    std::uint64_t sorts = 0;
    for (int k = 1; k <= 400; ++k) {
        const double t_stop = 0.1 * k;
        // A generous collision budget turns a run-away (a stop time never reached) into a failure.
        const auto stop = e.advance(t_stop, e.counters().collisions + 2000000);
        ASSERT_EQ(stop, EventDrivenEngine<2>::Stop::TimeLimit) << "at t = " << t_stop;
        ASSERT_EQ(e.now(), t_stop);
        e.synchronize();
        const double floor = e.wall_position(2, t_stop);
        for (std::size_t i = 0; i < e.particles().size(); ++i) {
            const double y = e.particles().r[i][1];
            ASSERT_GE(y - 0.5 - floor, -1e-9) << "particle below the piston at t = " << t_stop;
            ASSERT_LE(y, 24 - 0.5 + 1e-9);
        }
        sorts = e.counters().sorts;
    }
    EXPECT_GT(sorts, 5u);  // several origin shifts happened
    EXPECT_GT(e.wall_hits()[2], 1000u);
}

}  // namespace
}  // namespace gran
