// Soft-sphere DEM engine with many grains (libgran/engines/dem/engine.hpp): energy and momentum
// conservation, the neighbour list against brute force in every kind of box, tangential springs
// across list rebuilds, the time step's defaults and limits, a bed settling under gravity, a
// vibrated bed and the contact virial. Single collisions: test_dem_engine.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "species/contact_laws.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/dem_grains.hpp"

namespace gran {
namespace {

using namespace testing::dem;  // make_species, table_of, soft, duration, make_box, momentum, sci

// ----- many particles ----------------------------------------------------------------------------

template <int D>
struct Gas {
    SpeciesTable table;
    Box<D> box;
    Particles<D> particles;
};

// Random non-overlapping placement at packing fraction phi in a periodic box, Maxwellian
// velocities at T = 1 with zero total momentum. Two species (m 1 and 2, sigma 1 and 0.8).
template <int D>
Gas<D> periodic_gas(std::size_t n, double phi, std::uint64_t seed) {
    Gas<D> g;
    g.table =
        table_of({make_species("a", 1, 1, 0.4, n / 2), make_species("b", 2, 0.8, 0.5, n - n / 2)});
    const double vd = D == 2 ? kPi / 4 : kPi / 6;
    double volume = 0;
    for (const auto& s : g.table.species) volume += double(s.count) * vd * std::pow(s.diameter, D);
    g.box = make_box<D>(std::pow(volume / phi, 1.0 / D), true);
    Rng rng = make_rng(seed, Stream::Placement);
    g.particles = place_random<D>(g.box, g.table, rng);
    Rng vrng = make_rng(seed, Stream::Velocities);
    maxwellian_velocities<D>(g.particles, g.table, 1.0, vrng);
    return g;
}

// Elastic, frictionless spheres. Velocity Verlet is symplectic, but the linear spring's force has
// a kink at delta = 0: each contact ends with an energy offset of up to (pi dt / 2 t_c)^2 of its
// normal energy (contact_laws.hpp; 3e-5 at t_c / 200, 1.4e-6 at t_c / 1000), random in sign and
// zero on average, so the total energy does not drift but random-walks over the collisions
// (about sqrt(N_coll) offsets), on top of the O((omega dt)^2) oscillation during contacts. Measured
// with this gas (max over the run of |E/E0 - 1|): 1.5e-5 at t_c / 200, 1-2e-6 at t_c / 500,
// 2-4e-7 at t_c / 1000 over 10^5 steps of 100 spheres (10^7 particle-steps, ~430 collisions,
// 4 seeds). Over 10^6 steps (the acceptance) the walk is sqrt(5) longer at t_c / 2000 and
// each offset 4 times smaller: the test uses t_c / 2000 and requires 1e-6 at the end and at every
// sampled step (every 10 steps).
TEST(DemEngine, ElasticGasConservesEnergyWithinOnePartPerMillionOverAMillionSteps) {
    Gas<3> g = periodic_gas<3>(100, 0.2, 7);
    const ContactTable contacts = soft(g.table, "linear_dashpot", "contact_time: 0.02");
    DemSettings settings;
    settings.dt_fraction = 1.0 / 2000;
    DemEngine<3> e(g.box, g.table, contacts, g.particles, settings);
    EXPECT_FALSE(e.particles().rotating());
    const double e0 = e.energies().total();
    double worst = 0;
    for (int s = 0; s < 1000000; ++s) {
        e.step();
        if (s % 10 == 9) worst = std::max(worst, std::abs(e.energies().total() / e0 - 1));
    }
    const double end = std::abs(e.energies().total() / e0 - 1);
    RecordProperty("relative_energy_error_end", sci(end));
    RecordProperty("relative_energy_error_max", sci(worst));
    EXPECT_LT(end, 1e-6);
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(e.counters().contacts, 1500u);  // the gas did collide (~20 collisions per sphere)
    EXPECT_EQ(e.counters().steps, 1000000u);
}

// Newton's third law holds pair by pair (the force on j is minus the force on i, computed once),
// so the total momentum of a periodic system changes by round-off only, with damping, friction and
// tangential springs. Tolerance 1e-13 of sum m |v|.
template <int D>
void check_momentum(const std::string& law) {
    Gas<D> g = periodic_gas<D>(200, 0.35, 11);
    const ContactTable contacts = soft(
        g.table, law, "contact_time: 0.02, restitution: 0.7, friction: 0.4, tangential_damping: 5");
    DemEngine<D> e(g.box, g.table, contacts, g.particles, DemSettings{});
    double scale = 0;
    for (std::size_t i = 0; i < g.particles.size(); ++i) {
        scale += e.species_mass(g.particles.species[i]) * g.particles.v[i].norm();
    }
    const Vec<D> p0 = momentum(e);
    e.advance(2000 * e.dt());
    EXPECT_GT(e.counters().contacts, 100u);
    EXPECT_LT((momentum(e) - p0).norm(), 1e-13 * scale) << law << " D " << D;
}

TEST(DemEngine, PeriodicSystemConservesMomentumToRoundOff) {
    for (const char* law : {"linear_dashpot", "cundall_strack"}) {
        check_momentum<2>(law);
        check_momentum<3>(law);
    }
}

// The Verlet list with skin finds every overlapping pair, and the contact state (hence the
// tangential springs, stored alongside) survives the rebuilds: at every step of a dense run with a
// small skin (frequent rebuilds), the engine's count of active contacts equals a brute-force count
// over all pairs (minimum image), and its count of contacts formed equals the number of pairs
// found overlapping that did not overlap at the step before. Exact equalities.
template <int D>
void check_neighbour_list() {
    Gas<D> g = periodic_gas<D>(300, D == 2 ? 0.45 : 0.35, 3);
    const ContactTable contacts =
        soft(g.table, "linear_dashpot", "contact_time: 0.05, restitution: 0.95");
    DemSettings settings;
    settings.skin = 0.02;
    DemEngine<D> e(g.box, g.table, contacts, g.particles, settings);
    const auto& ps = e.particles();
    const std::size_t n = ps.size();
    std::vector<std::uint8_t> before(n * n, 0), now(n * n, 0);
    const auto overlaps = [&](std::vector<std::uint8_t>& out) {
        std::uint64_t count = 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = i + 1; j < n; ++j) {
                const double sigma =
                    0.5 * (e.species_diameter(ps.species[i]) + e.species_diameter(ps.species[j]));
                out[i * n + j] = e.box().separation(ps.r[i], ps.r[j]).norm() < sigma;
                count += out[i * n + j];
            }
        }
        return count;
    };
    overlaps(before);
    std::uint64_t formed = e.counters().contacts;
    for (int s = 0; s < 400; ++s) {
        e.step();
        const std::uint64_t active = overlaps(now);
        for (std::size_t k = 0; k < n * n; ++k) formed += now[k] && !before[k];
        ASSERT_EQ(e.counters().active_contacts, active) << "step " << s;
        ASSERT_EQ(e.counters().contacts, formed) << "step " << s;
        before.swap(now);
    }
    EXPECT_GT(e.counters().rebuilds, 5u);
    EXPECT_GT(formed, 100u);
}

TEST(DemEngine, NeighbourListFindsEveryOverlappingPair) {
    check_neighbour_list<2>();
    check_neighbour_list<3>();
}

// The cell-built list itself equals the brute-force list: every pair i < j closer than its cutoff
// sigma_ij + skin (minimum image), each exactly once as partner j of row i, and no other entry.
// Boxes that take every path of the build: periodic axes with a single cell (minimum image per
// pair), with 3 and more cells (image shifts of the half stencil), bounded axes binned over the
// range the particles occupy (also outside [0, L)), a grid coarsened to its cap of cells; two
// species (sigma 1 and 0.6), uniform random positions (overlaps allowed: the list is checked right
// after construction, before any step).
template <int D>
void check_list_against_brute_force(const Box<D>& box, std::size_t n, const Vec<D>& lo,
                                    const Vec<D>& hi, unsigned seed, std::size_t min_pairs) {
    const SpeciesTable t =
        table_of({make_species("a", 1, 1, 0.4, n / 2), make_species("b", 0.5, 0.6, 0.4, n / 2)});
    const ContactTable contacts = soft(t, "linear_dashpot", "contact_time: 0.05, restitution: 0.9");
    Particles<D> p;
    p.resize(n, false);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::size_t i = 0; i < n; ++i) {
        p.species[i] = std::uint32_t(i % 2);
        for (int a = 0; a < D; ++a) p.r[i][a] = lo[a] + u(rng) * (hi[a] - lo[a]);
    }
    DemSettings settings;
    settings.skin = 0.1;  // x the largest diameter, 1
    DemEngine<D> e(box, t, contacts, p, settings);
    const auto& nl = e.neighbour_list();
    const auto& ps = e.particles();
    ASSERT_EQ(nl.start.size(), n + 1);
    std::set<std::pair<std::size_t, std::size_t>> listed;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::uint32_t k = nl.start[i]; k < nl.start[i + 1]; ++k) {
            const std::size_t j = nl.partner[k];
            EXPECT_LT(i, j);
            EXPECT_EQ(nl.owner[k], i);
            EXPECT_TRUE(listed.insert({i, j}).second) << "pair " << i << " " << j << " twice";
        }
    }
    EXPECT_EQ(nl.entries(), listed.size());
    std::size_t expected = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            const double cut = 0.5 * e.species_diameter(ps.species[i]) +
                               0.5 * e.species_diameter(ps.species[j]) + 0.1;
            if (!(e.box().separation(ps.r[i], ps.r[j]).squaredNorm() < cut * cut)) continue;
            ++expected;
            EXPECT_TRUE(listed.count({i, j})) << "pair " << i << " " << j << " missing";
        }
    }
    EXPECT_EQ(listed.size(), expected);
    EXPECT_GE(expected, min_pairs);
}

TEST(DemEngine, NeighbourListEqualsBruteForceInEveryKindOfBox) {
    {  // 3D periodic, one cell per axis (L < 3 cutoffs), then 3 cells per axis
        check_list_against_brute_force<3>(make_box<3>(2.5, true), 40, Vec<3>::Zero(),
                                          Vec<3>::Constant(2.5), 1, 20);
        check_list_against_brute_force<3>(make_box<3>(3.5, true), 80, Vec<3>::Zero(),
                                          Vec<3>::Constant(3.5), 2, 40);
    }
    {  // 3D periodic x, y and a bounded z, particles in a slab well inside (the vibrated bed)
        Box<3> box = make_box<3>(7.3, true, 30);
        check_list_against_brute_force<3>(box, 300, Vec<3>(0, 0, 2), Vec<3>(7.3, 7.3, 9), 3, 100);
    }
    {  // 3D mixed: x periodic with one cell, y periodic with 4, z bounded, some particles outside
        Box<3> box;
        box.length = Vec<3>(2.5, 5.0, 4.0);
        box.periodic = {true, true, false};
        check_list_against_brute_force<3>(box, 100, Vec<3>(0, 0, -0.5), Vec<3>(2.5, 5.0, 4.5), 4,
                                          50);
    }
    {  // 3D bounded, 54^3 cells of one cutoff coarsened to the cap of 2^16
        check_list_against_brute_force<3>(make_box<3>(60, false), 2000, Vec<3>::Zero(),
                                          Vec<3>::Constant(60), 5, 20);
    }
    {  // 2D periodic with one and with 3 cells per axis
        check_list_against_brute_force<2>(make_box<2>(2.5, true), 30, Vec<2>::Zero(),
                                          Vec<2>::Constant(2.5), 6, 20);
        check_list_against_brute_force<2>(make_box<2>(3.5, true), 40, Vec<2>::Zero(),
                                          Vec<2>::Constant(3.5), 7, 20);
    }
    {  // 2D periodic x, bounded y, particles in a band
        Box<2> box = make_box<2>(9, true, 50);
        check_list_against_brute_force<2>(box, 200, Vec<2>(0, 1), Vec<2>(9, 12), 8, 50);
    }
    {  // 2D bounded, 272^2 cells coarsened to the cap
        check_list_against_brute_force<2>(make_box<2>(300, false), 3000, Vec<2>::Zero(),
                                          Vec<2>::Constant(300), 9, 50);
    }
}

// Contact states and tangential springs survive the rebuilds: a dense frictional gas with
// tangential springs (cundall_strack) run with a small skin (a rebuild every few steps) follows the
// same run with a large skin (few rebuilds) to round-off, which a spring lost or reset at a
// rebuild would not (the springs carry a sizeable part of the tangential forces).
template <int D>
void check_springs_survive_rebuilds() {
    const Gas<D> g = periodic_gas<D>(200, D == 2 ? 0.45 : 0.35, 21);
    const ContactTable contacts =
        soft(g.table, "cundall_strack", "contact_time: 0.05, restitution: 0.7, friction: 0.5");
    DemSettings small, large;
    small.skin = 0.01;
    large.skin = 0.5;
    DemEngine<D> a(g.box, g.table, contacts, g.particles, small);
    DemEngine<D> b(g.box, g.table, contacts, g.particles, large);
    for (int s = 0; s < 300; ++s) {
        a.step();
        b.step();
    }
    EXPECT_GT(a.counters().rebuilds, 20u);
    EXPECT_LT(b.counters().rebuilds, a.counters().rebuilds / 4);
    EXPECT_GT(a.counters().contacts, 100u);
    EXPECT_EQ(a.counters().contacts, b.counters().contacts);
    double worst = 0;
    for (std::size_t i = 0; i < a.particles().size(); ++i) {
        worst = std::max(worst, (a.particles().v[i] - b.particles().v[i]).norm());
        worst = std::max(worst, a.box().separation(a.particles().r[i], b.particles().r[i]).norm());
    }
    ::testing::Test::RecordProperty("largest_difference_D" + std::to_string(D), sci(worst));
    EXPECT_LT(worst, 1e-9);
}

TEST(DemEngine, TangentialSpringsSurviveNeighbourListRebuilds) {
    check_springs_survive_rebuilds<2>();
    check_springs_survive_rebuilds<3>();
}

TEST(DemEngine, TimeStepDefaultsToAFiftiethOfTheShortestContactAndRefusesMoreThanAFifth) {
    const SpeciesTable t = table_of({make_species("a", 1, 1, 0.4, 1)});
    const ContactTable contacts = soft(t, "linear_dashpot", "contact_time: 1e-3, restitution: 0.9");
    // Every contact is resolved for its own reduced mass (a wall's: m): the same contact time.
    EXPECT_NEAR(duration(contacts, contacts.pair_index(0, 0)), 1e-3, 1e-15);
    EXPECT_NEAR(duration(contacts, contacts.wall_index(0, 0)), 1e-3, 1e-15);
    Particles<2> p;
    p.resize(1, false);
    p.r[0] = Vec<2>(2, 2);
    DemEngine<2> e(make_box<2>(4, true), t, contacts, p, DemSettings{});
    EXPECT_NEAR(e.dt(), 1e-3 / 50, 1e-15);
    DemSettings coarse;
    coarse.dt = 1e-3 / 4;
    try {
        DemEngine<2> bad(make_box<2>(4, true), t, contacts, p, coarse);
        ADD_FAILURE() << "dt = t_c / 4 accepted";
    } catch (const std::invalid_argument& err) {
        EXPECT_NE(std::string(err.what()).find("t_c / 5"), std::string::npos) << err.what();
    }
    // advance() takes whole steps and reports the time reached.
    e.advance(1.01e-3 / 50 * 7);
    EXPECT_EQ(e.counters().steps, 8u);
    EXPECT_NEAR(e.now(), 8e-3 / 50, 1e-15);
}

// ----- beds under gravity ------------------------------------------------------------------------

// The paper's stiffness: k_n = 2e5 m g / d (units m = d = g = 1), e_p = e_w = 0.9, mu_p = mu
// (its smooth, 0, and rough, 0.4, systems; gamma_t is not given in the paper).
ContactTable bed_contacts(const SpeciesTable& t, double mu) {
    return soft(t, "linear_dashpot",
                "stiffness: 2e5, restitution: 0.9, tangential_damping: 20, friction: " +
                    std::to_string(mu));
}

// 100 smooth grains (the paper's law with mu = 0, e = 0.9) dropped on a static floor settle: the
// kinetic energy decays from ~0.5 m g d per grain (at impact) to ~0: below 1e-6 m g d per grain at
// t = 40 sqrt(d/g) (measured over 6 seeds: 2e-24 to 2e-7; frictionless packings keep slow sliding
// modes that only the normal damping removes, hence the spread). No grain is below the floor; the
// static overlaps are of order the weight of the column over k_n (2e-5 d measured; required
// < 1e-3 d); the largest overlap of the whole run (impacts of the drop) stays below 1 % of d; the
// floor carries the weight N m g within 1 % (measured <= 0.1 %).
// (Rough grains with the paper's law, which has no tangential spring and hence no static
// friction, keep creeping at ~1e-5 m g d per grain; with cundall_strack they stop apart from
// free spins about vertical contact normals, which no force of these laws resists.)
TEST(DemEngine, BedSettlesOnAStaticFloor) {
    const SpeciesTable t = table_of({make_species("a", 1, 1, 0.4, 100)});
    const ContactTable contacts = bed_contacts(t, 0.0);
    DemSettings settings;
    settings.gravity = {0, 0, -1};
    Box<3> box = make_box<3>(5, true, 40);
    DemEngine<3> e(box, t, contacts, vibrated_bed_lattice(100, 5, 1.0, 5), settings);
    e.remove_wall(2, 1);  // open top
    e.advance(40);
    const auto& ps = e.particles();
    const DemEnergies en = e.energies();
    RecordProperty("kinetic_per_grain", sci((en.translational + en.rotational) / 100));
    EXPECT_LT((en.translational + en.rotational) / 100, 1e-6);
    double lowest = 1e300, worst = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        lowest = std::min(lowest, ps.r[i][2]);
        for (std::size_t j = i + 1; j < ps.size(); ++j) {
            worst = std::max(worst, 1.0 - e.box().separation(ps.r[i], ps.r[j]).norm());
        }
        worst = std::max(worst, 0.5 - ps.r[i][2]);
    }
    RecordProperty("max_static_overlap", sci(worst));
    EXPECT_GT(lowest, 0.5 - 1e-3);  // centres above the floor (overlap < 1e-3 d)
    EXPECT_LT(worst, 1e-3);
    EXPECT_LT(e.counters().max_overlap, 0.01);  // including the impacts of the drop
    double floor_force = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (ps.r[i][2] < 0.5) floor_force += 2e5 * (0.5 - ps.r[i][2]);
    }
    EXPECT_NEAR(floor_force, 100.0, 1.0);
}

// Smoke test of the paper's setup (Sec. III): 100 grains in a 5d x 5d periodic column on a floor
// vibrated at A sin(omega t), A = d, W = (A omega)^2 / (d g) = 9, rough grains (mu_p = 0.4), no
// lid. The drop from the initial lattice settles into a steady state within ~7 periods (measured:
// T_z per period 1.4-1.7 m g d from period 7 to 40, i.e. T_z / m V_p^2 = 0.17). After 8 periods
// the granular temperature T_z = m <(v_z - <v_z>)^2> (Eq. 5) over the next 8 periods is finite,
// positive, and equal in its two halves within 30 % (steady state; one period fluctuates by
// about 10 %), and no grain ever sinks into the floor by more than 2 % of d.
TEST(DemEngine, VibratedBedReachesASteadyGranularTemperature) {
    const SpeciesTable t = table_of({make_species("a", 1, 1, 0.4, 100)});
    const ContactTable contacts = bed_contacts(t, 0.4);
    DemSettings settings;
    settings.gravity = {0, 0, -1};
    const double A = 1, omega = 3, period = 2 * kPi / omega;
    DemEngine<3> e(make_box<3>(5, true, 80), t, contacts, vibrated_bed_lattice(100, 5, 3.0, 9),
                   settings);
    e.remove_wall(2, 1);
    e.set_wall(2, 0, WallMotion::sinusoid(A, omega), 0);
    e.advance(8 * period);
    const auto& ps = e.particles();
    double sum[2] = {0, 0};
    int samples[2] = {0, 0};
    double deepest = 0;
    const double t0 = e.now();
    while (e.now() < t0 + 8 * period) {
        e.advance(e.now() + 0.01);
        double mean = 0;
        for (const auto& v : ps.v) mean += v[2];
        mean /= double(ps.size());
        double tz = 0;
        for (const auto& v : ps.v) tz += (v[2] - mean) * (v[2] - mean);
        const int half = e.now() < t0 + 4 * period ? 0 : 1;
        sum[half] += tz / double(ps.size());
        ++samples[half];
        const double floor = e.wall_position(4, e.now());
        for (const auto& r : ps.r) deepest = std::max(deepest, floor + 0.5 - r[2]);
    }
    const double tz1 = sum[0] / samples[0], tz2 = sum[1] / samples[1];
    RecordProperty("T_z_first_half", sci(tz1));
    RecordProperty("T_z_second_half", sci(tz2));
    EXPECT_TRUE(std::isfinite(tz1) && std::isfinite(tz2));
    EXPECT_GT(tz1, 0.0);
    EXPECT_GT(tz2, 0.0);
    EXPECT_LT(std::max(tz1, tz2) / std::min(tz1, tz2), 1.3);
    EXPECT_LT(deepest, 0.02);
    EXPECT_GT(e.wall_hits()[4], 100u);
    EXPECT_EQ(e.wall_hits()[5], 0u);
}

}  // namespace
}  // namespace gran

namespace gran {
namespace {

// The contact virial (DemEngine::contact_virial, the pressure observable's interaction part on
// this engine): for a cluster of grains far from the periodic boundaries, the sum over contacts
// of (r_i - r_j)_a F_a equals sum_i r_{i,a} f_{i,a} over the particles' total contact forces
// (Newton's third law pair by pair), with damping, friction and tangential springs. Checked per
// axis after each of 200 steps (about 50 with two or more contacts), to 1e-12 of the largest term.
template <int D>
void check_contact_virial() {
    const SpeciesTable t =
        table_of({make_species("a", 1, 1, 0.4, 4), make_species("b", 2, 0.8, 0.5, 4)});
    const ContactTable contacts =
        soft(t, "cundall_strack",
             "contact_time: 0.02, restitution: 0.7, friction: 0.4, tangential_damping: 5");
    Particles<D> p;
    p.resize(8, true);
    Rng rng = make_rng(5, Stream::Velocities);
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec<D> centre = Vec<D>::Constant(15.0);
    for (std::size_t i = 0; i < 8; ++i) {
        p.species[i] = i < 4 ? 0 : 1;
        Vec<D> offset;
        for (int a = 0; a < D; ++a) offset[a] = 1.05 * double((i >> a) & 1) + 0.05 * u(rng);
        p.r[i] = centre + offset;
        p.v[i] = -2.0 * (offset - Vec<D>::Constant(0.5));  // inwards: the cluster presses together
        for (int a = 0; a < D; ++a) p.v[i][a] += 0.3 * u(rng);
    }
    DemEngine<D> e(make_box<D>(30, true), t, contacts, p, DemSettings{});
    std::uint64_t checked = 0;
    for (int s = 0; s < 200; ++s) {
        e.step();
        const std::vector<double> virial = e.contact_virial();
        ASSERT_EQ(virial.size(), std::size_t(2 * D));
        const auto& ps = e.particles();
        for (int a = 0; a < D; ++a) {
            double direct = 0, scale = 1e-300;
            for (std::size_t i = 0; i < ps.size(); ++i) {
                const double term = (ps.r[i][a] - centre[a]) * e.forces()[i][a];
                direct += term;
                scale = std::max(scale, std::abs(term));
            }
            const double sum = virial[std::size_t(a)] + virial[std::size_t(D + a)];
            ASSERT_NEAR(sum, direct, 1e-12 * scale) << "step " << s << " axis " << a;
        }
        if (e.counters().active_contacts >= 2) ++checked;
    }
    EXPECT_GT(checked, 20u) << "the cluster must collide: steps with two or more contacts";
}

TEST(DemEngine, ContactVirialEqualsTheVirialOfTheParticlesTotalForces) {
    check_contact_virial<2>();
    check_contact_virial<3>();
}

}  // namespace
}  // namespace gran
