// Long runs (issue 6, `make validate`): no drift in the time bookkeeping and no growth of the cost
// per event or step.
//  - event-driven, 1e9 events, 100 elastic disks (phi 0.3, periodic): run as 10 chunks of 1e8
//    events (EventDrivenEngine::advance's event limit). After each chunk: energy within one ulp
//    (2.2e-16) per collision, the worst case of rounding biased one way (the rounding of the
//    collision rule is slightly biased: a pure random walk, ~1e-12, was exceeded: 1.2e-9 after
//    4e8 collisions, i.e. 1/70 ulp per collision), momentum to 1e-9, every particle
//    clock at the same time after synchronize(), no overlap (brute force). The collision frequency
//    per chunk (2 dN_coll / (N dt)) is stationary in an elastic equilibrium gas: every chunk within
//    1% of the first (statistical scatter ~1/sqrt(5e7) = 0.014%), so a drift of the simulated
//    time against the events would show. CPU time per event in the last chunk within 20% of the
//    first (a growing heap, cell lists or clock origin would show here).
//  - dem, 1e8 steps, 16 elastic disks (k_n = 1e4, dt = t_c / 50): 10 chunks of 1e7 steps; now()
//    is t0 + steps dt exactly (no accumulated sum) and CPU time per step in the last chunk is
//    within 20% of the first. Energy: the contact force switches on and off between steps, so
//    velocity Verlet is not exactly symplectic here; each contact leaves an error of order
//    (dt/t_c)^2 = 4e-4 of its pair's energy (~1/8 of the total with 16 grains), of random sign:
//    a random walk, |dE/E| < 3 x 5e-5 sqrt(contacts) (measured ~1% after 1e8 steps).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <ctime>

#include "libgran/engines/dem/engine.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/conservation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/periodic_cube.hpp"

namespace gran {
namespace {

double cpu_seconds() {
    return double(std::clock()) / CLOCKS_PER_SEC;
}

TEST(LongRuns, EventDrivenBillionEventsKeepTimeEnergyAndCostPerEvent) {
    constexpr int D = 2;
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, 0.5, 100});
    const ContactTable c = testing::contacts_of(t, "", D);
    const Box<D> box = testing::cube_for<D>(t, 0.3, true);
    Rng rng = make_rng(61, Stream::Placement);
    auto p = place_random<D>(box, t, rng);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    const double e0 = testing::translational_energy<D>(p, t);
    EventDrivenEngine<D> engine(box, t, c, p, EngineSettings{});
    constexpr std::uint64_t kChunk = 100000000;
    std::vector<double> freq, cost;
    double t_prev = engine.now();
    std::uint64_t c_prev = 0;
    for (int k = 1; k <= 10; ++k) {
        const double c0 = cpu_seconds();
        const auto stop = engine.advance(kInf, UINT64_MAX, nullptr, std::uint64_t(k) * kChunk);
        cost.push_back((cpu_seconds() - c0) / double(kChunk));
        ASSERT_EQ(stop, EventDrivenEngine<D>::Stop::EventLimit);
        engine.synchronize();
        const auto& q = engine.particles();
        for (std::size_t i = 1; i < q.size(); ++i) ASSERT_EQ(q.t[i], q.t[0]) << "clock of " << i;
        EXPECT_GT(engine.now(), t_prev);
        freq.push_back(2.0 * double(engine.counters().collisions - c_prev) / 100.0 /
                       (engine.now() - t_prev));
        t_prev = engine.now();
        c_prev = engine.counters().collisions;
        EXPECT_NEAR(testing::translational_energy<D>(q, t) / e0, 1.0,
                    2.2e-16 * double(engine.counters().collisions))
            << "chunk " << k;
        EXPECT_LT(testing::momentum<D>(q, t).norm(), 1e-9 * std::sqrt(2 * e0)) << "chunk " << k;
        EXPECT_GT(testing::closest_approach<D>(q, t, box), 1 - 1e-9) << "chunk " << k;
        RecordProperty("energy_chunk_" + std::to_string(k),
                       fmt::format("{:.3e}", testing::translational_energy<D>(q, t) / e0 - 1));
    }
    for (int k = 1; k < 10; ++k) EXPECT_NEAR(freq[k] / freq[0], 1.0, 0.01) << "chunk " << k;
    RecordProperty("frequency_last_over_first", std::to_string(freq.back() / freq.front()));
    EXPECT_NEAR(cost.back() / cost.front(), 1.0, 0.2);
    RecordProperty("events", std::to_string(engine.counters().events));
    RecordProperty("simulated_time", std::to_string(engine.now()));
    RecordProperty("ns_per_event_first_last",
                   std::to_string(cost.front() * 1e9) + " " + std::to_string(cost.back() * 1e9));
}

TEST(LongRuns, DemHundredMillionStepsKeepTimeEnergyAndCostPerStep) {
    constexpr int D = 2;
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, 0.5, 16});
    const ContactTable c = testing::contacts_of(t, "{law: linear_dashpot, stiffness: 1e4}", D);
    const Box<D> box = testing::cube_for<D>(t, 0.2, true);
    Rng rng = make_rng(62, Stream::Placement);
    auto p = place_random<D>(box, t, rng);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    DemEngine<D> engine(box, t, c, p, DemSettings{});
    const double e0 = engine.energies().total();
    const double dt = engine.dt();
    constexpr std::uint64_t kChunk = 10000000;
    std::vector<double> cost;
    for (int k = 1; k <= 10; ++k) {
        const double c0 = cpu_seconds();
        // Whole steps until now() >= the limit: half a step short of k chunks gives k chunks.
        engine.advance((double(std::uint64_t(k) * kChunk) - 0.5) * dt);
        cost.push_back((cpu_seconds() - c0) / double(kChunk));
        ASSERT_EQ(engine.counters().steps, std::uint64_t(k) * kChunk);
        EXPECT_EQ(engine.now(), double(engine.counters().steps) * dt);
        for (double ti : engine.particles().t) ASSERT_EQ(ti, engine.now());
        EXPECT_NEAR(engine.energies().total() / e0, 1.0,
                    3 * 5e-5 * std::sqrt(double(engine.counters().contacts)))
            << "chunk " << k;
        RecordProperty("energy_chunk_" + std::to_string(k),
                       fmt::format("{:.3e}", engine.energies().total() / e0 - 1));
    }
    EXPECT_GT(engine.counters().contacts, 10000u) << "too few contacts to test anything";
    EXPECT_NEAR(cost.back() / cost.front(), 1.0, 0.2);
    RecordProperty("steps", std::to_string(engine.counters().steps));
    RecordProperty("contacts", std::to_string(engine.counters().contacts));
    RecordProperty("ns_per_step_first_last",
                   std::to_string(cost.front() * 1e9) + " " + std::to_string(cost.back() * 1e9));
}

}  // namespace
}  // namespace gran
