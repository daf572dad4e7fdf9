// The DEM engine's spatial sort (DemSettings::sort_interval): the particles renumbered in the
// order of the neighbour list's cells, their contacts (with tangential springs, grain-grain and
// grain-wall) carried along, the original index of each kept in ids(); the same bits for any
// thread count and across a checkpoint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "tests/support/dem_beds.hpp"

namespace gran {
namespace {

using testing::Bed;
using testing::bed_engine;
using testing::dense_bed;
using testing::expect_same_state;

template <int D>
DemEngine<D> sorted_engine(const Bed<D>& b, std::uint64_t interval, int threads = 1) {
    DemSettings s;
    s.threads = threads;
    s.sort_interval = interval;
    s.min_particles_to_sort = 0;
    return bed_engine<D>(b, s);
}

// Mean distance between particles stored next to each other.
template <int D>
double mean_storage_neighbour_distance(const std::vector<Vec<D>>& r) {
    double sum = 0;
    for (std::size_t k = 1; k < r.size(); ++k) sum += (r[k] - r[k - 1]).norm();
    return sum / double(r.size() - 1);
}

template <int D>
void check_first_build_sorts() {
    const Bed<D> bed = dense_bed<D>(2000);
    const DemEngine<D> e = sorted_engine<D>(bed, 1000);
    EXPECT_EQ(e.counters().sorts, 1u);
    // ids() is a permutation, and each stored particle is the constructor's particle it names.
    std::vector<std::uint32_t> ids = e.ids();
    std::sort(ids.begin(), ids.end());
    std::vector<std::uint32_t> all(bed.particles.size());
    std::iota(all.begin(), all.end(), 0u);
    ASSERT_EQ(ids, all);
    std::size_t moved = 0;
    for (std::size_t k = 0; k < e.particles().size(); ++k) {
        const std::uint32_t i = e.ids()[k];
        EXPECT_EQ(e.particles().r[k], bed.particles.r[i]);
        EXPECT_EQ(e.particles().v[k], bed.particles.v[i]);
        EXPECT_EQ(e.particles().species[k], bed.particles.species[i]);
        moved += i != k;
    }
    EXPECT_GT(moved, bed.particles.size() / 2) << "the random placement was barely reordered";
    // Neighbours in memory are neighbours in space: from about half the box (random order: 37
    // diameters in 2D, 12 in 3D) to 3.5 and 2.5 diameters (cells 1.54 diameters wide, and a
    // jump at the end of each row of cells).
    const double before = mean_storage_neighbour_distance<D>(bed.particles.r);
    const double after = mean_storage_neighbour_distance<D>(e.particles().r);
    EXPECT_GT(before, 10.0);
    EXPECT_LT(after, before / 4);
}

TEST(DemSort, FirstListBuildStoresTheGrainsInCellOrderAndIdsNameThem) {
    check_first_build_sorts<2>();
    check_first_build_sorts<3>();
}

TEST(DemSort, UnsortedEngineKeepsTheConstructorsOrder) {
    const Bed<3> bed = dense_bed<3>(1000);
    DemEngine<3> e = bed_engine<3>(bed, 1);
    for (int s = 0; s < 50; ++s) e.step();
    EXPECT_EQ(e.counters().sorts, 0u);
    for (std::size_t k = 0; k < e.ids().size(); ++k) ASSERT_EQ(e.ids()[k], k);
}

// Sorting changes only the order in which forces are summed (a sum of two forces is the same
// either way, so in 2D, with few grains touching three others, the runs can agree to the bit):
// over a short stretch of a dense, frictional, vibrated bed (chaotic, but 300 steps amplify
// rounding to ~1e-13), every grain follows the trajectory of the unsorted run. A contact
// carried through a sort with the wrong partner, or with its tangential spring not turned round
// when its two grains swap roles, gives differences of the order of the velocities themselves.
template <int D>
void check_sorted_trajectory(const char* law = nullptr) {
    Bed<D> bed = dense_bed<D>(2000);
    if (law) bed.contacts = testing::contacts_of(bed.table, law, D);
    DemEngine<D> plain = bed_engine<D>(bed, 1);
    DemEngine<D> sorted = sorted_engine<D>(bed, 20);
    for (int s = 0; s < 300; ++s) {
        plain.step();
        sorted.step();
    }
    EXPECT_GE(sorted.counters().sorts, 5u);
    EXPECT_GT(plain.counters().active_contacts, 100u);
    EXPECT_GT(plain.wall_hits()[2 * (D - 1)], 10u);
    double dr = 0, dv = 0, dw = 0, w_scale = 0;
    for (std::size_t k = 0; k < sorted.particles().size(); ++k) {
        const std::uint32_t i = sorted.ids()[k];
        dr = std::max(dr, (sorted.particles().r[k] - plain.particles().r[i]).norm());
        dv = std::max(dv, (sorted.particles().v[k] - plain.particles().v[i]).norm());
        dw = std::max(
            dw,
            std::sqrt(ang_squared<D>(AngVec<D>(sorted.particles().w[k] - plain.particles().w[i]))));
        w_scale = std::max(w_scale, std::sqrt(ang_squared<D>(plain.particles().w[i])));
    }
    EXPECT_GT(w_scale, 0.1) << "the grains must spin for the springs to matter";
    EXPECT_LT(dr, 1e-9);
    EXPECT_LT(dv, 1e-7);
    EXPECT_LT(dw, 1e-6 * w_scale);
    EXPECT_EQ(sorted.counters().contacts, plain.counters().contacts);
    EXPECT_EQ(sorted.counters().rebuilds, plain.counters().rebuilds);
    EXPECT_NEAR(sorted.energies().elastic, plain.energies().elastic,
                1e-9 * plain.energies().elastic);
}

TEST(DemSort, SortedBedFollowsTheTrajectoryOfTheUnsortedOneGrainForGrain) {
    check_sorted_trajectory<2>();
    check_sorted_trajectory<3>();
    // A tangential dashpot (no spring): it reads the predicted angular velocities.
    check_sorted_trajectory<3>(
        "{law: linear_dashpot, contact_time: 0.05, restitution: 0.8, friction: 0.5, "
        "tangential_damping_ratio: 1, walls: {contact_time: 0.05, restitution: 0.9, "
        "friction: 0.3}}");
}

TEST(DemSort, SortedRunGivesTheSameBitsOnOneAndTwoThreads) {
    const Bed<3> bed = dense_bed<3>(2000);
    DemEngine<3> one = sorted_engine<3>(bed, 25, 1);
    DemEngine<3> two = sorted_engine<3>(bed, 25, 2);
    for (int s = 0; s < 200; ++s) {
        one.step();
        two.step();
    }
    EXPECT_GE(one.counters().sorts, 4u);
    expect_same_state(one, two, "sorted, 2 threads");
}

// The order and the step of the last sort are state: a run restored from a checkpoint sorts
// when the straight run does.
TEST(DemSort, CheckpointCarriesTheOrderAndTheNextSort) {
    const Bed<3> bed = dense_bed<3>(1000);
    DemEngine<3> straight = sorted_engine<3>(bed, 40);
    DemEngine<3> first = sorted_engine<3>(bed, 40);
    for (int s = 0; s < 130; ++s) {
        straight.step();
        first.step();
    }
    DemEngine<3> second = sorted_engine<3>(bed, 40);
    testing::restore_checkpoint<3>(first, second);
    if (HasFatalFailure()) return;
    const std::uint64_t sorts_before = straight.counters().sorts;
    for (int s = 0; s < 130; ++s) {
        straight.step();
        second.step();
    }
    EXPECT_GE(straight.counters().sorts, sorts_before + 2);
    expect_same_state(straight, second, "restored, sorted");
}

}  // namespace
}  // namespace gran
