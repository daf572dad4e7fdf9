// Threaded DEM steps (DemSettings::threads, libgran/core/parallel.hpp): the same bits for any
// number of threads, and a checkpoint written with one thread count continues with another.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "libgran/core/random.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/contacts.hpp"

namespace gran {
namespace {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// A dense, bidisperse, frictional bed (cundall_strack: tangential springs, rotation) under
// gravity: periodic sides, a floor vibrated at A sin(omega t), a static lid, about 2000 grains at
// packing fraction 0.45 (disks) or 0.35 (spheres) from a random placement, so the first steps
// resolve many overlaps, contacts form and break, and the list is rebuilt often.
template <int D>
struct Bed {
    SpeciesTable table;
    ContactTable contacts;
    Box<D> box;
    Particles<D> particles;
};

template <int D>
Bed<D> dense_bed(std::size_t n) {
    Bed<D> b;
    for (int s = 0; s < 2; ++s) {
        Species sp;
        sp.name = s == 0 ? "small" : "big";
        sp.mass = s == 0 ? 1.0 : 3.0;
        sp.diameter = s == 0 ? 1.0 : 1.4;
        sp.inertia_factor = D == 2 ? 0.5 : 0.4;
        sp.count = n / 2;
        b.table.species.push_back(sp);
    }
    b.contacts = testing::contacts_of(
        b.table,
        "{law: cundall_strack, contact_time: 0.05, restitution: 0.8, friction: 0.5, "
        "walls: {contact_time: 0.05, restitution: 0.9, friction: 0.3}}");
    const double vd = D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
    double volume = 0;
    for (const Species& s : b.table.species)
        volume += double(s.count) * vd * std::pow(s.diameter, D);
    const double phi = D == 2 ? 0.45 : 0.35;
    const double side = std::pow(volume / phi, 1.0 / D);
    b.box.length = Vec<D>::Constant(side);
    b.box.periodic.fill(true);
    b.box.periodic[D - 1] = false;
    Rng rng = make_rng(7, Stream::Placement);
    b.particles = place_random<D>(b.box, b.table, rng);
    Rng vrng = make_rng(7, Stream::Velocities);
    maxwellian_velocities<D>(b.particles, b.table, 1.0, vrng);
    return b;
}

// Many contacts per grain (the threaded sum by particle rather than by contact): grains of
// equal size and two masses on a square (cubic) lattice of spacing 0.97 d in a periodic box, so
// every lattice neighbour overlaps at the start and the crystal bursts.
template <int D>
Bed<D> compressed_lattice(std::size_t per_side) {
    Bed<D> b = dense_bed<D>(2);  // species and contacts
    std::size_t n = 1;
    for (int a = 0; a < D; ++a) n *= per_side;
    b.table.species[0].count = n / 2;
    b.table.species[1].count = n - n / 2;
    b.table.species[1].diameter = 1.0;
    b.contacts = testing::contacts_of(
        b.table, "{law: cundall_strack, contact_time: 0.05, restitution: 0.8, friction: 0.5}");
    const double spacing = 0.97;
    b.box.length = Vec<D>::Constant(spacing * double(per_side));
    b.box.periodic.fill(true);
    b.particles.resize(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t rest = i;
        for (int a = 0; a < D; ++a) {
            b.particles.r[i][a] = spacing * (double(rest % per_side) + 0.5);
            rest /= per_side;
        }
        b.particles.species[i] = std::uint32_t(i % 2);
    }
    Rng vrng = make_rng(11, Stream::Velocities);
    maxwellian_velocities<D>(b.particles, b.table, 0.01, vrng);
    return b;
}

template <int D>
DemEngine<D> bed_engine(const Bed<D>& b, int threads) {
    DemSettings s;
    s.gravity = {0, 0, 0};
    s.gravity[std::size_t(D - 1)] = -1;
    s.threads = threads;
    s.min_particles_per_thread = 100;  // small systems, really split
    DemEngine<D> e(b.box, b.table, b.contacts, b.particles, s);
    EXPECT_EQ(e.threads(), threads);
    if (!b.box.periodic[D - 1]) e.set_wall(D - 1, 0, WallMotion::sinusoid(0.2, 10.0), 0);
    return e;
}

// Everything a step leaves behind, compared bit for bit.
template <int D>
void expect_same_state(const DemEngine<D>& a, const DemEngine<D>& b, const std::string& what) {
    EXPECT_TRUE(same_bits(a.particles().r, b.particles().r)) << what << ": positions";
    EXPECT_TRUE(same_bits(a.particles().v, b.particles().v)) << what << ": velocities";
    EXPECT_TRUE(same_bits(a.particles().w, b.particles().w)) << what << ": angular velocities";
    EXPECT_TRUE(same_bits(a.forces(), b.forces())) << what << ": forces";
    EXPECT_TRUE(same_bits(a.torques(), b.torques())) << what << ": torques";
    EXPECT_TRUE(same_bits(a.neighbour_list().spring, b.neighbour_list().spring))
        << what << ": tangential springs";
    // The list built on several threads: the same entries in the same order.
    EXPECT_TRUE(same_bits(a.neighbour_list().start, b.neighbour_list().start)) << what << ": rows";
    EXPECT_TRUE(same_bits(a.neighbour_list().partner, b.neighbour_list().partner))
        << what << ": list entries";
    EXPECT_TRUE(same_bits(a.neighbour_list().owner, b.neighbour_list().owner))
        << what << ": entry owners";
    EXPECT_TRUE(same_bits(a.neighbour_list().touching, b.neighbour_list().touching))
        << what << ": contact flags";
    EXPECT_EQ(a.counters().contacts, b.counters().contacts) << what;
    EXPECT_EQ(a.counters().active_contacts, b.counters().active_contacts) << what;
    EXPECT_EQ(a.counters().rebuilds, b.counters().rebuilds) << what;
    EXPECT_EQ(std::memcmp(&a.counters().max_overlap, &b.counters().max_overlap, sizeof(double)), 0)
        << what << ": largest overlap";
    EXPECT_EQ(std::memcmp(a.wall_impulse().data(), b.wall_impulse().data(), sizeof(double) * 2 * D),
              0)
        << what << ": wall impulses";
    EXPECT_EQ(a.wall_hits(), b.wall_hits()) << what;
}

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

// Many contacts per grain: the threads sum the forces particle by particle.
template <int D>
void check_crowded() {
    const Bed<D> lattice = compressed_lattice<D>(D == 2 ? 40 : 12);
    const std::size_t n = lattice.particles.size();
    DemEngine<D> one = bed_engine<D>(lattice, 1);
    DemEngine<D> two = bed_engine<D>(lattice, 2);
    // Every lattice neighbour overlaps at the start: 2 (disks) or 3 (spheres) contacts per grain.
    EXPECT_GE(one.counters().active_contacts, std::uint64_t(D) * n) << "contacts at the start";
    std::uint64_t crowded_steps = 0;  // steps with over n / 4 contacts: summed particle-wise
    for (int s = 0; s < 200; ++s) {
        one.step();
        two.step();
        crowded_steps += 4 * one.counters().active_contacts >= n;
    }
    EXPECT_GT(crowded_steps, 20u);
    EXPECT_TRUE(std::isfinite(one.energies().total())) << "the crystal blew up";
    expect_same_state(one, two, "crowded, 2 threads");
}

TEST(DemThreads, CrowdedGrainsOnTwoThreadsGiveTheBitsOfOneThread) {
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
    StateArchive out = StateArchive::saver();
    first.checkpoint(out);
    DemEngine<3> second = bed_engine<3>(bed, 2);
    StateArchive in = StateArchive::loader(out.bytes());
    second.checkpoint(in);
    ASSERT_TRUE(in.at_end());
    for (int s = 0; s < 150; ++s) {
        straight.step();
        second.step();
    }
    EXPECT_GT(straight.counters().active_contacts, 100u);
    expect_same_state(straight, second, "resumed on 2 threads");
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
