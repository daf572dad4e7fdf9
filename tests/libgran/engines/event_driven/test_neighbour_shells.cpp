// Neighbour shells of the event-driven engine (neighbour_shells.hpp): the lists hold exactly the
// pairs within reach, and an engine that finds its pairs through them meets the same collisions
// as one that uses cells, in dense mixtures, between walls and with rough particles. Also the pair
// tests the scans share (event_times.hpp): branch-free and two-lane forms against the branched one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "libgran/core/random.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/event_driven_scenes.hpp"
#include "tests/support/periodic_cube.hpp"

namespace gran {
namespace {

using testing::bidisperse;
using testing::CollisionLog;
using testing::placed;

// Every list against a brute-force search over all pairs of shell centres.
template <int D>
void expect_lists_exact(const NeighbourShells<D>& shells, const Box<D>& box,
                        const std::vector<std::uint32_t>& species,
                        const std::vector<double>& radius, std::size_t n) {
    for (std::uint32_t i = 0; i < n; ++i) {
        std::set<std::uint32_t> listed(shells.list(i), shells.list(i) + shells.size(i));
        ASSERT_EQ(listed.size(), shells.size(i)) << "duplicate in the list of " << i;
        for (std::uint32_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const double reach = radius[species[i]] + radius[species[j]] + shells.skin();
            const double d = box.separation(shells.centre(i), shells.centre(j)).norm();
            if (std::abs(d - reach) < 1e-6 * reach) continue;  // at the edge: either is right
            ASSERT_EQ(listed.count(j) == 1, d < reach) << i << " and " << j << " at " << d;
        }
    }
}

template <int D>
void check_lists_follow_rebuilds() {
    const SpeciesTable t = bidisperse(150, 150, 0.6);
    const Box<D> box = testing::cube_for<D>(t, D == 2 ? 0.5 : 0.35, true);
    Rng rng = make_rng(3, Stream::Placement);
    const Particles<D> p = place_random<D>(box, t, rng);
    const std::vector<double> radius{0.5, 0.3};
    const double skin = 0.3;
    CellList<D> cells;
    cells.build(box, 1.0 + skin, p.r);
    NeighbourShells<D> shells;
    const typename NeighbourShells<D>::Sizes sizes{p.species.data(), radius.data()};
    shells.build(box, skin, p.r, cells, sizes);
    expect_lists_exact<D>(shells, box, p.species, radius, p.size());
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int step = 1; step <= 3000; ++step) {
        const auto i = std::uint32_t(unit(rng) * double(p.size()));
        Vec<D> x;
        for (int a = 0; a < D; ++a) x[a] = unit(rng) * box.length[a];
        shells.rebuild(i, x, box, cells, sizes);
        if (step % 1000 == 0) expect_lists_exact<D>(shells, box, p.species, radius, p.size());
    }
    // A re-sort permutes the rows and renames their entries.
    std::vector<std::uint32_t> order, inv;
    cells.sort_order(order, inv);
    std::vector<std::uint32_t> species(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) species[k] = p.species[order[k]];
    shells.reorder(order, inv);
    expect_lists_exact<D>(shells, box, species, radius, p.size());
}

TEST(NeighbourShells, ListsHoldExactlyThePairsWithinReachAfterRebuildsAndResortsInDisks) {
    check_lists_follow_rebuilds<2>();
}
TEST(NeighbourShells, ListsHoldExactlyThePairsWithinReachAfterRebuildsAndResortsInSpheres) {
    check_lists_follow_rebuilds<3>();
}

// The lists hold 16-bit indices (one cache line per 3D row): 65535 particles are the most.
TEST(NeighbourShells, HoldAtMost65535ParticlesAndRefuseOneMore) {
    const double side = 60.0;  // about 0.3 centres per unit volume: short lists
    Box<3> box;
    box.length = {side, side, side};
    box.periodic = {true, true, true};
    Rng rng = make_rng(5, Stream::Placement);
    std::uniform_real_distribution<double> unit(0.0, side);
    std::vector<Vec<3>> r(NeighbourShells<3>::kMaxParticles + 1);
    for (auto& x : r) x = {unit(rng), unit(rng), unit(rng)};
    const std::vector<std::uint32_t> species(r.size(), 0);
    const std::vector<double> radius{0.5};
    const NeighbourShells<3>::Sizes sizes{species.data(), radius.data()};
    CellList<3> cells;
    cells.build(box, 1.5, r);
    NeighbourShells<3> shells;
    EXPECT_THROW(shells.build(box, 0.5, r, cells, sizes), std::invalid_argument);
    r.pop_back();
    r[0] = {30.0, 30.0, 30.0};
    r.back() = {30.5, 30.0, 30.0};  // the last particle has a neighbour
    cells.build(box, 1.5, r);
    shells.build(box, 0.5, r, cells, sizes);
    // The last particle's index survives the 16 bits: it is in its neighbours' lists.
    const std::uint32_t last = std::uint32_t(r.size() - 1);
    ASSERT_GT(shells.size(last), 0u);
    const std::uint32_t j = shells.list(last)[0];
    EXPECT_EQ(std::count(shells.list(j), shells.list(j) + shells.size(j), last), 1);
}

TEST(ShellExitTime, ReachesTheShellEdgeFromInsideAndLeavesAtOnceFromOutside) {
    const Vec<3> d(0.1, 0.0, 0.0), v(1.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(shell_exit_time<3>(d, v, 0.25), 0.15);
    EXPECT_DOUBLE_EQ(shell_exit_time<3>(d, Vec<3>(-1.0, 0.0, 0.0), 0.25), 0.35);
    EXPECT_DOUBLE_EQ(shell_exit_time<3>(Vec<3>(0.0, 0.2, 0.0), v, 0.25), 0.15);  // sqrt(h^2 - y^2)
    EXPECT_EQ(shell_exit_time<3>(Vec<3>(0.3, 0.0, 0.0), v, 0.25), 0.0);
    EXPECT_EQ(shell_exit_time<3>(d, Vec<3>::Zero(), 0.25), kInf);
}

TEST(PairCollisionTime, BranchlessFormIsBitForBitTheBranchedOne) {
    Rng rng = make_rng(11, Stream::Placement);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int k = 0; k < 100000; ++k) {
        const Vec<3> dr(g(rng), g(rng), g(rng)), dv(g(rng), g(rng), g(rng));
        const double sigma = k % 3 == 0 ? 2.0 : 1.0;  // a third overlapping
        const double a = pair_collision_time<3>(dr, dv, sigma);
        const double b = pair_collision_time_branchless<3>(dr, dv, sigma);
        ASSERT_EQ(a, b) << k;
    }
    EXPECT_EQ(pair_collision_time_branchless<2>(Vec<2>(2, 0), Vec<2>(0, 1), 1.0), kInf);
}

// The scan tests two candidates per step (engine.cpp): each lane must give the one-pair time to
// the last bit, or runs would change with the parity of a candidate's position in a scan.
template <int D>
void check_two_lanes_match_one_pair(unsigned seed) {
    Rng rng = make_rng(seed, Stream::Placement);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int k = 0; k < 50000; ++k) {
        Vec<D> dr[2], dv[2];
        double sigma[2];
        for (int lane = 0; lane < 2; ++lane) {
            for (int a = 0; a < D; ++a) {
                dr[lane][a] = g(rng);
                dv[lane][a] = g(rng);
            }
            sigma[lane] = (k + lane) % 3 == 0 ? 2.0 : 1.0;  // a third overlapping
        }
        __m128d dr2[D], dv2[D];
        for (int a = 0; a < D; ++a) {
            dr2[a] = _mm_set_pd(dr[1][a], dr[0][a]);
            dv2[a] = _mm_set_pd(dv[1][a], dv[0][a]);
        }
        const __m128d t = pair_collision_times_two<D>(dr2, dv2, _mm_set_pd(sigma[1], sigma[0]));
        double lanes[2];
        _mm_storeu_pd(lanes, t);
        for (int lane = 0; lane < 2; ++lane) {
            const double one = pair_collision_time_branchless<D>(dr[lane], dv[lane], sigma[lane]);
            ASSERT_EQ(std::memcmp(&lanes[lane], &one, sizeof one), 0)
                << "pair " << k << " lane " << lane << ": " << lanes[lane] << " against " << one;
        }
    }
}

TEST(PairCollisionTime, TwoLaneFormIsBitForBitTheOnePairFormInEachLane) {
    check_two_lanes_match_one_pair<2>(12);
    check_two_lanes_match_one_pair<3>(13);
}

template <int D>
CollisionLog<D> log_collisions(const Box<D>& box, const SpeciesTable& t, const ContactTable& c,
                               const Particles<D>& p, double skin, std::uint64_t collisions) {
    EngineSettings s;
    s.neighbour_skin = skin;
    EventDrivenEngine<D> engine(box, t, c, p, s);
    EXPECT_EQ(engine.neighbour_skin(), skin);
    CollisionLog<D> log;
    engine.set_collision_sink(&log);
    engine.advance(kInf, collisions);
    if (skin > 0) {
        EXPECT_GT(engine.counters().shell_exits, 0u);
    }
    return log;
}

// Chaos amplifies round-off, so the two pair searches (which wrap positions at slightly different
// moments) agree collision by collision only for a while: the first `agree` collisions are
// compared, pairs exactly and times to 1e-9. A missed or spurious collision breaks the sequence at
// once.
template <int D>
void expect_same_collisions(const Box<D>& box, const SpeciesTable& t, const ContactTable& c,
                            const Particles<D>& p, double skin, std::size_t agree) {
    const auto cells = log_collisions<D>(box, t, c, p, 0.0, agree);
    const auto shells = log_collisions<D>(box, t, c, p, skin, agree);
    ASSERT_EQ(cells.pairs.size(), agree);
    ASSERT_EQ(shells.pairs.size(), agree);
    for (std::size_t k = 0; k < agree; ++k) {
        ASSERT_EQ(cells.pairs[k], shells.pairs[k]) << "collision " << k;
        ASSERT_NEAR(cells.times[k], shells.times[k], 1e-9) << "collision " << k;
    }
}

TEST(EventDrivenEngine, NeighbourShellsMeetTheCellsCollisionsInADenseElasticMixtureOfSpheres) {
    const SpeciesTable t = bidisperse(200, 200, 0.7);
    const auto c = testing::contacts_of(t);
    const Box<3> box = testing::cube_for<3>(t, 0.4, true);
    expect_same_collisions<3>(box, t, c, placed<3>(box, t, c, 21), 0.3, 2000);
}

TEST(EventDrivenEngine, NeighbourShellsMeetTheCellsCollisionsOfInelasticDisksBetweenWalls) {
    const SpeciesTable t = bidisperse(250, 250, 0.5);
    const auto c = testing::contacts_of(t, "{alpha: 0.9}", 2);
    Box<2> box = testing::cube_for<2>(t, 0.6, true);
    box.periodic[1] = false;  // walls at y = 0 and y = L
    expect_same_collisions<2>(box, t, c, placed<2>(box, t, c, 22), 0.2, 2000);
}

TEST(EventDrivenEngine, NeighbourShellsMeetTheCellsCollisionsOfRoughSpheresInABox) {
    const SpeciesTable t = bidisperse(300, 0, 1.0);
    const auto c = testing::contacts_of(t, "{alpha: 0.95, beta: 0.5}");
    const Box<3> box = testing::cube_for<3>(t, 0.3, false);
    expect_same_collisions<3>(box, t, c, placed<3>(box, t, c, 23), 0.5, 1500);
}

// A vibrating floor (no gravity): the wall's reach in cell layers counts the shells' skin.
TEST(EventDrivenEngine, NeighbourShellsMeetTheCellsCollisionsAboveAVibratingFloor) {
    const SpeciesTable t = bidisperse(250, 250, 0.8);
    const auto c = testing::contacts_of(t, "{alpha: 0.9}");
    Box<3> box = testing::cube_for<3>(t, 0.35, true);
    box.periodic[2] = false;
    const Particles<3> p = placed<3>(box, t, c, 26);
    auto run = [&](double skin) {
        EngineSettings s;
        s.neighbour_skin = skin;
        EventDrivenEngine<3> engine(box, t, c, p, s);
        engine.set_wall(2, 0, WallMotion::sinusoid(0.05, 6.0), 0);
        CollisionLog<3> log;
        engine.set_collision_sink(&log);
        engine.advance(kInf, 2000);
        EXPECT_GT(engine.wall_hits()[4], 20u);
        return log;
    };
    const auto cells = run(0.0), shells = run(0.5);
    ASSERT_EQ(cells.pairs.size(), shells.pairs.size());
    for (std::size_t k = 0; k < cells.pairs.size(); ++k) {
        ASSERT_EQ(cells.pairs[k], shells.pairs[k]) << "collision " << k;
        ASSERT_NEAR(cells.times[k], shells.times[k], 1e-9) << "collision " << k;
    }
}

// A checkpoint taken mid-run and loaded into an engine built from the same scene continues bit
// for bit as the uninterrupted run (the lists and centres are part of the state).
TEST(EventDrivenEngine, NeighbourShellsCheckpointContinuesBitForBit) {
    const SpeciesTable t = bidisperse(200, 200, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.95}");
    const Box<3> box = testing::cube_for<3>(t, 0.4, true);
    const Particles<3> p = placed<3>(box, t, c, 24);
    EngineSettings s;
    s.neighbour_skin = 0.4;
    EventDrivenEngine<3> a(box, t, c, p, s);
    ASSERT_GT(a.neighbour_skin(), 0.0);
    a.advance(kInf, 20000);
    StateArchive saver = StateArchive::saver();
    a.checkpoint(saver);
    EventDrivenEngine<3> b(box, t, c, p, s);
    StateArchive loader = StateArchive::loader(saver.bytes());
    b.checkpoint(loader);
    ASSERT_TRUE(loader.at_end());
    a.advance(kInf, 60000);
    b.advance(kInf, 60000);
    a.synchronize();
    b.synchronize();
    EXPECT_EQ(a.now(), b.now());
    for (std::size_t k = 0; k < p.size(); ++k) {
        ASSERT_EQ(a.particles().r[k], b.particles().r[k]) << k;
        ASSERT_EQ(a.particles().v[k], b.particles().v[k]) << k;
    }
}

TEST(EventDrivenEngine, NeighbourShellsAreRefusedUnderGravityAndInShortPeriodicBoxes) {
    const SpeciesTable t = bidisperse(100, 0, 1.0);
    const auto c = testing::contacts_of(t);
    const Box<3> box = testing::cube_for<3>(t, 0.3, true);  // 6.9 diameters: 4 cells of 1.5
    const Particles<3> p = placed<3>(box, t, c, 25);
    EngineSettings s;
    s.neighbour_skin = 0.8;  // cells 1.8 wide: 3 of them, too few
    EXPECT_THROW(EventDrivenEngine<3>(box, t, c, p, s), std::invalid_argument);
    s.neighbour_skin = 0.2;
    s.gravity = {0, 0, -1};
    Box<3> walled = box;
    walled.periodic[2] = false;
    EXPECT_THROW(EventDrivenEngine<3>(walled, t, c, p, s), std::invalid_argument);
    s.neighbour_skin = -1;  // the engine's choice falls back to cells under gravity
    EXPECT_EQ(EventDrivenEngine<3>(walled, t, c, p, s).neighbour_skin(), 0.0);
}

TEST(ChooseNeighbourSkin, DenseSmallThreeDimensionalGasesGetShellsTheRestCells) {
    EXPECT_EQ(choose_neighbour_skin(3, 0.1, 10000), 0.0);
    EXPECT_EQ(choose_neighbour_skin(3, 0.3, 10000), 0.0);
    EXPECT_GT(choose_neighbour_skin(3, 0.45, 10000), 0.0);
    EXPECT_EQ(choose_neighbour_skin(3, 0.45, 100000), 0.0);
    EXPECT_EQ(choose_neighbour_skin(2, 0.5, 10000), 0.0);
    EXPECT_EQ(choose_neighbour_skin(2, 0.75, 10000), 0.0);  // cells won in 2D
}

}  // namespace
}  // namespace gran
