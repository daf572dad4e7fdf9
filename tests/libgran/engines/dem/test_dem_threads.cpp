// Threaded DEM steps (DemSettings::threads, libgran/core/parallel.hpp): the same bits for any
// number of threads, and a checkpoint written with one thread count continues with another.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "tests/support/dem_beds.hpp"

namespace gran {
namespace {

using testing::Bed;
using testing::bed_engine;
using testing::compressed_lattice;
using testing::dense_bed;
using testing::expect_same_state;

template <int D>
void check_thread_counts() {
    const Bed<D> bed = dense_bed<D>(2000);
    DemEngine<D> one = bed_engine<D>(bed, 1);
    DemEngine<D> two = bed_engine<D>(bed, 2);
    DemEngine<D> three = bed_engine<D>(bed, 3);
    std::uint64_t active = 0;
    for (int s = 0; s < 400; ++s) {
        one.step();
        two.step();
        three.step();
        active += one.counters().active_contacts;
    }
    // The comparison means something only if the run had contacts, springs and rebuilds.
    EXPECT_GT(double(active) / 400, 100) << "contacts per step";
    EXPECT_GT(one.counters().contacts, 500u) << "contacts formed";
    EXPECT_GT(one.counters().rebuilds, 3u);
    EXPECT_GT(one.wall_hits()[2 * (D - 1)], 10u);
    const DemEnergies en = one.energies();
    EXPECT_TRUE(std::isfinite(en.total())) << "the bed blew up";
    expect_same_state(one, two, "2 threads");
    expect_same_state(one, three, "3 threads");
}

TEST(DemThreads, StepsOnTwoAndThreeThreadsGiveTheBitsOfOneThread) {
    check_thread_counts<2>();
    check_thread_counts<3>();
}

// Many contacts per grain, every grain next to a share's cut receiving contacts from two
// threads' rows (halo grains, summed from their slots after the rows), on two and on three
// threads.
template <int D>
void check_crowded() {
    const Bed<D> lattice = compressed_lattice<D>(D == 2 ? 40 : 12);
    const std::size_t n = lattice.particles.size();
    DemEngine<D> one = bed_engine<D>(lattice, 1);
    DemEngine<D> two = bed_engine<D>(lattice, 2);
    DemEngine<D> three = bed_engine<D>(lattice, 3);
    // Every lattice neighbour overlaps at the start: 2 (disks) or 3 (spheres) contacts per grain.
    EXPECT_GE(one.counters().active_contacts, std::uint64_t(D) * n) << "contacts at the start";
    std::uint64_t crowded_steps = 0;  // steps with over n / 4 contacts: summed particle-wise
    for (int s = 0; s < 200; ++s) {
        one.step();
        two.step();
        three.step();
        crowded_steps += 4 * one.counters().active_contacts >= n;
    }
    EXPECT_GT(crowded_steps, 20u);
    EXPECT_TRUE(std::isfinite(one.energies().total())) << "the crystal blew up";
    expect_same_state(one, two, "crowded, 2 threads");
    expect_same_state(one, three, "crowded, 3 threads");
}

TEST(DemThreads, CrowdedGrainsOnTwoAndThreeThreadsGiveTheBitsOfOneThread) {
    check_crowded<2>();
    check_crowded<3>();
}

// A checkpoint carries no trace of the thread count: written by a one-thread engine, loaded into
// a two-thread one (whose partner index is rebuilt from the loaded list), the run continues as the
// one-thread run does.
TEST(DemThreads, CheckpointOfOneThreadContinuesBitIdenticallyOnTwo) {
    const Bed<3> bed = dense_bed<3>(1000);
    DemEngine<3> straight = bed_engine<3>(bed, 1);
    DemEngine<3> first = bed_engine<3>(bed, 1);
    for (int s = 0; s < 150; ++s) {
        straight.step();
        first.step();
    }
    DemEngine<3> second = bed_engine<3>(bed, 2);
    testing::restore_checkpoint<3>(first, second);
    if (HasFatalFailure()) return;
    for (int s = 0; s < 150; ++s) {
        straight.step();
        second.step();
    }
    EXPECT_GT(straight.counters().active_contacts, 100u);
    expect_same_state(straight, second, "resumed on 2 threads");
}

// The floor's candidates split between the threads (DemEngine::wall_forces), which needs at
// least min_particles_per_thread candidates per thread: a small share here, so that the floor of
// the 2000-grain bed is split, on two and on three threads.
TEST(DemThreads, FloorContactsSplitBetweenThreadsGiveTheBitsOfOneThread) {
    const Bed<3> bed = dense_bed<3>(2000);
    const auto engine = [&bed](int threads) {
        DemSettings s;
        s.threads = threads;
        s.gravity = {0, 0, -1};
        s.min_particles_per_thread = 10;
        DemEngine<3> e(bed.box, bed.table, bed.contacts, bed.particles, s);
        e.set_wall(2, 0, WallMotion::sinusoid(0.2, 10.0), 0);
        return e;
    };
    DemEngine<3> one = engine(1), two = engine(2), three = engine(3);
    for (int s = 0; s < 400; ++s) {
        one.step();
        two.step();
        three.step();
    }
    // Enough floor contacts that each thread's share had some.
    EXPECT_GT(one.wall_hits()[4], 60u) << "floor contacts formed";
    expect_same_state(one, two, "floor split, 2 threads");
    expect_same_state(one, three, "floor split, 3 threads");
}

TEST(DemThreads, SmallSystemsUseOneThreadPerMinimumShare) {
    const Bed<3> bed = dense_bed<3>(1000);
    DemSettings s;
    s.threads = 8;
    s.min_particles_per_thread = 300;  // 1000 grains: 3 shares
    EXPECT_EQ(DemEngine<3>(bed.box, bed.table, bed.contacts, bed.particles, s).threads(), 3);
    s.min_particles_per_thread = 4096;  // the default: fewer grains than one share
    EXPECT_EQ(DemEngine<3>(bed.box, bed.table, bed.contacts, bed.particles, s).threads(), 1);
}

TEST(DemThreads, RefusesAThreadCountOutsideOneTo256) {
    const Bed<2> bed = dense_bed<2>(20);
    EXPECT_THROW(bed_engine<2>(bed, 0), std::invalid_argument);
    EXPECT_THROW(bed_engine<2>(bed, 257), std::invalid_argument);
}

}  // namespace
}  // namespace gran
