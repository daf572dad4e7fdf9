// Interaction laws are plugins (issue 12): the two laws below are defined and registered in this
// one file, and run on the engines with no other edit anywhere: a hard-sphere law on the
// event-driven engine and a soft-contact law on the DEM engine, both through the scene path.
//
//   test_speed_restitution  hard spheres with e(v) = 1 / (1 + v / v_s), v the normal impact speed
//   test_hookean_spring     an undamped linear spring: e = 1, t_c = pi sqrt(m_eff / k)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "libgran/engines/register_law.hpp"
#include "libgran/run/simulation.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

struct TestSpeedRestitution {
    struct Pair {
        double v_s = 1;
    };
    static constexpr bool impact_dependent = true;
    static Pair resolve(const Params& p, const ContactPartner&, const ContactPartner&,
                        const LawContext&) {
        return {p.real("v_s")};
    }
    static double normal_restitution(const Pair& c, double v) {
        return 1.0 / (1.0 + std::fabs(v) / c.v_s);
    }
    static double tangential_restitution(const Pair&) { return -1.0; }
    static double nominal_restitution(const Pair&) { return 0.5; }
    static bool rotates(const Pair&) { return false; }
};

const bool hard_registered = register_law<TestSpeedRestitution>(
    "test_speed_restitution", "test law: e(v) = 1 / (1 + v / v_s)",
    {real("v_s", "1", "velocity", "speed at which e = 1/2", 0, 1e308, true)});

struct TestHookeanSpring {
    struct Pair {
        double k = 1;
        double duration = 0;
    };
    static constexpr bool history = false;
    static Pair resolve(const Params& p, const ContactPartner& a, const ContactPartner& b,
                        const LawContext&) {
        const double m_eff = b.wall ? a.mass : a.mass * b.mass / (a.mass + b.mass);
        return {p.real("k"), std::numbers::pi * std::sqrt(m_eff / p.real("k"))};
    }
    template <int D>
    static ContactForce<D> force(const Pair& c, double delta, const Vec<D>& n, const Vec<D>&,
                                 double, double, Vec<D>&) {
        ContactForce<D> f;
        f.f_n = c.k * delta;
        f.force = f.f_n * n;
        f.torque_i = f.torque_j = ang_zero<D>();
        return f;
    }
    static double elastic_energy(const Pair& c, double delta, double) {
        return 0.5 * c.k * delta * delta;
    }
    static double duration(const Pair& c) { return c.duration; }
    static double restitution(const Pair&) { return 1.0; }
    static double nominal_restitution(const Pair&) { return 1.0; }
    static bool rotates(const Pair&) { return false; }
};

const bool soft_registered = register_law<TestHookeanSpring>(
    "test_hookean_spring", "test law: undamped linear spring",
    {real("k", "", "mass/time^2", "spring constant", 0, 1e308, true)});

TEST(LawPlugin, LawsDefinedInOneTestFileAreRegistered) {
    EXPECT_TRUE(hard_registered);
    EXPECT_TRUE(soft_registered);
    EXPECT_NE(LawRegistry::instance().find("test_speed_restitution"), nullptr);
    EXPECT_NE(LawRegistry::instance().find("test_hookean_spring"), nullptr);
}

// Head-on collision at relative speed v = 3 v_s on the event-driven engine: the relative velocity
// after is -e(v) v = -v / 4 (the collision kernel of the engine with this law's restitution).
TEST(LawPlugin, HardSphereTestLawRunsOnTheEventDrivenEngineWithItsRestitution) {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, 0.5, 2});
    const ContactTable c = testing::contacts_of(t, "{law: test_speed_restitution, v_s: 2}", 2);
    Box<2> box;
    box.length = Vec<2>(50, 50);
    box.periodic = {true, true};
    Particles<2> p;
    p.resize(2, false);
    p.r = {Vec<2>(10, 25), Vec<2>(20, 25)};
    p.v = {Vec<2>(3.0, 0), Vec<2>(-3.0, 0)};  // v = 6 = 3 v_s
    EventDrivenEngine<2> e(box, t, c, std::move(p), EngineSettings{});
    e.advance(kInf, 1);
    e.synchronize();
    const auto& q = e.particles();
    // Storage order may differ from placement order: the relative speed is what counts.
    EXPECT_NEAR(std::abs(q.v[0][0] - q.v[1][0]), 6.0 / 4.0, 1e-14);
}

// The same law through a scene file, `gran run`'s path: a free-cooling gas loses energy at every
// collision, faster while it is hot (e falls with the impact speed), and the resolved scene keeps
// the law and its key.
TEST(LawPlugin, HardSphereTestLawRunsThroughASceneOnTheSimulation) {
    Simulation sim(parse_scene(YAML::Load(R"(
dimension: 2
seed: 3
species: [{name: a, count: 200}]
interactions: {law: test_speed_restitution, v_s: 0.5}
box: {packing_fraction: 0.1}
run: {measurement: 10}
)"),
                               "plugin.yaml"));
    EXPECT_EQ(sim.scene().resolved["interactions"]["law"].as<std::string>(),
              "test_speed_restitution");
    EXPECT_EQ(sim.scene().resolved["interactions"]["v_s"].as<double>(), 0.5);
    const auto energy = [&] {
        double e = 0;
        for (double v : sim.velocities()) e += 0.5 * v * v;
        return e;
    };
    const double e0 = energy();
    sim.advance({.collisions = 2000});
    const double e1 = energy();
    sim.advance({.collisions = 2000});
    const double e2 = energy();
    EXPECT_EQ(sim.collisions(), 4000u);
    EXPECT_LT(e1, e0);
    EXPECT_LT(e2, e1);
    EXPECT_LT(e1 / e0, e2 / e1) << "cooling should slow as e(v) rises towards 1";
}

// The soft test law on the DEM engine, through a scene: the isolated test collision of the run
// has e = 1 and the law's closed-form duration pi sqrt(m_eff / k), and the gas keeps its kinetic
// energy: 3 T / 2 per degree of freedom left once the total momentum is removed, 3 T (N - 1) /
// (2 N), less what the springs hold (about omega t_c ~ 0.3 % at this stiffness).
TEST(LawPlugin, SoftContactTestLawRunsOnTheDemEngine) {
    const YAML::Node s = testing::run_yaml(R"(
dimension: 3
seed: 4
species: [{name: a, count: 60}]
interactions: {law: test_hookean_spring, k: 1.0e+6}
box: {packing_fraction: 0.1}
engine: {type: dem, dt_fraction: 0.01}
observables: [{type: kinetic_energy}]
run: {unit: time, measurement: 2, sample_interval: 0.1}
)",
                                           "hookean");
    ASSERT_EQ(s["status"].as<std::string>(), "completed");
    const YAML::Node iso = s["performance"]["isolated_collisions"]["a-a"];
    EXPECT_NEAR(iso["restitution"].as<double>(), 1.0, 1e-3);
    EXPECT_NEAR(iso["contact_time"].as<double>(), std::numbers::pi * std::sqrt(0.5 / 1e6), 1e-12);
    EXPECT_NEAR(iso["measured_contact_time"].as<double>() / iso["contact_time"].as<double>(), 1,
                0.02);
    EXPECT_GT(s["performance"]["contacts"].as<double>(), 20);
    EXPECT_NEAR(testing::value(s["observables"]["kinetic_energy"]["mean_energy_per_particle"]),
                1.5 * 59.0 / 60.0, 0.005);
}

}  // namespace
}  // namespace gran
