// Extremes of the tangential restitution beta (issue 6), event-driven engine:
//  - beta = +1 with alpha = 1 (perfectly rough, elastic): the collision reverses the relative
//    velocity of the contact points; translational plus rotational energy is conserved exactly
//    (to round-off, 1e-10 relative after 2e5 collisions) while energy flows between the two;
//  - beta = -1 (smooth): no tangential impulse, so angular velocities are never touched (bitwise).
// DEM: roughness is Coulomb friction there; a scene with beta != -1 on the dem engine is refused
// with a message that says so.
#include <gtest/gtest.h>

#include <cmath>

#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/run/run.hpp"
#include "libgran/scene/placement.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/conservation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/contains.hpp"

namespace gran {
namespace {

template <int D>
Box<D> periodic_box(const SpeciesTable& t, double phi) {
    double v = 0;
    for (const auto& s : t.species)
        v += double(s.count) * (D == 2 ? M_PI / 4 : M_PI / 6) * std::pow(s.diameter, D);
    Box<D> box;
    box.length = Vec<D>::Constant(std::pow(v / phi, 1.0 / D));
    box.periodic.fill(true);
    return box;
}

template <int D>
void check_perfectly_rough_elastic() {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, D == 2 ? 0.5 : 0.4, 400});
    const ContactTable c = testing::contacts_of(t, "{beta: 1.0}", D);
    const Box<D> box = periodic_box<D>(t, 0.2);
    Rng rng = make_rng(21, Stream::Placement);
    auto p = place_random<D>(box, t, rng);
    testing::allocate_rotation<D>(p, c);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    // Start with no spin: the rough collisions must feed rotation from translation.
    for (auto& w : p.w) w = ang_zero<D>();
    const double e0 = testing::translational_energy<D>(p, t);
    EventDrivenEngine<D> engine(box, t, c, p, EngineSettings{});
    engine.advance(kInf, 200000);
    engine.synchronize();
    const auto& q = engine.particles();
    const double tr = testing::translational_energy<D>(q, t),
                 rot = testing::rotational_energy<D>(q, t);
    EXPECT_NEAR((tr + rot) / e0, 1.0, 1e-10);
    // Equipartition between the d translational and the 1 (2D) or 3 (3D) rotational degrees of
    // freedom is reached in a few collisions per particle; here just: a large share was exchanged.
    EXPECT_GT(rot / e0, 0.1);
}

TEST(RoughnessExtremes, PerfectlyRoughElasticDisksConserveTranslationalPlusRotationalEnergy) {
    check_perfectly_rough_elastic<2>();
}
TEST(RoughnessExtremes, PerfectlyRoughElasticSpheresConserveTranslationalPlusRotationalEnergy) {
    check_perfectly_rough_elastic<3>();
}

// Species a collides smoothly with everyone (beta = -1), b-b pairs are perfectly rough: the
// angular velocities of a must come out bitwise unchanged, those of b must change.
template <int D>
void check_smooth_leaves_spin_alone() {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, D == 2 ? 0.5 : 0.4, 200});
    t.species.push_back(Species{"b", 1.0, 1.0, D == 2 ? 0.5 : 0.4, 200});
    const ContactTable c =
        testing::contacts_of(t, "{alpha: 0.9, pairs: [{between: [b, b], beta: 1.0}]}", D);
    const Box<D> box = periodic_box<D>(t, 0.2);
    Rng rng = make_rng(22, Stream::Placement);
    auto p = place_random<D>(box, t, rng);
    testing::allocate_rotation<D>(p, c);
    maxwellian_velocities<D>(p, t, 1.0, rng);
    ASSERT_TRUE(p.rotating());
    EventDrivenEngine<D> engine(box, t, c, p, EngineSettings{});
    engine.advance(kInf, 50000);
    engine.synchronize();
    const auto& q = engine.particles();
    std::size_t a_same = 0, b_changed = 0;
    for (std::size_t k = 0; k < q.size(); ++k) {
        const std::uint32_t i = engine.ids()[k];  // storage is re-sorted; ids map back
        const bool same = ang_squared<D>(q.w[k] - p.w[i]) == 0.0;
        if (q.species[k] == 0) a_same += same ? 1 : 0;
        if (q.species[k] == 1) b_changed += same ? 0 : 1;
    }
    EXPECT_EQ(a_same, 200u) << "smooth collisions changed some angular velocities";
    EXPECT_GT(b_changed, 190u) << "rough collisions should have changed almost every b spin";
}

TEST(RoughnessExtremes, SmoothCollisionsNeverTouchAngularVelocitiesOfDisks) {
    check_smooth_leaves_spin_alone<2>();
}
TEST(RoughnessExtremes, SmoothCollisionsNeverTouchAngularVelocitiesOfSpheres) {
    check_smooth_leaves_spin_alone<3>();
}

TEST(RoughnessExtremes, DemRefusesTangentialRestitutionAndPointsToFriction) {
    for (const char* beta : {"1", "-0.5"}) {
        const std::string yaml = std::string(R"(
dimension: 2
species: [{name: a, count: 10}]
interactions: {law: linear_dashpot, restitution: 0.9, stiffness: 1e5, beta: )") +
                                 beta + R"(}
box: {packing_fraction: 0.1}
engine: {type: dem}
run: {unit: time, measurement: 1}
)";
        try {
            check_scene(parse_scene(YAML::Load(yaml), "rough_dem.yaml"));
            ADD_FAILURE() << "beta = " << beta << " was accepted on the dem engine";
        } catch (const SceneError& e) {
            EXPECT_TRUE(testing::contains(e.what(), "rough_dem.yaml"));
            EXPECT_TRUE(testing::contains(e.what(), "interactions.beta"));
            EXPECT_TRUE(testing::contains(e.what(), "friction"));
        }
    }
}

}  // namespace
}  // namespace gran
