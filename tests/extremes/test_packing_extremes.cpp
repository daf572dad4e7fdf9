// Extremes of the packing fraction (issue 6), event-driven engine, elastic.
//  - phi = 1e-4: the collision frequency must be the Boltzmann value omega = S n sigma^(d-1)
//    chi sqrt(T/m) (libgran/kinetic_theory, chi = 1.0002 here) within 3% (measured error < 1%);
//    the dilute cell cap (<= max(65536, 8 N) cells) keeps cell crossings per collision in the
//    hundreds (without it the cells would be one diameter wide: ~1e4 crossings per collision
//    and 8e6 cells).
//  - near the maximum: 0.8 (2D) and 0.55 (3D) absolute, and 0.8 x close packing = 0.726 (2D) and
//    0.55 x close packing = 0.407 (3D). Random insertion jams near 0.55 / 0.38 and the square /
//    cubic lattice stops at pi/4 / pi/6, so the dense ones start from initial.placement:
//    close_packed (hexagonal / fcc). Expectations: the run completes, energy is conserved to
//    round-off, nothing ever overlaps (brute-force check on the engine), and the pressure
//    measured from the collisions (profiles: kinetic + collisional virial) is finite, positive
//    and follows the equation of state of the phase:
//      solids (hexagonal 0.726 and 0.8, fcc 0.55): the cell (free-volume) theory
//        Z = P / (n T) = 1 / (1 - (phi / phi_cp)^(1/d)), exact as phi -> phi_cp (Z. W. Salsburg
//        & W. W. Wood, J. Chem. Phys. 37, 798 (1962)) and within ~10% of simulations at
//        phi / phi_cp ~ 0.75-0.9 (it neglects correlated cage motion); tolerance 15%;
//      fluid (0.407 from the cubic lattice, which melts at once: spheres freeze above 0.494):
//        Carnahan-Starling, Z = 1 + 4 phi chi, good to <1% in the fluid; tolerance 3%.
//    and Z grows with phi.
//  - above the densest packing the scene is refused with the reason.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/core/h5.hpp"
#include "libgran/core/kinetic_theory.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/run/run.hpp"
#include "libgran/scene/placement.hpp"
#include "tests/support/conservation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/contains.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

using testing::value;

void check_dilute(int d) {
    const std::string tag = fmt::format("dilute{}", d);
    const YAML::Node s = testing::run_yaml(fmt::format(R"(
dimension: {}
seed: 5
species: [{{name: a, count: 1000}}]
box: {{packing_fraction: 1.0e-4}}
observables: [{{type: temperatures}}, {{type: collision_statistics}}]
run: {{equilibration: 5, measurement: 60, sample_interval: 2}}
)",
                                                       d),
                                           tag);
    ASSERT_EQ(s["status"].as<std::string>(), "completed");
    const double T = value(s["observables"]["temperatures"]["T_mixture"]);
    const YAML::Node w = s["observables"]["collision_statistics"]["frequency_per_particle"];
    const double n = 1e-4 / theory::unit_ball_volume(d);
    const double expected =
        theory::enskog_collision_frequency(d, n, 1.0, theory::contact_value(d, 1e-4), T, 1.0);
    EXPECT_LT(testing::error(w) / value(w), 0.01) << "statistics too poor";
    EXPECT_NEAR(value(w) / expected, 1.0, 0.03);
    const double per_collision =
        s["performance"]["events"].as<double>() / s["performance"]["collisions"].as<double>();
    EXPECT_LT(per_collision, 2000) << "cell crossings per collision";
}

TEST(PackingExtremes, DisksAtPhi1em4CollideAtTheBoltzmannRate) {
    check_dilute(2);
}
TEST(PackingExtremes, SpheresAtPhi1em4CollideAtTheBoltzmannRate) {
    check_dilute(3);
}

struct DenseOutcome {
    double z = 0;         // P / (n T) in the middle of the box
    double p_enskog = 0;  // the fluid equation of state there, as P
    double p = 0;         // measured P (mean of the diagonal)
    double energy_drift = 0;
};

DenseOutcome run_dense(int d, double phi, const std::string& placement, int count,
                       const std::string& aspect) {
    const std::string tag = fmt::format("dense{}_{}", d, phi);
    const YAML::Node s =
        testing::run_yaml(fmt::format(R"(
dimension: {0}
seed: 1
species: [{{name: a, count: {3}}}]
box: {{packing_fraction: {1}, aspect: {4}}}
initial: {{placement: {2}}}
observables: [{{type: kinetic_energy}}, {{type: profiles, axis: {5}, bins: 4}}]
run: {{equilibration: 50, measurement: 500, sample_interval: 10}}
)",
                                      d, phi, placement, count, aspect, d == 2 ? "y" : "z"),
                          tag);
    EXPECT_EQ(s["status"].as<std::string>(), "completed");
    EXPECT_EQ(s["performance"]["overlap_collisions"].as<int>(), 0);
    const YAML::Node pr = s["observables"]["profiles"];
    DenseOutcome o;
    for (const char* c : {"xx", "yy", "zz"}) {
        if (d == 2 && std::string(c) == "zz") continue;
        o.p += value(pr[std::string("middle/pressure/P_") + c]) / d;
    }
    o.z = o.p / value(pr["middle/eos/P_ideal"]);
    o.p_enskog = value(pr["middle/eos/P_enskog"]);
    auto f = h5::File::open_read((testing::temp_dir() / (tag + ".h5")).string());
    const auto e = f.root().read_doubles("observables/kinetic_energy/energy_per_particle/value");
    for (double x : e) o.energy_drift = std::max(o.energy_drift, std::abs(x / e.front() - 1));
    EXPECT_TRUE(std::isfinite(o.p) && o.p > 0) << "P = " << o.p;
    EXPECT_LT(o.energy_drift, 1e-10);
    ::testing::Test::RecordProperty(tag + "_Z", fmt::format("{:.4f}", o.z));
    return o;
}

double cell_theory_z(int d, double phi) {
    return 1.0 / (1.0 - std::pow(phi / max_packing_fraction(d), 1.0 / d));
}

// 392 = 2 x 14 x 14 sites: a box of aspect sqrt(3) holds a perfect hexagonal lattice.
const std::string kHexAspect = "[1, 1.7320508075688772]";

TEST(PackingExtremes, HexagonalDisksAtPhi080And0726FollowTheCellTheory) {
    const double phi_a = 0.8, phi_b = 0.8 * max_packing_fraction(2);  // 0.7255
    const DenseOutcome a = run_dense(2, phi_a, "close_packed", 392, kHexAspect);
    const DenseOutcome b = run_dense(2, phi_b, "close_packed", 392, kHexAspect);
    EXPECT_NEAR(a.z / cell_theory_z(2, phi_a), 1.0, 0.15) << "Z = " << a.z;
    EXPECT_NEAR(b.z / cell_theory_z(2, phi_b), 1.0, 0.15) << "Z = " << b.z;
    EXPECT_GT(a.z, b.z);
}

TEST(PackingExtremes, FccSpheresAtPhi055FollowTheCellTheoryAndTheFluidAt0407Carnahan) {
    const double phi_a = 0.55, phi_b = 0.55 * max_packing_fraction(3);  // 0.4073
    const DenseOutcome a = run_dense(3, phi_a, "close_packed", 500, "[1, 1, 1]");
    const DenseOutcome b = run_dense(3, phi_b, "lattice", 512, "[1, 1, 1]");
    EXPECT_NEAR(a.z / cell_theory_z(3, phi_a), 1.0, 0.15) << "Z = " << a.z;
    EXPECT_NEAR(b.p / b.p_enskog, 1.0, 0.03)
        << "P = " << b.p << ", Carnahan-Starling " << b.p_enskog;
    EXPECT_GT(a.z, b.z);
}

// Brute force on the engine: no pair ever closer than its contact distance.
template <int D>
void check_dense_never_overlaps(double phi, std::size_t n, const Vec<D>& aspect) {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, 0.5, n});
    const ContactTable c = testing::contacts_of(t, "", D);
    const double volume = double(n) * theory::unit_ball_volume(D) / phi;
    Box<D> box;
    box.length = aspect * std::pow(volume / aspect.prod(), 1.0 / D);
    box.periodic.fill(true);
    Rng rng = make_rng(3, Stream::Placement);
    auto p = place_close_packed<D>(box, t, rng);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    EXPECT_GT(testing::closest_approach<D>(p, t, box), 1.0);
    const double e0 = testing::translational_energy<D>(p, t);
    EventDrivenEngine<D> engine(box, t, c, p, EngineSettings{});
    for (int k = 1; k <= 4; ++k) {
        engine.advance(kInf, std::uint64_t(k) * 25 * n);
        engine.synchronize();
        const auto& q = engine.particles();
        EXPECT_GT(testing::closest_approach<D>(q, t, box), 1 - 1e-9) << "sample " << k;
        EXPECT_NEAR(testing::translational_energy<D>(q, t) / e0, 1.0, 1e-10);
    }
}

TEST(PackingExtremes, DisksAtPhi080NeverOverlap) {
    check_dense_never_overlaps<2>(0.8, 392, Vec<2>(1, std::sqrt(3.0)));
}
TEST(PackingExtremes, SpheresAtPhi055NeverOverlap) {
    check_dense_never_overlaps<3>(0.55, 500, Vec<3>(1, 1, 1));
}

std::string refusal(int d, double phi, const std::string& placement) {
    const std::string yaml = fmt::format(
        "dimension: {}\nspecies: [{{name: a, count: 400}}]\nbox: {{packing_fraction: {}}}\n"
        "initial: {{placement: {}}}\nrun: {{measurement: 1}}\n",
        d, phi, placement);
    try {
        check_scene(parse_scene(YAML::Load(yaml), "dense.yaml"));
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

TEST(PackingExtremes, AboveTheDensestPackingTheSceneIsRefused) {
    const std::string m2 = refusal(2, 0.91, "close_packed");
    EXPECT_TRUE(testing::contains(m2, "dense.yaml:"));
    EXPECT_TRUE(testing::contains(m2, "exceeds the densest packing 0.9069 of disks"));
    EXPECT_TRUE(testing::contains(refusal(3, 0.75, "close_packed"),
                                  "exceeds the densest packing 0.7405 of spheres"));
}

TEST(PackingExtremes, PlacementsThatCannotReachADensityNameTheOneThatCan) {
    const std::string random = refusal(2, 0.8, "random");
    EXPECT_TRUE(testing::contains(random, "random placement failed"));
    EXPECT_TRUE(testing::contains(random, "close_packed (up to 0.9069)"));
    const std::string lattice = refusal(3, 0.55, "lattice");
    EXPECT_TRUE(testing::contains(lattice, "lattice placement failed"));
    EXPECT_TRUE(testing::contains(lattice, "close_packed"));
    EXPECT_EQ(refusal(2, 0.8, "close_packed"), "");
    EXPECT_EQ(refusal(3, 0.55, "close_packed"), "");
}

}  // namespace
}  // namespace gran
