// Velocities about the local flow (observables/local_flow.hpp, the `flow_cell` option of
// `temperatures`, `profiles` and `velocity_pdf`): the correction for a cell's own mean is exact for
// independent velocities (an elastic mixture in equilibrium, small cells), one cell spanning the
// box gives back the centre-of-mass values, and cells too small to measure are refused.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "libgran/core/scene_error.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

// An elastic binary mixture in equilibrium (masses 1 and 3, sizes 1 and 1.4): every species has
// the same temperature, a Gaussian distribution (a2 = 0) and no collective flow. 2000 disks,
// packing fraction 0.2; cells of 4.15 diameters (26 x 26) hold about 3 disks, so about the cells'
// plain means the temperatures would read 23% (light) and 41% (heavy) low and gamma 0.76 (the
// expectation of 1 - m_i / M_cell over Poisson occupancies).
std::string equilibrium_mixture(const std::string& flow_cell) {
    return fmt::format(R"(
dimension: 2
seed: 9
particles: 2000
species:
  - {{name: light, mass: 1, number_fraction: 0.5}}
  - {{name: heavy, mass: 3, diameter: 1.4, number_fraction: 0.5}}
interactions: {{alpha: 1}}
box: {{packing_fraction: 0.2}}
observables:
  - {{type: temperatures}}
  - {{type: temperatures, name: local, flow_cell: {0}}}
  - {{type: profiles, axis: y, bins: 2, pressure: false, flow_cell: {0}}}
  - {{type: velocity_pdf, flow_cell: {0}}}
run: {{equilibration: 20, measurement: 400, sample_interval: 1}}
)",
                       flow_cell);
}

TEST(LocalFlow, SmallCellsGiveUnbiasedTemperaturesAndSonineCoefficientsInEquilibrium) {
    const YAML::Node s = testing::run_yaml(equilibrium_mixture("4"), "cells4")["observables"];
    const YAML::Node global = s["temperatures"], local = s["local"];
    for (const char* sp : {"light", "heavy"}) {
        const YAML::Node t = local["species"][sp]["T"], tg = global["species"][sp]["T"];
        const YAML::Node a2 = local["species"][sp]["sonine_a2"];
        RecordProperty(std::string(sp) + "_T",
                       fmt::format("{:.4f} +- {:.4f} (global {:.4f})", testing::value(t),
                                   testing::error(t), testing::value(tg)));
        RecordProperty(std::string(sp) + "_a2",
                       fmt::format("{:.4f} +- {:.4f}", testing::value(a2), testing::error(a2)));
        // Elastic: the energy is conserved, T only fluctuates; both estimators see the same T.
        EXPECT_NEAR(testing::value(t) / testing::value(tg), 1.0, 4 * testing::error(t)) << sp;
        EXPECT_NEAR(testing::value(a2), 0.0, 4 * testing::error(a2) + 0.002) << sp;
        EXPECT_LT(testing::error(a2), 0.01) << sp;
    }
    const YAML::Node gamma = local["ratios"]["heavy_over_light"]["gamma"];
    EXPECT_NEAR(testing::value(gamma), 1.0, 4 * testing::error(gamma) + 0.002);
    const YAML::Node middle = s["profiles"]["middle/ratios/heavy_over_light/gamma"];
    EXPECT_NEAR(testing::value(middle), 1.0, 4 * testing::error(middle) + 0.004);
    // No collective flow: the flow's energy is what independent velocities give.
    const YAML::Node flow = local["flow"];
    EXPECT_GT(testing::value(flow["energy_share"]), 0.1) << "cells of about 4 disks";
    EXPECT_NEAR(testing::value(flow["collective_share"]), 0.0,
                4 * testing::error(flow["collective_share"]) + 0.002);
    // The distribution about the local flow is measured (its kurtosis is pulled towards 3).
    EXPECT_NEAR(s["velocity_pdf"]["light"]["x"]["kurtosis"]["value"].as<double>(), 3.0, 0.05);
}

// One cell spanning the box: the local flow is the centre-of-mass velocity, and the corrected
// estimates differ from the plain ones only by the O(1/N) corrections for that mean.
TEST(LocalFlow, OneCellSpanningTheBoxGivesTheCentreOfMassValues) {
    const YAML::Node s = testing::run_yaml(equilibrium_mixture("1000"), "whole")["observables"];
    for (const char* sp : {"light", "heavy"}) {
        const double t = testing::value(s["local"]["species"][sp]["T"]);
        const double tg = testing::value(s["temperatures"]["species"][sp]["T"]);
        EXPECT_NEAR(t / tg, 1.0, 2.0 / 2000) << sp;
        const double a2 = testing::value(s["local"]["species"][sp]["sonine_a2"]);
        const double a2g = testing::value(s["temperatures"]["species"][sp]["sonine_a2"]);
        EXPECT_NEAR(a2, a2g, 2e-3) << sp;
    }
    EXPECT_NEAR(testing::value(s["local"]["flow"]["energy_share"]), 0.0, 1e-12);
    EXPECT_NEAR(testing::value(s["local"]["flow"]["collective_share"]), 0.0, 1e-12);
}

TEST(LocalFlow, CellsHoldingFewerThanTwoParticlesAreRefusedNamingTheKey) {
    try {
        testing::run_yaml(equilibrium_mixture("1.5"), "tiny");
        FAIL() << "cells of 1.5 diameters were accepted";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("flow_cell"), std::string::npos) << what;
        EXPECT_NE(what.find("at least 2"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace gran
