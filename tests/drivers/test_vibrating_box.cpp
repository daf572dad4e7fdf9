// The `vibrating_box` driver (drivers/vibrating_box.cpp): the whole box moves along one axis, its
// side walls along their normal with one displacement, its floor and lid in their own plane.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>
#include <string>

#include "libgran/core/scene_error.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

constexpr double kPi = std::numbers::pi;

// 2D box 12 x 10, both axes bounded, shaken along x with A = 0.5, f = 0.3: 40 disks (a DEM law
// whose hard limit the event-driven engine runs).
std::string shaken_box(const std::string& engine) {
    return fmt::format(R"(
dimension: 2
seed: 4
box: {{lengths: [12, 10], periodic: [false, false]}}
species: [{{name: g, count: 40}}]
interactions: {{law: linear_dashpot, restitution: 0.9, contact_time: 0.002}}
engine: {{type: {}}}
drivers: [{{type: vibrating_box, axis: x, amplitude: 0.5, frequency: 0.3}}]
run: {{unit: time, measurement: 10, sample_interval: 1}}
)",
                       engine);
}

// The walls normal to x follow x_lower = A - A cos(omega t) and x_upper = L - A - A cos(omega t)
// (one displacement: the inner width stays L - 2 A); the floor and lid stay at 0 and 10; every
// disk stays between the moving walls. Both engines, at 25 times over three periods.
TEST(VibratingBox, SideWallsMoveTogetherAndTheFloorAndLidStayOnBothEngines) {
    const double A = 0.5, omega = 2 * kPi * 0.3, L = 12;
    for (const char* engine : {"event_driven", "dem"}) {
        Simulation sim(parse_scene(YAML::Load(shaken_box(engine)), "box.yaml"));
        const auto& view = sim.state<2>().runner->view();
        for (int k = 1; k <= 25; ++k) {
            const double t = k * 10.0 / 25;
            sim.advance({.time = t});
            const double shift = -A * std::cos(omega * t);
            EXPECT_NEAR(view.wall_position(0, t), A + shift, 1e-12) << engine;
            EXPECT_NEAR(view.wall_position(1, t), L - A + shift, 1e-12) << engine;
            EXPECT_NEAR(view.wall_position(2, t), 0.0, 1e-12) << engine;
            EXPECT_NEAR(view.wall_position(3, t), 10.0, 1e-12) << engine;
            const std::vector<double> r = sim.positions();
            for (std::size_t i = 0; i < r.size(); i += 2) {
                // Centres at least a radius inside (less the soft contact's overlap).
                EXPECT_GT(r[i], A + shift + 0.45) << engine;
                EXPECT_LT(r[i], L - A + shift - 0.45) << engine;
            }
        }
    }
}

// The temperature of a dilute gas shaken between the side walls (no gravity, y periodic, e = 0.9
// for grains and walls): DEM with stiff contacts (t_c = 2e-3, 1e-3 of the mean free time) and
// the event-driven engine's hard limit of the same law agree within 3 combined standard errors
// plus 2% (the soft contacts' finite duration). T_x > T_y: the energy comes in along x.
TEST(VibratingBox, ShakenGasHasTheSameTemperatureOnBothEngines) {
    auto scene = [](const char* engine) {
        return fmt::format(R"(
dimension: 2
seed: 6
box: {{lengths: [21, 20], periodic: [false, true]}}
species: [{{name: g, count: 60}}]
interactions: {{law: linear_dashpot, restitution: 0.9, contact_time: 0.002}}
engine: {{type: {}}}
drivers: [{{type: vibrating_box, axis: x, amplitude: 0.5, frequency: 1}}]
observables: [{{type: temperatures}}]
run: {{unit: time, equilibration: 50, measurement: 600, sample_interval: 0.37}}
)",
                           engine);
    };
    const YAML::Node ed = testing::run_yaml(scene("event_driven"),
                                            "ed")["observables"]["temperatures"]["species"]["g"];
    const YAML::Node dem =
        testing::run_yaml(scene("dem"), "dem")["observables"]["temperatures"]["species"]["g"];
    for (const char* c : {"T_x", "T_y"}) {
        const double a = testing::value(ed[c]), b = testing::value(dem[c]);
        const double sigma = std::hypot(testing::error(ed[c]), testing::error(dem[c]));
        RecordProperty(c, fmt::format("event-driven {:.4f} +- {:.4f}, dem {:.4f} +- {:.4f}", a,
                                      testing::error(ed[c]), b, testing::error(dem[c])));
        EXPECT_NEAR(b, a, 3 * sigma + 0.02 * a) << c;
        EXPECT_LT(sigma, 0.05 * a) << c;
    }
    EXPECT_GT(testing::value(ed["T_x"]), 1.1 * testing::value(ed["T_y"]));
}

// Spheres (q = 2/5) resting on the floor of a box shaken along the periodic x axis (only floor
// and lid move: A = 4, omega = 0.2, from rest): with friction each rolls without slipping,
// v = q / (1 + q) u(t) (tests/libgran/engines/dem/test_dem_sliding_wall.cpp), so its kinetic
// energy (translation and rotation) averages m <u^2> q / (2 (1 + q)) = m (A omega)^2 / 14 over
// whole periods. Tolerance 3%: the grains land (within 0.05 d, in about one time unit) while the
// floor already moves at up to 0.05 A omega. A smooth floor leaves them at rest.
TEST(VibratingBox, FrictionalFloorRollsTheGrainsAtTwoSeventhsOfItsVelocity) {
    auto energy = [](double friction) {
        const std::string scene =
            fmt::format(R"(
dimension: 3
seed: 2
gravity: [0, 0, -1]
box: {{lengths: [12, 12, 1.05], periodic: [true, true, false]}}
species: [{{name: g, count: 16}}]
interactions: {{law: linear_dashpot, stiffness: 2.0e+5, restitution: 0.5, friction: {},
               tangential_damping_ratio: 1}}
initial: {{placement: random, temperature: 1.0e-12}}
engine: {{type: dem}}
drivers: [{{type: vibrating_box, axis: x, amplitude: 4, frequency: {}}}]
observables: [{{type: kinetic_energy}}]
run: {{unit: time, equilibration: 0, measurement: {}, sample_interval: {}}}
)",
                        friction, 0.2 / (2 * kPi), 2 * 2 * kPi / 0.2, 2 * kPi / 0.2 / 40);
        const YAML::Node s = testing::run_yaml(scene, fmt::format("floor{}", friction));
        return testing::value(s["observables"]["kinetic_energy"]["mean_energy_per_particle"]);
    };
    const double theory = (4 * 0.2) * (4 * 0.2) / 14;
    const double rough = energy(0.5);
    RecordProperty("energy", fmt::format("{:.6f} (theory {:.6f})", rough, theory));
    EXPECT_NEAR(rough, theory, 0.03 * theory);
    EXPECT_LT(energy(0.0), 0.01 * theory);
}

TEST(VibratingBox, RefusesAnotherDriverOnItsWallsAndAnAmplitudeTheBoxCannotHold) {
    const std::string base = shaken_box("event_driven");
    std::string lid = base;
    lid.replace(lid.find("frequency: 0.3}]"), 16,
                "frequency: 0.3}, {type: static_wall, axis: y, side: upper}]");
    EXPECT_THROW(
        {
            try {
                parse_scene(YAML::Load(lid), "lid.yaml");
            } catch (const SceneError& e) {
                EXPECT_NE(std::string(e.what()).find("already given by driver 'vibrating_box'"),
                          std::string::npos)
                    << e.what();
                throw;
            }
        },
        SceneError);
    std::string wide = base;
    wide.replace(wide.find("amplitude: 0.5"), 14, "amplitude: 5.6");
    EXPECT_THROW(
        {
            try {
                parse_scene(YAML::Load(wide), "wide.yaml");
            } catch (const SceneError& e) {
                EXPECT_NE(std::string(e.what()).find("leaves no room"), std::string::npos)
                    << e.what();
                throw;
            }
        },
        SceneError);
}

}  // namespace
}  // namespace gran
