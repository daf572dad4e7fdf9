// Speed versus accuracy: the Pareto front kernel, the comparison of every run with its reference
// (analytic value or the reference point), the ladder `gran tradeoff` derives from a scene, and the
// command end to end (table, HDF5 group, CSV, PNG).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/study/knob.hpp"
#include "libgran/study/study.hpp"
#include "libgran/study/study_tradeoff.hpp"
#include "libgran/study/tradeoff_ladder.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::run_gran;

TEST(ParetoFront, KeepsOnlyPointsNoOtherIsBothCheaperAndMoreAccurate) {
    // cost, error: (1, 10) front; (2, 5) front; (3, 6) dominated by (2, 5); (4, 1) front;
    // (5, 1) dominated by (4, 1) (same error, dearer); (0.5, NaN) never on the front.
    const std::vector<double> cost{1, 2, 3, 4, 5, 0.5};
    const std::vector<double> err{10, 5, 6, 1, 1, std::nan("")};
    const auto f = gran::pareto_front(cost, err);
    EXPECT_EQ(f, (std::vector<bool>{true, true, false, true, false, false}));
}

TEST(ParetoFront, IdenticalPointsAreBothOnTheFront) {
    const std::vector<double> cost{2, 2, 3};
    const std::vector<double> err{1, 1, 2};
    EXPECT_EQ(gran::pareto_front(cost, err), (std::vector<bool>{true, true, false}));
}

gran::Study two_run_study(bool analytic) {
    gran::Study st;
    st.has_tradeoff = true;
    st.tradeoff.quantities = {"q"};
    if (analytic) st.tradeoff.analytic = {{"q", 2.0}};
    gran::StudyRun cheap, ref;
    cheap.name = cheap.point = "cheap";
    ref.name = ref.point = "reference";
    cheap.metadata["knob"] = "dt";
    cheap.metadata["level"] = "0.1";
    st.runs = {cheap, ref};
    return st;
}

TEST(TradeoffAnalysis, DeviationFromTheReferenceRunCombinesBothErrors) {
    const gran::Study st = two_run_study(false);
    std::vector<gran::Row> rows(2);
    rows[0] = {{"q", {2.2, 0.03}}, {"performance.cpu_time", {1.0, std::nan("")}}};
    rows[1] = {{"q", {2.0, 0.04}}, {"performance.cpu_time", {10.0, std::nan("")}}};
    const auto t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true});
    ASSERT_EQ(t.quantities, std::vector<std::string>{"q"});
    ASSERT_EQ(t.rows.size(), 2u);
    const auto& c = t.rows[0].cells[0];
    EXPECT_DOUBLE_EQ(c.reference, 2.0);
    EXPECT_NEAR(c.deviation, 0.1, 1e-12);
    EXPECT_NEAR(c.deviation_error, 0.05 / 2.0, 1e-12);  // sqrt(0.03^2 + 0.04^2) / 2
    EXPECT_NEAR(c.accuracy, 0.1 + 0.025, 1e-12);
    EXPECT_EQ(t.rows[0].knob, "dt");
    EXPECT_EQ(t.rows[0].level, "0.1");
    // The reference run: no deviation, its own error only; both runs are on the front (cheaper
    // but worse, dearer but better).
    EXPECT_NEAR(t.rows[1].cells[0].deviation, 0, 1e-15);
    EXPECT_NEAR(t.rows[1].cells[0].deviation_error, 0.02, 1e-12);
    EXPECT_TRUE(t.rows[1].reference);
    EXPECT_TRUE(t.rows[0].pareto && t.rows[1].pareto);
}

TEST(TradeoffAnalysis, AnAnalyticValueIsTheReferenceWithNoErrorOfItsOwn) {
    const gran::Study st = two_run_study(true);
    std::vector<gran::Row> rows(2);
    rows[0] = {{"q", {2.2, 0.03}}, {"performance.cpu_time", {1.0, std::nan("")}}};
    rows[1] = {{"q", {1.9, 0.01}}, {"performance.cpu_time", {10.0, std::nan("")}}};
    const auto t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true});
    ASSERT_EQ(t.reference_kind, std::vector<std::string>{"analytic"});
    EXPECT_NEAR(t.rows[0].cells[0].deviation_error, 0.015, 1e-12);
    EXPECT_NEAR(t.rows[1].cells[0].deviation, -0.05, 1e-12);
    EXPECT_NEAR(t.rows[1].cells[0].accuracy, 0.055, 1e-12);
}

TEST(TradeoffAnalysis, NamesQuantitiesItCannotCompare) {
    gran::Study st = two_run_study(false);
    st.tradeoff.quantities = {"q", "missing", "zero"};
    std::vector<gran::Row> rows(2);
    rows[0] = {{"q", {1, 0.1}}, {"zero", {0, 0}}};
    rows[1] = {{"q", {1, 0.1}}, {"zero", {0, 0}}};
    const auto t = gran::analyse_tradeoff(st, {"q", "zero"}, rows, {true, true});
    EXPECT_EQ(t.quantities, std::vector<std::string>{"q"});
    // No cost column, `missing` unreported, `zero` is 0, and no CPU split for the forecasts.
    ASSERT_EQ(t.problems.size(), 4u);
    EXPECT_NE(t.problems[0].find("cost"), std::string::npos);
    EXPECT_NE(t.problems[1].find("missing"), std::string::npos);
    EXPECT_NE(t.problems[2].find("0"), std::string::npos);
    EXPECT_NE(t.problems[3].find("cpu_time_measuring"), std::string::npos);
}

class TradeoffLadder : public gran::testing::TempDirTest {
  protected:
    TradeoffLadder() : TempDirTest("gran_tradeoff") {}
    std::string scene(const std::string& text) const {
        std::ofstream(path("scene.yaml")) << text;
        return path("scene.yaml");
    }
};

const char* kDemBed = R"(dimension: 2
gravity: [0, -1]
box: {lengths: [10, 60], periodic: [true, false]}
species: [{name: grain, count: 40}]
interactions: {law: linear_dashpot, restitution: 0.9, stiffness: 2.0e+5, friction: 0}
engine: {type: dem, dt_fraction: 0.02}
drivers: [{type: vibrating_wall, axis: y, side: lower, amplitude: 0.1, frequency: 3}]
observables: [{type: local_temperature}]
run: {unit: time, equilibration: 2, measurement: 8, sample_interval: 0.04}
)";

TEST_F(TradeoffLadder, FrictionlessDemSceneGetsTheEventDrivenHardLimitAsReference) {
    gran::TradeoffRequest rq;
    rq.scene = scene(kDemBed);
    std::vector<std::string> skipped;
    const auto knobs = gran::automatic_knobs(rq, skipped);
    std::vector<std::string> names;
    for (const auto& k : knobs) names.push_back(k.name);
    EXPECT_EQ(names,
              (std::vector<std::string>{"dt_over_tc", "stiffness", "engine", "N", "measurement"}));
    // dt_fraction 0.02 x 4, 2, 1, 1/2: never above the refused 0.2.
    EXPECT_EQ(knobs[0].levels.size(), 4u);
    EXPECT_EQ(knobs[0].levels[0].set[0].second, "0.08");
    EXPECT_EQ(knobs[0].base, 2);
    // N at the same density: 40 -> 20 grains on a 5-wide base (the periodic axis only).
    bool halved = false;
    for (const auto& l : knobs[3].levels) {
        if (l.label == "x1/2") {
            halved = true;
            EXPECT_EQ(l.set, (std::vector<std::pair<std::string, std::string>>{
                                 {"species.0.count", "20"}, {"box.lengths.0", "5"}}));
        }
    }
    EXPECT_TRUE(halved);
    const std::string text = gran::tradeoff_study_text(rq, path("out"));
    // The reference is the hard limit: the event_driven engine and no DEM knob with it.
    const auto ref = text.find("{name: reference");
    ASSERT_NE(ref, std::string::npos) << text;
    const std::string line = text.substr(ref, text.find('\n', ref) - ref);
    EXPECT_NE(line.find("event_driven"), std::string::npos) << line;
    EXPECT_EQ(line.find("stiffness"), std::string::npos) << line;
    EXPECT_EQ(line.find("dt_fraction"), std::string::npos) << line;
}

TEST_F(TradeoffLadder, FrictionKeepsTheDemEngineAndUnknownKnobsAreRefused) {
    std::string bed = kDemBed;
    bed.replace(bed.find("friction: 0"), 11, "friction: 0.4");
    gran::TradeoffRequest rq;
    rq.scene = scene(bed);
    std::vector<std::string> skipped;
    for (const auto& k : gran::automatic_knobs(rq, skipped)) EXPECT_NE(k.name, "engine");
    bool said = false;
    for (const auto& s : skipped) said = said || s.rfind("engine: friction", 0) == 0;
    EXPECT_TRUE(said);
    rq.knobs = {"timestep"};
    EXPECT_THROW((void)gran::automatic_knobs(rq, skipped), gran::SceneError);
}

TEST(KnobRegistry, HoldsTheSixKnobsInLadderOrderEachDeclaredByItsPlugin) {
    std::vector<std::string> names;
    for (const gran::KnobPlugin* k : gran::knobs_in_order()) {
        names.push_back(k->name);
        EXPECT_FALSE(k->summary.empty()) << k->name;
        EXPECT_TRUE(k->make) << k->name;
    }
    EXPECT_EQ(names, (std::vector<std::string>{"dt_over_tc", "stiffness", "engine", "kick_interval",
                                               "N", "measurement"}));
    EXPECT_EQ(gran::knob_names(), "dt_over_tc, stiffness, engine, kick_interval, N, measurement");
}

TEST_F(TradeoffLadder, TheUnknownKnobMessageListsTheRegisteredKnobs) {
    gran::TradeoffRequest rq;
    rq.scene = scene(kDemBed);
    rq.knobs = {"N", "timestep"};
    std::vector<std::string> skipped;
    try {
        (void)gran::automatic_knobs(rq, skipped);
        FAIL() << "accepted an unknown knob";
    } catch (const gran::SceneError& e) {
        EXPECT_EQ(std::string(e.what()), "gran tradeoff: unknown knob 'timestep'; the knobs are " +
                                             gran::knob_names() +
                                             " (or --knob KEY=v1,v2,... for any scene key)");
        for (const gran::KnobPlugin* k : gran::knobs_in_order())
            EXPECT_NE(std::string(e.what()).find(k->name), std::string::npos) << k->name;
    }
}

TEST_F(TradeoffLadder, KnobsThatDoNotApplySayWhyUnderTheirName) {
    gran::TradeoffRequest rq;
    rq.scene = scene(kDemBed);
    std::vector<std::string> skipped;
    (void)gran::automatic_knobs(rq, skipped);
    ASSERT_FALSE(skipped.empty());
    EXPECT_EQ(skipped[0], "kick_interval: no stochastic_thermostat driver");
}

TEST_F(TradeoffLadder, ThermostatSceneLaddersTheKickIntervalAndRefinesItForTheReference) {
    gran::TradeoffRequest rq;
    rq.scene = scene(R"(dimension: 2
particles: 200
species: [{name: a, number_fraction: 1}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.01, interval: 0.4}]
observables: [{type: temperatures}]
run: {equilibration: 10, measurement: 200}
)");
    rq.knobs = {"kick_interval", "N"};
    std::vector<std::string> skipped;
    const auto knobs = gran::automatic_knobs(rq, skipped);
    ASSERT_EQ(knobs.size(), 2u);
    EXPECT_EQ(knobs[0].levels.back().set[0],
              (std::pair<std::string, std::string>{"drivers.0.interval", "0.2"}));
    // The box follows the packing fraction: only `particles` changes with N.
    EXPECT_EQ(knobs[1].levels[0].set,
              (std::vector<std::pair<std::string, std::string>>{{"particles", "25"}}));
}

class TradeoffCommand : public gran::testing::TempDirTest {
  protected:
    TradeoffCommand() : TempDirTest("gran_tradeoff_cmd") {}
};

TEST_F(TradeoffCommand, WritesTheTableTheHdf5GroupTheCsvAndThePlot) {
    std::ofstream(path("gas.yaml")) << R"(dimension: 2
particles: 100
species: [{name: a, number_fraction: 1}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.01, interval: 0.4}]
observables: [{type: temperatures}, {type: velocity_pdf}]
run: {equilibration: 10, measurement: 100}
)";
    const std::string out = path("out");
    const auto r = run_gran({"-q", "tradeoff", path("gas.yaml"), "--knobs", "kick_interval",
                             "--knob", "run.sample_interval=2,1", "-o", out, "-j", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("| run | knob | level | CPU s |"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(fs::path(out) / "gas.tradeoff.md"));
    EXPECT_TRUE(fs::exists(fs::path(out) / "gas.tradeoff.csv"));
    EXPECT_TRUE(fs::exists(fs::path(out) / "gas.tradeoff.png")) << r.output;
    gran::h5::File f = gran::h5::File::open_read((fs::path(out) / "gas.study.h5").string());
    const auto runs = f.root().read_doubles("tradeoff/cost");
    // base (sample interval 1: the scene's own), kick interval x4 and x2, sample interval 2, the
    // reference (kick interval x1/2; the sample interval's best level is the base's).
    EXPECT_EQ(runs.size(), 5u);
    // The cost and wall time come from each run's summary (performance.cpu_time, .wall_time).
    for (double c : runs) EXPECT_GT(c, 0);
    for (double w : f.root().read_doubles("tradeoff/wall_time")) EXPECT_GT(w, 0);
    {
        // Every row of the CSV has a field per column of its header.
        std::ifstream csv(fs::path(out) / "gas.tradeoff.csv");
        std::string header, row;
        ASSERT_TRUE(std::getline(csv, header));
        EXPECT_EQ(header.rfind("run,point,knob,level,cost,wall_time,", 0), 0u) << header;
        while (std::getline(csv, row))
            EXPECT_EQ(std::count(row.begin(), row.end(), ','),
                      std::count(header.begin(), header.end(), ','))
                << row;
    }
    const auto dev =
        f.root().read_doubles("tradeoff/quantities/observables.temperatures.T_mixture/deviation");
    ASSERT_EQ(dev.size(), runs.size());
    for (double d : dev) EXPECT_TRUE(std::isfinite(d));
    // Each setting's cost to the base run's error bar (the run summaries' cpu_time_measuring
    // and n_eff), above its measurement-free part and finite; printed as a second table.
    const auto to_target = f.root().read_doubles(
        "tradeoff/quantities/observables.temperatures.T_mixture/cpu_to_target");
    ASSERT_EQ(to_target.size(), runs.size());
    for (double c : to_target) EXPECT_TRUE(std::isfinite(c) && c > 0) << c;
    EXPECT_NE(r.output.find("Cost to the same error bar"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(base runs' error)"), std::string::npos) << r.output;
    // The velocity distributions are compared too: the total-variation distance from the
    // reference run's, 0 for the reference itself, between 0 and 1 otherwise.
    const auto dist =
        f.root().read_doubles("tradeoff/quantities/observables.velocity_pdf.pdf_distance/value");
    const auto is_ref = f.root().read_int64s("tradeoff/reference");
    ASSERT_EQ(dist.size(), runs.size());
    for (std::size_t i = 0; i < dist.size(); ++i) {
        if (is_ref[i]) {
            EXPECT_EQ(dist[i], 0);
        } else {
            EXPECT_GT(dist[i], 0);
            EXPECT_LT(dist[i], 1);
        }
    }
}

TEST_F(TradeoffCommand, ReadsTargetErrorsAndRefusesABadOneAtItsLine) {
    std::ofstream(path("gas.yaml")) << "dimension: 2\nspecies: [{name: a, count: 50}]\n"
                                       "box: {packing_fraction: 0.05}\n"
                                       "run: {measurement: 10}\n";
    std::ofstream(path("study.yaml")) << "scene: gas.yaml\npoints: [{name: reference}]\n"
                                         "tradeoff:\n  target_error: {a.b: 2%, c.d: 0.003}\n";
    const gran::Study st = gran::load_study(path("study.yaml"));
    ASSERT_EQ(st.tradeoff.target_error.size(), 2u);
    EXPECT_TRUE(st.tradeoff.target_error[0].relative);
    EXPECT_DOUBLE_EQ(st.tradeoff.target_error[0].error, 0.02);
    EXPECT_DOUBLE_EQ(st.tradeoff.target_error[1].error, 0.003);
    std::ofstream(path("study.yaml")) << "scene: gas.yaml\npoints: [{name: reference}]\n"
                                         "tradeoff:\n  target_error: {a.b: 150%}\n";
    try {
        (void)gran::load_study(path("study.yaml"));
        FAIL() << "accepted a relative error bar of 150%";
    } catch (const gran::SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("study.yaml:4"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("target_error.a.b"), std::string::npos) << e.what();
    }
}

TEST_F(TradeoffCommand, RefusesAStudyWhoseReferenceIsNoPoint) {
    std::ofstream(path("gas.yaml")) << "dimension: 2\nspecies: [{name: a, count: 50}]\n"
                                       "box: {packing_fraction: 0.05}\n"
                                       "run: {measurement: 10}\n";
    std::ofstream(path("study.yaml")) << "scene: gas.yaml\npoints: [{name: a}]\n"
                                         "tradeoff: {reference: best}\n";
    try {
        (void)gran::load_study(path("study.yaml"));
        FAIL() << "accepted a reference that is no point";
    } catch (const gran::SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("study.yaml:3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'best'"), std::string::npos) << e.what();
    }
}

}  // namespace

namespace {

TEST_F(TradeoffCommand, RefusesUnknownKnobsAndMalformedLaddersWithExitCode2) {
    std::ofstream(path("gas.yaml")) << "dimension: 2\nspecies: [{name: a, count: 50}]\n"
                                       "box: {packing_fraction: 0.05}\n"
                                       "run: {measurement: 10}\n";
    const auto unknown = run_gran(
        {"tradeoff", path("gas.yaml"), "--knobs", "timestep", "--dry-run", "-o", path("out")});
    EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
    EXPECT_NE(unknown.output.find("unknown knob 'timestep'"), std::string::npos) << unknown.output;
    const auto malformed =
        run_gran({"tradeoff", path("gas.yaml"), "--knob", "seed", "--dry-run", "-o", path("out")});
    EXPECT_EQ(malformed.exit_code, 2) << malformed.output;
    EXPECT_NE(malformed.output.find("KEY=v1,v2"), std::string::npos) << malformed.output;
    // A ladder value the scene refuses is named before anything runs.
    const auto refused = run_gran(
        {"tradeoff", path("gas.yaml"), "--knob", "interactions.alpha=0.5,1.5", "-o", path("out")});
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("interactions.alpha"), std::string::npos) << refused.output;
}

}  // namespace
