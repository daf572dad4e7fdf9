// The event queue's two layouts (event_queue.hpp): the calendar gives the earliest entry first,
// exactly as the heap does, through the engine's pattern of updates (the top moved later, a
// partner moved anywhere, entries set to never), across many cycles and redistributions, with
// the event density changing, and through a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/engines/event_driven/event_queue.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/event_driven_scenes.hpp"
#include "tests/support/periodic_cube.hpp"

namespace gran {
namespace {

constexpr double kNeverTime = std::numeric_limits<double>::infinity();

// A heap and a calendar fed the same updates; every top compared.
struct Twin {
    EventQueue heap, calendar;
    explicit Twin(std::size_t n) {
        heap.reset(n, false);
        calendar.reset(n, true);
    }
    template <class TimeOf>
    void rebuild(TimeOf time_of) {
        heap.rebuild(time_of);
        calendar.rebuild(time_of);
    }
    void update(std::uint32_t id, double t) {
        heap.update(id, t);
        calendar.update(id, t);
    }
    // Same top, same time; returns the top.
    std::uint32_t expect_same_top() const {
        EXPECT_EQ(calendar.top(), heap.top());
        EXPECT_EQ(calendar.top_time(), heap.top_time());
        return heap.top();
    }
};

// The engine's use: pop the top, move it to a later time; move a random "partner" to a time
// after now or to never; now and then drop an entry to never and bring it back. The mean delay
// is `scale` (changed mid-run to force new slice widths).
void run_engine_pattern(Twin& q, std::mt19937_64& rng, std::size_t steps, double& scale) {
    const std::size_t n = q.heap.size();
    std::exponential_distribution<double> delay(1.0);
    std::uniform_int_distribution<std::uint32_t> any(0, std::uint32_t(n - 1));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t s = 0; s < steps; ++s) {
        const std::uint32_t i = q.expect_same_top();
        if (::testing::Test::HasFailure()) return;  // one report, not one per step
        const double now = q.heap.top_time();
        ASSERT_LT(now, kNeverTime) << "step " << s;
        if (s == steps / 3) scale *= 50.0;       // a sudden slowdown: slices far too narrow
        if (s == 2 * steps / 3) scale /= 400.0;  // then far too wide
        q.update(i, now + scale * delay(rng));
        const std::uint32_t j = any(rng);
        const double x = u(rng);
        if (x < 0.02) {
            q.update(j, kNeverTime);
        } else if (x < 0.04) {
            q.update(j, 1e300);
        } else {
            q.update(j, now + scale * delay(rng));
        }
        const std::uint32_t k = any(rng);
        EXPECT_EQ(q.calendar.time_of(k), q.heap.time_of(k));
    }
}

// Every entry at `start` plus an exponential delay of mean 1.
void start_exponential(Twin& q, std::mt19937_64& rng, double start) {
    std::exponential_distribution<double> delay(1.0);
    std::vector<double> t0(q.heap.size());
    for (double& t : t0) t = start + delay(rng);
    q.rebuild([&](std::uint32_t id) { return t0[id]; });
}

TEST(EventQueue, CalendarPopsTheEarliestEntryAsTheHeapThroughTheEnginesUpdates) {
    const std::size_t n = 5000;
    Twin q(n);
    std::mt19937_64 rng(7);
    start_exponential(q, rng, 3.0);
    EXPECT_LT(q.calendar.heap_size(), n / 10) << "the calendar keeps most entries out of the heap";
    double scale = 1.0;
    run_engine_pattern(q, rng, 400000, scale);
}

TEST(EventQueue, CalendarWithAllEntriesTiedOrNeverIsAPlainHeap) {
    const std::size_t n = 1000;
    Twin q(n);
    q.rebuild([](std::uint32_t) { return 2.0; });  // all tied: no slice width from the median
    EXPECT_EQ(q.calendar.heap_size(), n);
    q.expect_same_top();
    q.rebuild([](std::uint32_t) { return kNeverTime; });
    q.expect_same_top();
    EXPECT_EQ(q.calendar.top_time(), kNeverTime);
    // One entry comes alive: it is the top.
    q.update(17, 5.0);
    EXPECT_EQ(q.expect_same_top(), 17u);
    std::mt19937_64 rng(11);
    q.rebuild([&](std::uint32_t id) { return 1.0 + 1e-3 * double((id * 7919u) % 1000u); });
    double scale = 1e-3;
    run_engine_pattern(q, rng, 50000, scale);
}

TEST(EventQueue, CalendarResumedFromACheckpointPopsAsTheOriginal) {
    const std::size_t n = 3000;
    Twin q(n);
    std::mt19937_64 rng(5);
    start_exponential(q, rng, 0.0);
    double scale = 1.0;
    run_engine_pattern(q, rng, 20000, scale);

    StateArchive out = StateArchive::saver();
    q.calendar.checkpoint(out);
    Twin resumed(n);
    resumed.heap = q.heap;
    StateArchive in = StateArchive::loader(out.bytes());
    resumed.calendar.checkpoint(in);
    std::mt19937_64 rng_resumed = rng;
    double scale_resumed = scale;
    run_engine_pattern(q, rng, 20000, scale);
    run_engine_pattern(resumed, rng_resumed, 20000, scale_resumed);
    EXPECT_EQ(resumed.calendar.top(), q.calendar.top());
    EXPECT_EQ(resumed.calendar.top_time(), q.calendar.top_time());
}

// The engine on each layout: the same collisions in the same order. Both partners of a pending
// collision hold the same time, and the layouts pop such ties in different orders, so the
// partners' roles can swap and round in the last bit; chaos then parts the runs after a while.
// The first `agree` collisions are compared, pairs exactly and times to 1e-9.
template <int D>
void expect_layouts_agree(const Box<D>& box, const SpeciesTable& t, const ContactTable& c,
                          const Particles<D>& p, EngineSettings s, std::uint64_t collisions,
                          std::size_t agree) {
    testing::CollisionLog<D> log[2];
    for (int k = 0; k < 2; ++k) {
        s.queue_layout = k == 0 ? QueueLayout::heap : QueueLayout::calendar;
        EventDrivenEngine<D> engine(box, t, c, p, s);
        engine.set_collision_sink(&log[k]);
        engine.advance(kNeverTime, collisions);
        EXPECT_EQ(engine.event_calendar(), k == 1);
    }
    ASSERT_GE(log[0].pairs.size(), agree);
    ASSERT_GE(log[1].pairs.size(), agree);
    for (std::size_t m = 0; m < agree; ++m) {
        ASSERT_EQ(log[0].pairs[m], log[1].pairs[m]) << "collision " << m;
        ASSERT_NEAR(log[0].times[m], log[1].times[m], 1e-9) << "collision " << m;
    }
}

TEST(EventQueue, EngineOnTheCalendarMeetsTheHeapsCollisionsInADenseInelasticSphereMixture) {
    const SpeciesTable t = testing::bidisperse(1000, 1000, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.8}");
    const Box<3> box = testing::cube_for<3>(t, 0.3, true);
    const Particles<3> p = testing::placed<3>(box, t, c, 51);
    EngineSettings s;
    s.neighbour_skin = 0.0;  // cells
    expect_layouts_agree<3>(box, t, c, p, s, 60000, 20000);
}

TEST(EventQueue, EngineOnTheCalendarMeetsTheHeapsCollisionsOfRoughSpheresOnNeighbourShells) {
    const SpeciesTable t = testing::bidisperse(600, 600, 0.7);
    const auto c = testing::contacts_of(t, "{alpha: 0.9, beta: 0.3}");
    const Box<3> box = testing::cube_for<3>(t, 0.4, true);
    const Particles<3> p = testing::placed<3>(box, t, c, 52);
    EngineSettings s;
    s.neighbour_skin = 0.5;
    expect_layouts_agree<3>(box, t, c, p, s, 40000, 10000);
}

TEST(EventQueue, EngineOnTheCalendarMeetsTheHeapsCollisionsOfDisksUnderGravityBetweenWalls) {
    const SpeciesTable t = testing::bidisperse(800, 800, 0.5);
    const auto c = testing::contacts_of(t, "{alpha: 0.95}", 2);
    Box<2> box = testing::cube_for<2>(t, 0.3, true);
    box.periodic[1] = false;  // static walls at y = 0 and y = L
    const Particles<2> p = testing::placed<2>(box, t, c, 53);
    EngineSettings s;
    s.gravity = {0.0, -0.5, 0.0};
    expect_layouts_agree<2>(box, t, c, p, s, 40000, 10000);
}

// The engine's own choice: a calendar from EventQueue::kCalendarFromEntries particles on, turned
// into a heap at the first change of every velocity (a thermostat's kick, which rebuilds the
// queue each time); a layout forced by the settings stays. After the change the collisions still
// come in time order.
TEST(EventQueue, EngineTurnsItsOwnCalendarIntoAHeapWhenEveryVelocityChangesAndKeepsAForcedOne) {
    const SpeciesTable small = testing::bidisperse(2000, 2000, 0.8);  // below the threshold
    const SpeciesTable large = testing::bidisperse(2500, 2500, 0.8);
    for (const SpeciesTable* t : {&small, &large}) {
        for (QueueLayout layout : {QueueLayout::automatic, QueueLayout::calendar}) {
            const auto c = testing::contacts_of(*t, "{alpha: 1.0}");
            const Box<3> box = testing::cube_for<3>(*t, 0.2, true);
            const Particles<3> p = testing::placed<3>(box, *t, c, 54);
            EngineSettings s;
            s.queue_layout = layout;
            EventDrivenEngine<3> engine(box, *t, c, p, s);
            const bool calendar = layout == QueueLayout::calendar ||
                                  engine.particles().size() >= EventQueue::kCalendarFromEntries;
            EXPECT_EQ(engine.event_calendar(), calendar) << engine.particles().size();
            engine.advance(kNeverTime, 5000);
            engine.velocities_changed();
            EXPECT_EQ(engine.event_calendar(), layout == QueueLayout::calendar);
            testing::CollisionLog<3> log;
            engine.set_collision_sink(&log);
            engine.advance(kNeverTime, 25000);  // the limit counts from the start
            ASSERT_EQ(log.times.size(), 20000u);
            for (std::size_t m = 1; m < log.times.size(); ++m)
                ASSERT_LE(log.times[m - 1], log.times[m]) << "collision " << m;
        }
    }
}

}  // namespace
}  // namespace gran
