// The dem cost estimate (libgran/run/dem_cost.hpp): particle-steps by hand for a small scene, the
// steps the engine then takes, and the runs that could never finish refused at the key that makes
// them so.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "libgran/core/scene_error.hpp"
#include "libgran/run/dem_cost.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {
namespace {

// 10 disks of mass 1 and diameter 1 at T = 1, periodic (no walls), contacts lasting 0.01 (the
// default dt_fraction 0.02 gives dt = 2e-4), 1 + 2 time units: 10 x 3 / 2e-4 = 1.5e5
// particle-steps. The arguments are keys of the sections `interactions`, `engine` and `run`.
const std::string kShortRun = "measurement: 2, sample_interval: 0.5";
Scene small_scene(const std::string& interactions = "contact_time: 0.01",
                  const std::string& engine = "", const std::string& run = kShortRun) {
    return parse_scene(YAML::Load(R"(
dimension: 2
seed: 3
species: [{name: a, count: 10}]
interactions: {law: linear_dashpot, restitution: 0.9, )" +
                                  interactions + R"(}
box: {packing_fraction: 0.1}
engine: {type: dem)" + engine + R"(}
run: {unit: time, equilibration: 1, )" +
                                  run + R"(}
)"),
                       "small.yaml");
}

TEST(DemCost, SmallSceneCostsParticlesTimesRunOverTimeStep) {
    const DemEstimate e = estimate_particle_steps(small_scene());
    // The contact time goes through the stiffness and back (k_n from t_c, t_c from k_n): equal to
    // rounding, 1e-12 relative.
    EXPECT_NEAR(e.contact_time, 0.01, 1e-14);
    EXPECT_NEAR(e.dt, 2e-4, 2e-16);
    EXPECT_DOUBLE_EQ(e.simulated_time, 3.0);
    EXPECT_DOUBLE_EQ(e.particles, 10.0);
    EXPECT_NEAR(e.steps(), 15000.0, 15000.0 * 1e-12);
    EXPECT_NEAR(e.particle_steps(), 1.5e5, 1.5e5 * 1e-12);
    EXPECT_DOUBLE_EQ(e.grain_time, 1.0);  // diameter 1 at the thermal speed sqrt(T / m) = 1
    const RunCost cost = run_cost(e);
    EXPECT_EQ(cost.unit, "particle-steps");
    EXPECT_DOUBLE_EQ(cost.per_runner_work, 10.0);  // a step of the runner moves 10 particles
    EXPECT_NE(cost.text.find("expected cost: about 1.5e+05 particle-steps (10 particles x 1.5e+04 "
                             "steps of dt = 0.0002, t_c / 50)"),
              std::string::npos)
        << cost.text;
}

TEST(DemCost, EngineTakesTheEstimatedSteps) {
    const Scene sc = small_scene();
    const DemEstimate e = estimate_particle_steps(sc);
    Simulation sim(sc);
    sim.advance({.time = e.simulated_time});
    // Whole steps while now() < t: the last one may end up to one step past the target.
    EXPECT_NEAR(double(sim.work()), e.steps(), 1.0);
    EXPECT_EQ(std::string(sim.work_unit()), "steps");
}

// The message of the refusal of a scene, "" when it is accepted.
std::string refusal(const std::string& interactions, const std::string& engine,
                    const std::string& run) {
    try {
        small_scene(interactions, engine, run);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

TEST(DemCost, StiffContactsAreRefusedNamingTheStiffness) {
    // k_n = 1e30, m_eff = 1/2: t_c ~ 2.2e-15, 50 steps per contact: ~7e16 steps of 10 disks.
    const std::string why = refusal("stiffness: 1.0e+30", "", kShortRun);
    EXPECT_NE(why.find("small.yaml:5:"), std::string::npos) << why;
    EXPECT_NE(why.find("lower interactions.stiffness"), std::string::npos) << why;
    EXPECT_NE(why.find("more than 1e+15: it could not finish"), std::string::npos) << why;
}

TEST(DemCost, TinyTimeStepFractionIsRefusedNamingIt) {
    // dt = 1e-12 x 0.01: 3e14 steps of 10 disks.
    const std::string why = refusal("contact_time: 0.01", ", dt_fraction: 1.0e-12", kShortRun);
    EXPECT_NE(why.find("small.yaml:7:"), std::string::npos) << why;
    EXPECT_NE(why.find("raise engine.dt_fraction"), std::string::npos) << why;
}

TEST(DemCost, TinyExplicitTimeStepIsRefusedNamingIt) {
    const std::string why = refusal("contact_time: 0.01", ", dt: 1.0e-14", kShortRun);
    EXPECT_NE(why.find("engine.dt:"), std::string::npos) << why;
    EXPECT_NE(why.find("raise engine.dt (at most t_c / 5"), std::string::npos) << why;
}

TEST(DemCost, EndlessRunIsRefusedNamingTheMeasurement) {
    // 2.2e10 time units: 1.1e14 steps at dt = 2e-4, 1.1e15 particle-steps.
    const std::string why =
        refusal("contact_time: 0.01", "", "measurement: 2.2e+10, sample_interval: 1.0e+3");
    EXPECT_NE(why.find("run.measurement:"), std::string::npos) << why;
    EXPECT_NE(why.find("shorten run.measurement"), std::string::npos) << why;
}

TEST(DemCost, RunJustBelowTheBoundIsAccepted) {
    // 1.8e10 time units: 9e13 steps of 10 disks, 9e14 particle-steps.
    EXPECT_EQ(refusal("contact_time: 0.01", "", "measurement: 1.8e+10, sample_interval: 1.0e+3"),
              "");
}

TEST(DemCost, ManyParticlesAreRefusedNamingTheSpecies) {
    // The blame alone, on the small scene's estimate with 1e11 particles rather than a scene of
    // 1e11 grains: 1e11 x 1.5e4 steps.
    const Scene sc = small_scene();
    DemEstimate e = estimate_particle_steps(sc);
    e.particles = 1e11;
    try {
        refuse_endless_run(sc, e);
        FAIL() << "1.5e15 particle-steps were accepted";
    } catch (const SceneError& err) {
        const std::string why = err.what();
        EXPECT_NE(why.find("small.yaml:4:"), std::string::npos) << why;
        EXPECT_NE(why.find("species: this run would need about 1.5e+15 particle-steps"),
                  std::string::npos)
            << why;
        EXPECT_NE(why.find("use fewer particles"), std::string::npos) << why;
    }
}

}  // namespace
}  // namespace gran
