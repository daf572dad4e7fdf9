// Scenes on the soft-sphere DEM engine (engine.type: dem, libgran/run.cpp): the same scene file
// runs on either engine; what the dem engine cannot run is refused with file, line and key; the
// physics of a run (momentum balance at the base, T_z ~ V_p^2 without gravity, Bhateja et al.
// 2016 Fig. 6) and the agreement of both engines on a stiff frictionless bed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "libgran/run/run.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/study/study_fit.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

double value(const YAML::Node& n) {
    return n["value"].as<double>();
}
double error(const YAML::Node& n) {
    return n["error"].as<double>();
}

// The 3D canonical bed of Bhateja et al. 2016 (5d x 5d periodic, 100 grains, A = d, sinusoid,
// e_p = e_w = 0.9), with `extra` appended to the contact law's keys and a tall box (open top in
// effect, the top of the box elastic).
std::string bed3d(double frequency, const std::string& contact_extra, double gravity, double height,
                  const std::string& drivers_extra, double measurement) {
    return fmt::format(R"(
dimension: 3
seed: 4
gravity: [0, 0, {g}]
box: {{lengths: [5, 5, {h}], periodic: [true, true, false]}}
species: [{{name: grain, count: 100, mass: 1, diameter: 1, inertia_factor: 0.4}}]
interactions:
  {{law: linear_dashpot, restitution: 0.9, stiffness: 2e5{extra},
   pairs: [{{between: [grain, box], restitution: 1}}]}}
engine: {{type: dem}}
drivers:
  - {{type: vibrating_wall, axis: z, waveform: sinusoid, amplitude: 1, frequency: {f}}}
{drivers}
observables:
  - {{type: local_temperature}}
  - {{type: wall_pressure, axis: z}}
  - {{type: temperatures}}
run: {{unit: time, equilibration: {eq}, measurement: {m}, sample_interval: {si}}}
)",
                       fmt::arg("g", gravity), fmt::arg("h", height),
                       fmt::arg("extra", contact_extra), fmt::arg("f", frequency),
                       fmt::arg("drivers", drivers_extra), fmt::arg("eq", 20 / frequency),
                       fmt::arg("m", measurement / frequency),
                       // incommensurate with the period: every drive phase is sampled
                       fmt::arg("si", 0.1373 / frequency));
}

TEST(DemRun, EngineKeyRunsTheSceneOnTheDemEngineAndReportsIsolatedCollisions) {
    const YAML::Node s = testing::run_yaml(bed3d(0.5, "", -1, 40, "", 20), "dem");
    const YAML::Node perf = s["performance"];
    EXPECT_EQ(perf["engine"].as<std::string>(), "dem");
    EXPECT_NEAR(perf["dt_over_tc"].as<double>(), 0.02, 1e-12);  // default dt = t_c / 50
    EXPECT_GT(perf["steps"].as<double>(), 1e5);
    // Restitution achieved on the engine itself at this dt: within 0.5% of the request.
    const YAML::Node iso = perf["isolated_collisions"];
    ASSERT_TRUE(iso["grain-grain"]);
    ASSERT_TRUE(iso["grain-vibrating_wall"]);  // the vibrating base
    ASSERT_TRUE(iso["grain-box"]);             // the static elastic top of the box
    EXPECT_EQ(iso["grain-vibrating_wall"]["requested_restitution"].as<double>(), 0.9);
    EXPECT_EQ(iso["grain-box"]["requested_restitution"].as<double>(), 1.0);
    for (const char* k : {"grain-grain", "grain-vibrating_wall", "grain-box"}) {
        const double e = iso[k]["restitution"].as<double>();
        const double want = iso[k]["requested_restitution"].as<double>();
        EXPECT_NEAR(e / want, 1.0, 0.005) << k;
        EXPECT_NEAR(
            iso[k]["measured_contact_time"].as<double>() / iso[k]["contact_time"].as<double>(), 1.0,
            0.01)
            << k;
    }
    // Temperature conventions: the plain average of local_temperature is the paper's m <c^2> / 2
    // about the centre-of-mass velocity, half the temperatures observable's m <c^2>.
    const YAML::Node lt = s["observables"]["local_temperature"];
    EXPECT_GT(value(lt["T_z"]), 0);
    EXPECT_NEAR(value(lt["T_z_plain"]),
                0.5 * value(s["observables"]["temperatures"]["species"]["grain"]["T_z"]),
                1e-12 * value(lt["T_z_plain"]));
    // Fluctuations about the local (slab, drive phase) mean are smaller than about the bed's
    // centre-of-mass velocity, which counts the layers' collective motion too.
    EXPECT_LT(value(lt["T_z"]), value(lt["T_z_plain"]));
}

// Momentum balance: averaged over the measurement, the base carries the weight of the bed (the
// top wall is never reached), sum F_n dt / (time area) = N m g / area.
TEST(DemRun, VibratingBaseCarriesTheWeightOfTheBed) {
    const YAML::Node s = testing::run_yaml(
        bed3d(0.5, ", friction: 0.4, tangential_damping_ratio: 1", -1, 40, "", 100), "bed");
    const YAML::Node wp = s["observables"]["wall_pressure"];
    const double weight = wp["weight_per_area"].as<double>();
    EXPECT_DOUBLE_EQ(weight, 100.0 / 25.0);
    const double p = value(wp["lower"]["pressure"]);
    const double err = error(wp["lower"]["pressure"]);
    EXPECT_LT(err, 0.03 * weight);
    EXPECT_NEAR(p, weight, 3 * err + 0.01 * weight) << "base pressure " << p << " +- " << err;
    EXPECT_EQ(value(wp["upper"]["collision_frequency"]), 0.0);
}

// Bhateja et al. 2016, Fig. 6 and Sec. IV: without gravity, under a lid 10d above the base, the
// only time scale is d / V_p, so T_z ~ V_p^2 whatever the other parameters. V_p = 2 pi f A from 1.6
// to 6.3 d per unit time; fitted exponent within 0.05 of 2. Smooth grains: with friction (c_t =
// c_n) the grains cluster under the lid and the same precision needs runs ten times longer
// (studies/bhateja-2016 runs those).
TEST(DemRun, WithoutGravityUnderALidTzGrowsAsTheSquareOfThePeakVelocity) {
    std::vector<double> vp, tz;
    for (double f : {0.25, 0.5, 1.0}) {
        // Box height: the base sweeps [0, 2A], the lid 10d above the base's mean position.
        const YAML::Node s = testing::run_yaml(
            bed3d(f, "", 0, 11, "  - {type: static_wall, axis: z, side: upper}", 100),
            fmt::format("lid{}", f));
        const YAML::Node lt = s["observables"]["local_temperature"];
        vp.push_back(lt["peak_velocity"].as<double>());
        tz.push_back(value(lt["T_z"]));
        EXPECT_LT(error(lt["T_z"]), 0.03 * value(lt["T_z"]));
    }
    const PowerLawFit fit = fit_power_law(vp, tz, 0.25);
    ASSERT_TRUE(fit.valid);
    RecordProperty("alpha", fmt::format("{:.4f}", fit.theta));
    EXPECT_NEAR(fit.theta, 2.0, 0.05) << "T_z: " << tz[0] << " " << tz[1] << " " << tz[2];
}

// The same frictionless scene with constant restitution on both engines: a vibrated 2D binary
// bed (m_heavy = 2 m_light, 20 + 20 disks, e_p = e_w = 0.9, W = (2 pi 0.7)^2 = 19). With
// k_n = 2e5 m g / d (contacts last 0.5% of sqrt(d/g); largest overlap about 1% of d) the
// temperature ratio and the volume-averaged T_y agree within their error bars (3 sigma).
TEST(DemRun, BothEnginesGiveTheSameTemperatureRatioAndTzOnAStiffFrictionlessBed) {
    auto scene = [](const std::string& engine) {
        return fmt::format(R"(
dimension: 2
seed: 5
gravity: [0, -1]
box: {{lengths: [10, 60], periodic: [true, false]}}
species:
  - {{name: light, count: 20, mass: 1, diameter: 1}}
  - {{name: heavy, count: 20, mass: 2, diameter: 1}}
interactions:
  {{law: linear_dashpot, restitution: 0.9, stiffness: 2e5,
   pairs: [{{between: [light, box], restitution: 1}}, {{between: [heavy, box], restitution: 1}}]}}
engine: {{type: {}}}
drivers:
  - {{type: vibrating_wall, axis: y, waveform: sinusoid, amplitude: 1, frequency: 0.7}}
observables:
  - {{type: temperatures, reference_species: light}}
  - {{type: local_temperature}}
run: {{unit: time, equilibration: 50, measurement: 3000, sample_interval: 0.0913}}
)",
                           engine);
    };
    const YAML::Node ed = testing::run_yaml(scene("event_driven"), "ed")["observables"];
    const YAML::Node dem = testing::run_yaml(scene("dem"), "dem")["observables"];
    auto agree = [](const YAML::Node& a, const YAML::Node& b, const char* what) {
        const double sigma = std::hypot(error(a), error(b));
        EXPECT_LT(sigma, 0.03 * value(a)) << what;
        EXPECT_NEAR(value(a), value(b), 3 * sigma)
            << what << ": event-driven " << value(a) << " dem " << value(b);
    };
    agree(ed["temperatures"]["ratios"]["heavy_over_light"]["gamma"],
          dem["temperatures"]["ratios"]["heavy_over_light"]["gamma"], "T_heavy / T_light");
    agree(ed["local_temperature"]["T_y_volume"], dem["local_temperature"]["T_y_volume"],
          "T_y (volume average)");
    agree(ed["local_temperature"]["T_y"], dem["local_temperature"]["T_y"],
          "T_y (particle average)");
}

// The sawtooth wall of Barrat & Trizac 2002 is the limit A -> 0 at fixed v0 = 2 A f of a real
// sawtooth; the dem engine moves the real one. With the contact much shorter than the period
// (t_c = 0.007 << 2 A / v0 = 0.4) and A well below the mean free path, the vibrated gas (100 disks,
// alpha = 0.9, walls at both ends) has the event-driven temperature within 3 sigma.
TEST(DemRun, RealSawtoothWallGivesTheTemperatureOfTheEventDrivenSawtoothLimit) {
    auto scene = [](const std::string& engine) {
        return fmt::format(R"(
dimension: 2
seed: 3
box: {{lengths: [20, 20], periodic: [true, false]}}
species: [{{name: a, count: 100}}]
interactions: {{law: linear_dashpot, restitution: 0.9, stiffness: 2e5, walls: {{restitution: 1}}}}
engine: {{type: {}}}
drivers: [{{type: vibrating_wall, axis: y, side: both, waveform: sawtooth, amplitude: 0.2, frequency: 2.5}}]
observables: [{{type: temperatures}}]
run: {{unit: time, equilibration: 50, measurement: 600, sample_interval: 0.5}}
)",
                           engine);
    };
    const YAML::Node ed = testing::run_yaml(scene("event_driven"), "ed")["observables"];
    const YAML::Node dem = testing::run_yaml(scene("dem"), "dem")["observables"];
    const YAML::Node a = ed["temperatures"]["T_mixture"], b = dem["temperatures"]["T_mixture"];
    const double sigma = std::hypot(error(a), error(b));
    EXPECT_LT(sigma, 0.02 * value(a));
    EXPECT_NEAR(value(a), value(b), 3 * sigma)
        << "event-driven " << value(a) << " dem " << value(b);
}

// What the dem engine cannot run is refused before running, naming file, line and key.
TEST(DemRun, RefusesWhatTheDemEngineCannotRunNamingFileLineAndKey) {
    const std::string base = R"(dimension: 2
seed: 1
gravity: [0, -1]
box: {lengths: [10, 30], periodic: [true, false]}
species: [{name: a, count: 20}]
)";
    struct Case {
        std::string body, location, needle;
    };
    const std::string soft = "interactions: {law: linear_dashpot, stiffness: 1e4}\n";
    const std::vector<Case> cases{
        {soft + "engine: {type: dem}\ndrivers: [{type: thermal_wall, axis: y, temperature: 1}]\n"
                "run: {unit: time, measurement: 1}\n",
         "bad.yaml:8:", "not available on the dem engine"},
        {soft + "engine: {type: dem}\ndrivers: [{type: vibrating_wall, axis: y, waveform: "
                "sawtooth, velocity: 1}]\nrun: {unit: time, measurement: 1}\n",
         "waveform", "no wall position"},
        {soft + "engine: {type: dem}\nobservables: [{type: restitution_statistics}]\n"
                "run: {unit: time, measurement: 1}\n",
         "bad.yaml:8:", "binary collision records"},
        {soft + "engine: {type: dem, dt_fraction: 0.3}\nrun: {unit: time, measurement: 1}\n",
         "engine.dt_fraction", "5 steps per contact"},
        {soft + "engine: {type: dem, dt: 0.01}\nrun: {unit: time, measurement: 1}\n", "engine",
         "exceeds t_c / 5"},
        {"interactions: {law: linear_dashpot}\nengine: {type: dem}\nrun: {unit: time, "
         "measurement: 1}\n",
         "interactions.stiffness", "`contact_time`"},
        {soft + "engine: {type: dem}\nrun: {measurement: 1}\n", "run.unit", "schedules by time"},
        {"interactions: {alpha: 0.9, beta: 0.5}\nengine: {type: dem}\nrun: {unit: time, "
         "measurement: 1}\n",
         "interactions", "linear_dashpot"},
        {"engine: {type: dem, stiffness: 1e4}\nrun: {unit: time, measurement: 1}\n",
         "engine.stiffness", "interactions: {law: linear_dashpot, stiffness:"},
    };
    for (const auto& c : cases) {
        try {
            check_scene(parse_scene(YAML::Load(base + c.body), "bad.yaml"));
            ADD_FAILURE() << "accepted:\n" << c.body;
        } catch (const SceneError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(c.location), std::string::npos) << msg;
            EXPECT_NE(msg.find(c.needle), std::string::npos) << msg;
        }
    }
}

}  // namespace
}  // namespace gran
