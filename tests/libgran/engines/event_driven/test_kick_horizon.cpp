// After a thermostat kick the engine predicts every event again, and it is told when the next
// kick comes (EventDrivenEngine::velocities_changed(next_change)): collisions after it are not
// looked for. The collisions before it must all be found, so an engine given the horizon meets
// the same collisions as one that searches without it, kick after kick. A horizon cut short (half
// the interval) drops real collisions, and the comparison catches it.
#include <gtest/gtest.h>

#include <algorithm>
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

struct KickedRun {
    double interval = 0;  // between kicks
    int kicks = 0;        // how many
    double kick_sd = 0;   // velocity kick per component
    double horizon = 0;   // told to the engine, in intervals; 0: none (search without a horizon)
    double skin = -1;     // EngineSettings::neighbour_skin
};

// Kicks every `interval`; particle with original id k gets the k-th kick of the round whatever
// its storage index (the two engines re-sort at different moments).
template <int D>
CollisionLog<D> run_kicked(const Box<D>& box, const SpeciesTable& t, const ContactTable& c,
                           const Particles<D>& p0, const KickedRun& k) {
    EngineSettings s;
    s.neighbour_skin = k.skin;
    EventDrivenEngine<D> engine(box, t, c, p0, s);
    CollisionLog<D> log;
    engine.set_collision_sink(&log);
    Rng rng = make_rng(99, Stream::Driver);
    std::vector<Vec<D>> kick(p0.size());
    for (int round = 1; round <= k.kicks; ++round) {
        engine.advance(round * k.interval, UINT64_MAX);
        engine.synchronize();
        for (auto& dv : kick)
            for (int a = 0; a < D; ++a) dv[a] = k.kick_sd * gaussian(rng);
        Particles<D>& p = engine.particles_for_update();
        for (std::size_t i = 0; i < p.size(); ++i) p.v[i] += kick[engine.ids()[i]];
        if (k.horizon > 0)
            engine.velocities_changed(engine.now() + k.horizon * k.interval);
        else
            engine.velocities_changed();
    }
    return log;
}

// Chaos amplifies round-off (a collision found from the other partner's side is computed in the
// other order), so the two runs agree collision by collision only for a while: the first
// `agree` collisions are compared, pairs exactly and times to 1e-9.
template <int D>
void expect_same_collisions(const CollisionLog<D>& a, const CollisionLog<D>& b, std::size_t agree) {
    ASSERT_GE(a.pairs.size(), agree);
    ASSERT_GE(b.pairs.size(), agree);
    for (std::size_t k = 0; k < agree; ++k) {
        ASSERT_EQ(a.pairs[k], b.pairs[k]) << "collision " << k;
        ASSERT_NEAR(a.times[k], b.times[k], 1e-9) << "collision " << k;
    }
}

// The run told the next kick (horizon: one interval) against the run without a horizon: the
// first 1500 collisions.
template <int D>
void expect_horizon_changes_no_collision(const Box<D>& box, const SpeciesTable& t,
                                         const ContactTable& c, const Particles<D>& p,
                                         KickedRun k) {
    const auto full = run_kicked<D>(box, t, c, p, k);
    k.horizon = 1.0;
    const auto limited = run_kicked<D>(box, t, c, p, k);
    expect_same_collisions<D>(full, limited, 1500);
}

// Kicks every ~1/8 of the mean free time (the thermostat's default), 1500 collisions.
TEST(KickHorizon, EngineToldTheNextKickMeetsTheSameCollisionsInADenseInelasticSphereMixture) {
    const SpeciesTable t = bidisperse(300, 300, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.8}");
    const Box<3> box = testing::cube_for<3>(t, 0.3, true);
    const Particles<3> p = placed<3>(box, t, c, 41);
    expect_horizon_changes_no_collision<3>(box, t, c, p, {0.01, 200, 0.1, 0.0, 0.0});
}

TEST(KickHorizon, EngineToldTheNextKickMeetsTheSameCollisionsOfRoughSpheresOnNeighbourShells) {
    const SpeciesTable t = bidisperse(200, 200, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.9, beta: 0.3}");
    const Box<3> box = testing::cube_for<3>(t, 0.4, true);
    const Particles<3> p = placed<3>(box, t, c, 42);
    expect_horizon_changes_no_collision<3>(box, t, c, p, {0.005, 200, 0.1, 0.0, 0.5});
}

TEST(KickHorizon, EngineToldTheNextKickMeetsTheSameCollisionsOfDisksBetweenWalls) {
    const SpeciesTable t = bidisperse(300, 300, 0.5);
    const auto c = testing::contacts_of(t, "{alpha: 0.9}", 2);
    Box<2> box = testing::cube_for<2>(t, 0.4, true);
    box.periodic[1] = false;  // static walls at y = 0 and y = L
    const Particles<2> p = placed<2>(box, t, c, 43);
    expect_horizon_changes_no_collision<2>(box, t, c, p, {0.02, 200, 0.1, 0.0, 0.0});
}

// Whatever the engine skips after a kick, every cell crossing before the next kick must happen:
// each particle is in its cell when the next kick comes. A dilute gas kicked hard, so that many
// particles cross within an interval; checked at every kick, each coordinate within 1e-9 cell
// widths of its cell. (A schedule that skipped the crossings after half the interval left 3089
// coordinates outside their cells here.)
TEST(KickHorizon, EveryParticleIsInItsCellAtEachKick) {
    const SpeciesTable t = bidisperse(400, 0, 1.0);
    const auto c = testing::contacts_of(t, "{alpha: 0.9}");
    const Box<3> box = testing::cube_for<3>(t, 0.1, true);
    const Particles<3> p0 = placed<3>(box, t, c, 44);
    EventDrivenEngine<3> engine(box, t, c, p0, EngineSettings{});
    Rng rng = make_rng(7, Stream::Driver);
    const double interval = 0.05;
    std::size_t outside = 0, crossings_within = 0;
    for (int round = 1; round <= 100; ++round) {
        const std::uint64_t before = engine.counters().cell_crossings;
        engine.advance(round * interval, UINT64_MAX);
        crossings_within += engine.counters().cell_crossings - before;
        engine.synchronize();
        const CellList<3>& cells = engine.cell_list();
        const Particles<3>& p = engine.particles();
        for (std::uint32_t i = 0; i < p.size(); ++i) {
            for (int a = 0; a < 3; ++a) {
                const double w = cells.width(a), lo = cells.coordinate(i, a) * w;
                if (p.r[i][a] < lo - 1e-9 * w || p.r[i][a] > lo + w + 1e-9 * w) ++outside;
            }
        }
        Particles<3>& q = engine.particles_for_update();
        for (auto& v : q.v)
            for (int a = 0; a < 3; ++a) v[a] += 0.3 * gaussian(rng);
        engine.velocities_changed(engine.now() + interval);
    }
    EXPECT_GT(crossings_within, 2000u);  // the test exercises crossings within an interval
    EXPECT_EQ(outside, 0u);
}

// The comparison can fail: told the next kick comes after half the interval, the engine misses
// the collisions of the second half, and the sequences part within the first kicks.
TEST(KickHorizon, AHorizonCutShortMissesCollisionsAndTheComparisonSeesIt) {
    const SpeciesTable t = bidisperse(300, 300, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.8}");
    const Box<3> box = testing::cube_for<3>(t, 0.3, true);
    const Particles<3> p = placed<3>(box, t, c, 41);
    KickedRun k{0.01, 200, 0.1, 0.0, 0.0};
    const auto full = run_kicked<3>(box, t, c, p, k);
    k.horizon = 0.5;
    const auto cut = run_kicked<3>(box, t, c, p, k);
    std::size_t same = 0;
    while (same < std::min(full.pairs.size(), cut.pairs.size()) &&
           full.pairs[same] == cut.pairs[same])
        ++same;
    EXPECT_LT(same, 200u) << "a horizon of half the interval should lose collisions at once";
}

}  // namespace
}  // namespace gran
