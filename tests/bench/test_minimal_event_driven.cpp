// The minimal kernel of gran_bench_features (bench/minimal_event_driven) is the yardstick of the
// bare gas's speed, so its physics must be right: elastic hard disks/spheres conserve energy and
// momentum, never overlap, and collide at the Enskog frequency
//   omega = S n sigma^(d-1) g(sigma) sqrt(T/m)   (S = 2 sqrt(pi) in 2D, 4 sqrt(pi) in 3D)
// with the Henderson (2D) or Carnahan-Starling (3D) contact value. Tolerance 3%, as for gran's
// engine (tests/libgran/engines/event_driven/test_equilibrium_collision_frequency.cpp): the
// statistical error of 2e5 collisions is ~0.3% and the contact values are good to <1% at these
// densities, while a wrong contact distance or missed collisions shift omega by more.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bench/minimal_event_driven.hpp"
#include "libgran/core/kinetic_theory.hpp"
#include "libgran/scene/placement.hpp"

namespace gran {
namespace {

template <int D>
void check_kernel(double phi, std::size_t n) {
    SpeciesTable table;
    Species s;
    s.name = "a";
    s.count = n;
    table.species.push_back(s);
    Box<D> box;
    const double vd = theory::unit_ball_volume(D);
    box.length = Vec<D>::Constant(std::pow(double(n) * vd / phi, 1.0 / D));
    box.periodic.fill(true);
    Rng rng = make_rng(11, Stream::Placement);
    Particles<D> p = place_lattice<D>(box, table, rng);
    Rng vrng = make_rng(11, Stream::Velocities);
    maxwellian_velocities<D>(p, table, 1.0, vrng);
    std::vector<double> r, v;
    for (std::size_t i = 0; i < n; ++i) {
        for (int a = 0; a < D; ++a) {
            r.push_back(p.r[i][a]);
            v.push_back(p.v[i][a]);
        }
    }
    double e0 = 0;
    for (double x : v) e0 += 0.5 * x * x;
    const double T = 2 * e0 / (D * double(n));  // k_B T per degree of freedom, m = 1

    bench::MinimalEventDriven<D> md(box.length[0], r, v);
    const auto equilibration = static_cast<std::uint64_t>(30 * n / 2);
    const auto measured = static_cast<std::uint64_t>(200 * n / 2);
    md.run_until(equilibration);
    const double t0 = md.now();
    md.run_until(equilibration + measured);
    const double omega = 2.0 * double(measured) / (double(n) * (md.now() - t0));

    md.state(r, v);
    double e1 = 0;
    std::vector<double> mom(D, 0.0);
    for (std::size_t k = 0; k < v.size(); ++k) {
        e1 += 0.5 * v[k] * v[k];
        mom[k % D] += v[k];
    }
    EXPECT_LT(std::abs(e1 - e0) / e0, 1e-10);
    for (double m : mom) EXPECT_LT(std::abs(m) / std::sqrt(2 * e0), 1e-10);
    EXPECT_EQ(md.overlaps(), 0u);
    EXPECT_EQ(md.collisions(), equilibration + measured);
    const double expected =
        theory::enskog_collision_frequency(D, phi / vd, 1.0, theory::contact_value(D, phi), T, 1);
    EXPECT_NEAR(omega / expected, 1.0, 0.03) << "omega " << omega << ", Enskog " << expected;
}

TEST(MinimalEventDriven, DisksAtPhi030ConserveEnergyAndCollideAtTheEnskogFrequency) {
    check_kernel<2>(0.30, 2000);
}
TEST(MinimalEventDriven, SpheresAtPhi020ConserveEnergyAndCollideAtTheEnskogFrequency) {
    check_kernel<3>(0.20, 2000);
}

}  // namespace
}  // namespace gran
