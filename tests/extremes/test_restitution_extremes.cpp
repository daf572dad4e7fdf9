// Extremes of the normal restitution (issue 6): alpha exactly 1 and alpha = 1e-3.
//  - alpha = 1: the collision rule conserves energy and momentum exactly, so in floating point
//    both drift only by round-off: ~1e-16 per collision as a random walk, ~1e-13 after 2e5
//    collisions; we allow 1e-12 (energy, relative) and 1e-12 x sqrt(N m T) (momentum).
//  - alpha = 1e-3: free cooling clusters and, without a guard, collapses (tests/extremes/
//    test_watchdog.cpp). With the TC model (default) the run must complete, the energy must fall
//    at every sample (each collision dissipates or, under the guard, is elastic) to a small
//    fraction of its start, and stay finite.
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/conservation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

template <int D>
void check_exactly_elastic(std::uint64_t seed) {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, D == 2 ? 0.5 : 0.4, 500});
    const ContactTable c = testing::contacts_of(t, "", D);  // alpha = 1, smooth
    Box<D> box;
    box.length = Vec<D>::Constant(std::pow(500 * (D == 2 ? M_PI / 4 : M_PI / 6) / 0.3, 1.0 / D));
    box.periodic.fill(true);
    Rng rng = make_rng(seed, Stream::Placement);
    auto p = place_random<D>(box, t, rng);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    const double e0 = testing::translational_energy<D>(p, t);
    const Vec<D> p0 = testing::momentum<D>(p, t);
    EventDrivenEngine<D> engine(box, t, c, p, EngineSettings{});
    engine.advance(kInf, 200000);
    engine.synchronize();
    const auto& q = engine.particles();
    EXPECT_EQ(engine.counters().collisions, 200000u);
    EXPECT_NEAR(testing::translational_energy<D>(q, t) / e0, 1.0, 1e-12);
    EXPECT_LT((testing::momentum<D>(q, t) - p0).norm(), 1e-12 * std::sqrt(500.0));
    EXPECT_GT(testing::closest_approach<D>(q, t, box), 1 - 1e-9);
}

TEST(RestitutionExtremes, ExactlyElasticDisksConserveEnergyAndMomentumToRoundOff) {
    check_exactly_elastic<2>(11);
}
TEST(RestitutionExtremes, ExactlyElasticSpheresConserveEnergyAndMomentumToRoundOff) {
    check_exactly_elastic<3>(12);
}

void check_nearly_sticky_free_cooling(int d) {
    const std::string tag = "sticky" + std::to_string(d);
    const YAML::Node s = testing::run_yaml("dimension: " + std::to_string(d) + R"(
seed: 4
species: [{name: a, count: 1000}]
interactions: {alpha: 0.001}
box: {packing_fraction: 0.1}
observables: [{type: kinetic_energy}]
run: {measurement: 200, sample_interval: 5}
)",
                                           tag);
    EXPECT_EQ(s["status"].as<std::string>(), "completed");
    // The TC guard did act (otherwise this would be the unguarded collapse).
    EXPECT_GT(s["performance"]["tc_guard_collisions"].as<double>(), 0);
    auto f = h5::File::open_read((testing::temp_dir() / (tag + ".h5")).string());
    const auto e = f.root().read_doubles("observables/kinetic_energy/energy_per_particle/value");
    ASSERT_EQ(e.size(), 40u);
    const double e_start = 0.5 * d * 1.0;  // T0 = 1: d/2 T per particle
    EXPECT_LT(e.front(), e_start);
    for (std::size_t k = 0; k < e.size(); ++k) {
        ASSERT_TRUE(std::isfinite(e[k])) << "sample " << k;
        EXPECT_GT(e[k], 0) << "sample " << k;
        if (k > 0) {
            EXPECT_LE(e[k], e[k - 1] * (1 + 1e-12)) << "energy rose at sample " << k;
        }
    }
    // 200 collisions per particle at alpha = 1e-3: the gas keeps less than 1% of its energy.
    EXPECT_LT(e.back(), 0.01 * e_start);
}

TEST(RestitutionExtremes, NearlyStickyDisksCoolWithoutHangOrNaN) {
    check_nearly_sticky_free_cooling(2);
}
TEST(RestitutionExtremes, NearlyStickySpheresCoolWithoutHangOrNaN) {
    check_nearly_sticky_free_cooling(3);
}

}  // namespace
}  // namespace gran
