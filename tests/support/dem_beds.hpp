#pragma once
// DEM test beds shared by the tests of the threaded steps and of the spatial sort
// (tests/libgran/engines/dem): a dense frictional bed, a compressed lattice, and a bit-for-bit
// comparison of two engines' states.
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

namespace gran::testing {

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

// The bed under gravity along the last axis, its floor (if bounded) vibrated at A = 0.2,
// omega = 10, with `s`'s threads (at least 100 grains each: small systems really split) and sort.
template <int D>
DemEngine<D> bed_engine(const Bed<D>& b, DemSettings s) {
    s.gravity = {0, 0, 0};
    s.gravity[std::size_t(D - 1)] = -1;
    s.min_particles_per_thread = 100;
    DemEngine<D> e(b.box, b.table, b.contacts, b.particles, s);
    EXPECT_EQ(e.threads(), s.threads);
    if (!b.box.periodic[D - 1]) e.set_wall(D - 1, 0, WallMotion::sinusoid(0.2, 10.0), 0);
    return e;
}

template <int D>
DemEngine<D> bed_engine(const Bed<D>& b, int threads) {
    DemSettings s;
    s.threads = threads;
    return bed_engine<D>(b, s);
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
    EXPECT_TRUE(same_bits(a.ids(), b.ids())) << what << ": storage order";
    EXPECT_EQ(a.counters().sorts, b.counters().sorts) << what;
}

// `to` continues from `from`'s state, written and read back through a checkpoint.
template <int D>
void restore_checkpoint(DemEngine<D>& from, DemEngine<D>& to) {
    StateArchive out = StateArchive::saver();
    from.checkpoint(out);
    StateArchive in = StateArchive::loader(out.bytes());
    to.checkpoint(in);
    ASSERT_TRUE(in.at_end());
}

}  // namespace gran::testing
