// Event-driven engine: conservation laws and event bookkeeping on small systems.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/conservation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/periodic_cube.hpp"

namespace gran {
namespace {

SpeciesTable make_table(int ns, double mass_ratio, std::size_t n_each, double q) {
    SpeciesTable t;
    for (int s = 0; s < ns; ++s) {
        Species sp;
        sp.name = s == 0 ? "a" : "b";
        sp.mass = s == 0 ? mass_ratio : 1.0;
        sp.diameter = s == 0 ? 1.0 : 0.8;
        sp.inertia_factor = q;
        sp.count = n_each;
        t.species.push_back(sp);
    }
    return t;
}

// Constant restitution alpha, beta for every contact.
ContactTable contacts(const SpeciesTable& t, double alpha, double beta) {
    return testing::contacts_of(t, fmt::format("{{alpha: {}, beta: {}}}", alpha, beta));
}

using testing::cube_for;

template <int D>
double kinetic_energy(const Particles<D>& p, const SpeciesTable& t) {
    return testing::translational_energy<D>(p, t) + testing::rotational_energy<D>(p, t);
}

using testing::momentum;

template <int D>
void check_elastic_conservation(int ns, bool periodic, std::uint64_t collisions, double beta,
                                double q) {
    const auto table = make_table(ns, 3.0, ns == 1 ? 400 : 200, q);
    const auto c = contacts(table, 1.0, beta);
    const auto box = cube_for<D>(table, 0.2, periodic);
    Rng rng = make_rng(7, Stream::Placement);
    auto p = place_random<D>(box, table, rng);
    testing::allocate_rotation<D>(p, c);
    maxwellian_velocities<D>(p, table, 1.0, rng);
    const double e0 = kinetic_energy<D>(p, table);
    const Vec<D> p0 = momentum<D>(p, table);
    EventDrivenEngine<D> engine(box, table, c, p, EngineSettings{});
    engine.advance(kInf, collisions);
    engine.synchronize();
    const double e1 = kinetic_energy<D>(engine.particles(), table);
    EXPECT_EQ(engine.counters().collisions, collisions);
    EXPECT_NEAR(e1 / e0, 1.0, 1e-10);
    if (periodic) {
        EXPECT_LT((momentum<D>(engine.particles(), table) - p0).norm(), 1e-9);
    }
    // No overlaps at the end: every pair at least its contact distance apart (to round-off).
    const auto& q_ = engine.particles();
    double worst = 1;
    for (std::size_t i = 0; i < q_.size(); ++i) {
        for (std::size_t j = i + 1; j < q_.size(); ++j) {
            const double sig = 0.5 * (table.species[q_.species[i]].diameter +
                                      table.species[q_.species[j]].diameter);
            worst = std::min(worst, box.separation(q_.r[i], q_.r[j]).norm() / sig);
        }
    }
    EXPECT_GT(worst, 1 - 1e-9);
}

// Issue #2 acceptance: elastic limit conserves energy to 1e-10 relative after 10^6 collisions.
TEST(EventDrivenEngine, ElasticDisksConserveEnergyOverAMillionCollisions) {
    check_elastic_conservation<2>(1, true, 1000000, -1, 0.5);
}
TEST(EventDrivenEngine, ElasticSpheresConserveEnergyOverAMillionCollisions) {
    check_elastic_conservation<3>(1, true, 1000000, -1, 0.4);
}
TEST(EventDrivenEngine, ElasticBinaryDisksConserveEnergyOverAMillionCollisions) {
    check_elastic_conservation<2>(2, true, 1000000, -1, 0.5);
}
TEST(EventDrivenEngine, ElasticBinarySpheresConserveEnergyOverAMillionCollisions) {
    check_elastic_conservation<3>(2, true, 1000000, -1, 0.4);
}
TEST(EventDrivenEngine, ElasticBinaryDisksBetweenWallsConserveEnergy) {
    check_elastic_conservation<2>(2, false, 200000, -1, 0.5);
}
TEST(EventDrivenEngine, PerfectlyRoughSpheresConserveEnergy) {
    check_elastic_conservation<3>(2, true, 200000, 1.0, 0.4);
}

// Size ratio 4 at high packing: many small particles share a cell one large diameter wide, so the
// dense cell layout must grow its capacity; energy is still conserved and nothing overlaps.
TEST(EventDrivenEngine, SizeRatioFourDenseMixtureConservesEnergyAndNeverOverlaps) {
    SpeciesTable t;
    t.species.push_back(Species{"big", 4.0, 1.0, 0.4, 100});
    t.species.push_back(Species{"small", 0.1, 0.25, 0.4, 3000});
    const auto c = testing::contacts_of(t);
    const auto box = cube_for<3>(t, 0.35, true);
    Rng rng = make_rng(8, Stream::Placement);
    auto p = place_random<3>(box, t, rng);
    maxwellian_velocities<3>(p, t, 1.0, rng);
    const double e0 = kinetic_energy<3>(p, t);
    EventDrivenEngine<3> engine(box, t, c, p, EngineSettings{});
    engine.advance(kInf, 300000);
    engine.synchronize();
    EXPECT_NEAR(kinetic_energy<3>(engine.particles(), t) / e0, 1.0, 1e-10);
    const auto& q = engine.particles();
    double worst = 1;
    for (std::size_t i = 0; i < q.size(); ++i) {
        for (std::size_t j = i + 1; j < q.size(); ++j) {
            const double sig =
                0.5 * (t.species[q.species[i]].diameter + t.species[q.species[j]].diameter);
            worst = std::min(worst, box.separation(q.r[i], q.r[j]).norm() / sig);
        }
    }
    EXPECT_GT(worst, 1 - 1e-9);
}

TEST(PairCollisionTime, ApproachingOverlappingPairCollidesNow) {
    const Vec<2> dr(0.999, 0.0), dv(-1.0, 0.0);
    EXPECT_EQ(pair_collision_time<2>(dr, dv, 1.0), 0.0);
}
TEST(PairCollisionTime, RecedingOverlappingPairIsIgnored) {
    const Vec<2> dr(0.999, 0.0), dv(1.0, 0.0);
    EXPECT_EQ(pair_collision_time<2>(dr, dv, 1.0), kInf);
}
TEST(PairCollisionTime, HeadOnTimeIsGapOverSpeed) {
    const Vec<3> dr(3.0, 0.0, 0.0), dv(-2.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(pair_collision_time<3>(dr, dv, 1.0), 1.0);
}
TEST(PairCollisionTime, NearlyTouchingPairHasAccurateSmallTime) {
    // Gap 1e-12 closing at speed 1: the stable root gives the time to within the round-off of
    // |dr|^2 - sigma^2 (~1e-16), never a negative time and no cancellation in the root itself.
    const Vec<2> dr(1.0 + 1e-12, 0.0), dv(-1.0, 0.0);
    const double t = pair_collision_time<2>(dr, dv, 1.0);
    EXPECT_GT(t, 0.0);
    EXPECT_NEAR(t, 1e-12, 1e-15);
}
TEST(PairCollisionTime, MissingPairNeverCollides) {
    const Vec<2> dr(5.0, 2.0), dv(-1.0, 0.0);
    EXPECT_EQ(pair_collision_time<2>(dr, dv, 1.0), kInf);
}

// A very inelastic dense system undergoes inelastic collapse without a guard; the TC model keeps
// the run going and counts how often it intervened.
TEST(EventDrivenEngine, CollapseGuardKeepsVeryInelasticDenseGasRunning) {
    const auto table = make_table(1, 1.0, 1000, 0.5);
    const auto c = contacts(table, 0.1, -1);
    const auto box = cube_for<2>(table, 0.4, true);
    Rng rng = make_rng(3, Stream::Placement);
    auto p = place_lattice<2>(box, table, rng);
    maxwellian_velocities<2>(p, table, 1.0, rng);
    EngineSettings settings;
    settings.tc = 1e-4;
    EventDrivenEngine<2> engine(box, table, c, p, settings);
    const auto stop = engine.advance(kInf, 300000);
    EXPECT_EQ(stop, EventDrivenEngine<2>::Stop::CollisionLimit);
    EXPECT_GT(engine.counters().tc_collisions, 0u);
    EXPECT_LT(engine.counters().tc_collisions, engine.counters().collisions);
}

// Events are never scheduled in the past: the engine clock never decreases.
TEST(EventDrivenEngine, ClockIsMonotonicAcrossEvents) {
    const auto table = make_table(2, 2.0, 200, 0.5);
    const auto c = contacts(table, 0.7, 0.3);
    const auto box = cube_for<2>(table, 0.3, true);
    Rng rng = make_rng(4, Stream::Placement);
    auto p = place_random<2>(box, table, rng);
    testing::allocate_rotation<2>(p, c);
    maxwellian_velocities<2>(p, table, 1.0, rng);
    EventDrivenEngine<2> engine(box, table, c, p, EngineSettings{});
    double last = engine.now();
    for (int k = 1; k <= 2000; ++k) {
        engine.advance(kInf, std::uint64_t(k) * 10);
        ASSERT_GE(engine.now(), last);
        last = engine.now();
    }
}

}  // namespace
}  // namespace gran
