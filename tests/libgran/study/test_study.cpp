// Studies: a study file expands into runs (points x grid x zip x replicas) with clear errors; `gran
// study` runs them several at a time, merges them into one HDF5 file with a group per run and a
// summary table, and a second invocation recomputes nothing. Power-law fits over the runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libgran/core/build_info.hpp"
#include "libgran/core/h5.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/study/study.hpp"
#include "libgran/study/study_fit.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::run_gran;

// A thermostatted gas that runs in a fraction of a second.
const char* kScene = R"(dimension: 2
species: [{name: a, count: 100}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.01}]
observables: [{type: temperatures}]
run: {equilibration: 10, measurement: 300}
)";

class Study : public gran::testing::TempDirTest {
  protected:
    Study() : TempDirTest("gran_study") {}
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name)) << text;
    }
    std::string study_file(const std::string& body) const {
        write("scene.yaml", kScene);
        write("study.yaml", "scene: scene.yaml\n" + body);
        return path("study.yaml");
    }
    std::string error_of(const std::string& body) const {
        try {
            (void)gran::load_study(study_file(body));
        } catch (const gran::SceneError& e) {
            return e.what();
        }
        return "";
    }
};

TEST_F(Study, ExpandsPointsTimesGridTimesZipTimesReplicas) {
    const gran::Study st = gran::load_study(study_file(R"(points:
  - {name: hot, set: {drivers.0.strength: 0.02}, paper: {T: 1.5}}
  - {name: cold}
grid: {interactions.alpha: [0.8, 0.9]}
zip: {box.packing_fraction: [0.02, 0.05, 0.1], seed: [4, 5, 6]}
replicas: 2
)"));
    ASSERT_EQ(st.runs.size(), 2u * 2u * 3u * 2u);
    EXPECT_EQ(st.runs.front().name, "hot_alpha0.8_packing_fraction0.02_seed4_r1");
    EXPECT_EQ(st.runs.back().name, "cold_alpha0.9_packing_fraction0.1_seed6_r2");
    EXPECT_EQ(st.runs.front().metadata["paper"]["T"].as<double>(), 1.5);
    // Zipped keys advance together; the replica seed comes last and wins over the zipped one.
    const auto& o = st.runs[2].overrides;  // hot, alpha 0.8, zip index 1, replica 1
    EXPECT_EQ(st.runs[2].name, "hot_alpha0.8_packing_fraction0.05_seed5_r1");
    ASSERT_EQ(o.size(), 5u);
    EXPECT_EQ(o[2].second, "0.05");
    EXPECT_EQ(o[3].second, "5");
    EXPECT_EQ(o[4], (std::pair<std::string, std::string>{"seed", "1"}));
    EXPECT_EQ(st.swept_keys.front(), "drivers.0.strength");
}

TEST_F(Study, WithoutPointsRunsTheBaseSceneOnce) {
    const gran::Study st = gran::load_study(study_file(""));
    ASSERT_EQ(st.runs.size(), 1u);
    EXPECT_EQ(st.runs[0].name, "scene");
    EXPECT_TRUE(st.runs[0].overrides.empty());
}

TEST_F(Study, RefusesABadOverrideNamingThePointAndTheKey) {
    const std::string e = error_of("points:\n  - {name: p, set: {interactions.alpha: 1.5}}\n");
    EXPECT_NE(e.find("study.yaml:3:5: points[0]: run 'p'"), std::string::npos) << e;
    EXPECT_NE(e.find("interactions.alpha=1.5"), std::string::npos) << e;
}

TEST_F(Study, RefusesZippedListsOfUnequalLength) {
    const std::string e = error_of("zip: {seed: [1, 2], interactions.alpha: [0.8]}\n");
    EXPECT_NE(e.find("study.yaml:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("zip.interactions.alpha: zipped lists must have equal lengths"),
              std::string::npos)
        << e;
}

TEST_F(Study, RefusesUnknownKeysAndDuplicateRunNames) {
    EXPECT_NE(error_of("pionts: []\n").find("study.yaml:2:1: pionts: unknown key"),
              std::string::npos);
    EXPECT_NE(error_of("points: [{name: a}, {name: a}]\n").find("two runs are both named 'a'"),
              std::string::npos);
    EXPECT_NE(error_of("replicas: 0\n").find("replicas: expected an integer >= 1"),
              std::string::npos);
}

TEST_F(Study, FourPointSweepRunsTwoAtATimeMergesAndResumeRecomputesNothing) {
    const std::string file = study_file(
        "grid: {interactions.alpha: [0.7, 0.8, 0.9, 1.0]}\n"
        "fits:\n  - {name: T_alpha, x: interactions.alpha, y: "
        "observables.temperatures.T_mixture}\n");
    const std::string out = path("out");
    const auto first = run_gran({"-q", "study", file, "-o", out, "-j", "2"});
    ASSERT_EQ(first.exit_code, 0) << first.output;
    EXPECT_NE(first.output.find("4 ran, 0 reused, 0 failed; at most 2 at a time"),
              std::string::npos)
        << first.output;
    {
        gran::h5::File f = gran::h5::File::open_read(out + "/study.study.h5");
        const gran::h5::Group r = f.root();
        EXPECT_EQ(r.read_int64s("performance/max_concurrent_runs").at(0), 2);
        const auto t =
            r.read_doubles("summary/quantities/observables.temperatures.T_mixture/value");
        ASSERT_EQ(t.size(), 4u);
        // A group per run holding the whole run file (scene, observables, performance).
        EXPECT_TRUE(r.exists("points/scene_alpha0.7/parameters/scene"));
        EXPECT_TRUE(r.exists("points/scene_alpha1.0/observables/temperatures"));
        EXPECT_EQ(r.read_doubles("points/scene_alpha0.8/observables/temperatures/T_mixture").at(0),
                  t[1]);
        // Stronger dissipation, lower steady temperature at fixed driving.
        EXPECT_GT(t[3], t[0]);
        EXPECT_TRUE(r.exists("fits/T_alpha/theta"));
    }
    const auto mtime = fs::last_write_time(out + "/scene_alpha0.7.h5");
    const auto second = run_gran({"-q", "study", file, "-o", out, "-j", "2"});
    ASSERT_EQ(second.exit_code, 0) << second.output;
    EXPECT_NE(second.output.find("0 ran, 4 reused"), std::string::npos) << second.output;
    EXPECT_EQ(fs::last_write_time(out + "/scene_alpha0.7.h5"), mtime);

    // A changed value is a different run: only that point runs again.
    write("study.yaml", "scene: scene.yaml\ngrid: {interactions.alpha: [0.7, 0.8, 0.9, 0.95]}\n");
    const auto third = run_gran({"-q", "study", file, "-o", out});
    EXPECT_NE(third.output.find("1 ran, 3 reused"), std::string::npos) << third.output;
    // A changed base scene changes every run.
    write("scene.yaml", std::string(kScene) + "seed: 9\n");
    const auto fourth = run_gran({"-q", "study", file, "-o", out});
    EXPECT_NE(fourth.output.find("4 ran, 0 reused"), std::string::npos) << fourth.output;
}

// Replicas pooled: a study with replicas also writes <study>.pooled.csv, one row per point, each
// quantity the inverse-variance mean of its replicas with error 1 / sqrt(sum 1 / e_i^2) and the
// Birge ratio of their scatter. Checked against the per-run table the study writes beside it.
TEST_F(Study, ReplicasArePooledIntoOneRowPerPointWithInverseVarianceWeights) {
    const std::string file = study_file("grid: {interactions.alpha: [0.8, 0.9]}\nreplicas: 3\n");
    const std::string out = path("out");
    const auto r = run_gran({"-q", "study", file, "-o", out, "-j", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("replicas pooled: " + out + "/study.pooled.csv"), std::string::npos)
        << r.output;
    auto rows_of = [](const std::string& csv) {
        std::ifstream in(csv);
        std::vector<std::vector<std::string>> rows;
        for (std::string line; std::getline(in, line);) {
            std::vector<std::string> cells;
            std::stringstream ss(line);
            for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
            rows.push_back(cells);
        }
        return rows;
    };
    const auto runs = rows_of(out + "/study.study.csv");
    const auto pooled = rows_of(out + "/study.pooled.csv");
    ASSERT_EQ(pooled.size(), 3u);  // header, two points
    auto column = [](const std::vector<std::string>& header, const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        EXPECT_NE(it, header.end()) << name;
        return std::size_t(it - header.begin());
    };
    const std::string q = "observables.temperatures.T_mixture";
    const std::size_t pv = column(pooled[0], q), pe = column(pooled[0], q + ".error"),
                      rv = column(runs[0], q), re = column(runs[0], q + ".error"),
                      rn = column(runs[0], "run");
    EXPECT_EQ(pooled[1][column(pooled[0], "replicas")], "3");
    for (std::size_t k = 1; k < pooled.size(); ++k) {
        const std::string group = pooled[k][0];
        double sw = 0, swx = 0;
        int members = 0;
        for (std::size_t i = 1; i < runs.size(); ++i) {
            if (runs[i][rn].rfind(group + "_r", 0) != 0) continue;
            const double v = std::stod(runs[i][rv]), e = std::stod(runs[i][re]);
            sw += 1 / (e * e);
            swx += v / (e * e);
            ++members;
        }
        EXPECT_EQ(members, 3) << group;
        EXPECT_NEAR(std::stod(pooled[k][pv]), swx / sw, 1e-8 * std::abs(swx / sw)) << group;
        EXPECT_NEAR(std::stod(pooled[k][pe]), 1 / std::sqrt(sw), 1e-8 / std::sqrt(sw)) << group;
    }
    // Without replicas there is no pooled table.
    const std::string single = study_file("grid: {interactions.alpha: [0.8]}\n");
    const auto r2 = run_gran({"-q", "study", single, "-o", path("out2")});
    ASSERT_EQ(r2.exit_code, 0) << r2.output;
    EXPECT_FALSE(fs::exists(path("out2") + "/study.pooled.csv"));
}

// Provenance: a result made by other code (another commit, uncommitted changes, or a build
// older than provenance records) is not mixed into the study silently.
TEST_F(Study, ResultOfAnotherCodeVersionIsRerunUnlessReuseIsAskedFor) {
    const std::string file =
        study_file("grid: {interactions.alpha: [0.8, 0.9]}\nset: {run.measurement: 50}\n");
    const std::string out = path("out");
    ASSERT_EQ(run_gran({"-q", "study", file, "-o", out}).exit_code, 0);
    const std::string run = out + "/scene_alpha0.8.h5";
    {
        gran::h5::File f = gran::h5::File::open_read(run);
        EXPECT_EQ(f.root().group("provenance").read_attr_string("code_id"),
                  gran::build_info().code_id());
    }
    auto mark_as_other_code = [&] {
        gran::h5::File f = gran::h5::File::open_write(run);
        f.root().group("provenance").attr("code_id", "0.0.1+0123456789ab");
    };
    mark_as_other_code();
    const auto reused = run_gran({"study", file, "-o", out, "--reuse-any-version"});
    EXPECT_NE(reused.output.find("0 ran, 2 reused"), std::string::npos) << reused.output;
    EXPECT_NE(reused.output.find("reusing a result made by code 0.0.1+0123456789ab"),
              std::string::npos)
        << reused.output;
    const auto rerun = run_gran({"study", file, "-o", out});
    EXPECT_NE(rerun.output.find("1 ran, 1 reused"), std::string::npos) << rerun.output;
    EXPECT_NE(rerun.output.find("made by code 0.0.1+0123456789ab, rerun"), std::string::npos)
        << rerun.output;
}

// Readers group runs by their point from the table itself, never by parsing run names.
TEST_F(Study, TableNamesThePointOfEveryRunInAPointColumn) {
    const std::string file = study_file(
        "points: [{name: hot_gas, set: {drivers.0.strength: 0.02}}, {name: cold}]\n"
        "grid: {interactions.alpha: [0.8, 0.9]}\n"
        "set: {run.measurement: 50}\n");
    const std::string out = path("out");
    const auto done = run_gran({"-q", "study", file, "-o", out, "-j", "2"});
    ASSERT_EQ(done.exit_code, 0) << done.output;
    std::ifstream csv(out + "/study.study.csv");
    std::string header, line;
    ASSERT_TRUE(std::getline(csv, header));
    EXPECT_EQ(header.rfind("run,point,drivers.0.strength,interactions.alpha,", 0), 0u) << header;
    std::vector<std::string> rows;
    while (std::getline(csv, line)) {  // the first two fields: run, point
        const auto second_comma = line.find(',', line.find(',') + 1);
        rows.push_back(line.substr(0, second_comma));
    }
    const std::vector<std::string> expected{"hot_gas_alpha0.8,hot_gas", "hot_gas_alpha0.9,hot_gas",
                                            "cold_alpha0.8,cold", "cold_alpha0.9,cold"};
    EXPECT_EQ(rows, expected);
    gran::h5::File f = gran::h5::File::open_read(out + "/study.study.h5");
    EXPECT_EQ(f.root().shape("summary/points"), std::vector<std::size_t>{4});
}

TEST(PowerLawFit, RecoversTheExponentOfAnExactPowerLaw) {
    const std::vector<double> x{1, 2, 4, 8, 16};
    std::vector<double> y;
    for (double v : x) y.push_back(3.0 * std::pow(v, 1.7));
    const gran::PowerLawFit f = gran::fit_power_law(x, y, 0.25);
    EXPECT_NEAR(f.theta, 1.7, 1e-12);
    EXPECT_NEAR(std::exp(f.log_prefactor), 3.0, 1e-10);
    EXPECT_NEAR(f.theta_error, 0.0, 1e-10);
    EXPECT_TRUE(f.valid);
}

TEST(PowerLawFit, NoExponentWhenAPointDeviatesByAQuarterInLog) {
    // McNamara & Falcon 2005, Sec. IV: reject when any |log X_obs - log X_fit| >= 0.25.
    const std::vector<double> x{1, 2, 3, 4, 5};
    const std::vector<double> y{1, 4, 9 * std::exp(0.6), 16, 25};
    const gran::PowerLawFit f = gran::fit_power_law(x, y, 0.25);
    EXPECT_GE(f.max_deviation, 0.25);
    EXPECT_FALSE(f.valid);
    // Small scatter keeps the fit, with a slope error from the residuals.
    const std::vector<double> y2{1, 4 * 1.05, 9 / 1.05, 16 * 1.05, 25 / 1.05};
    const gran::PowerLawFit g = gran::fit_power_law(x, y2, 0.25);
    EXPECT_TRUE(g.valid);
    EXPECT_NEAR(g.theta, 2.0, 0.1);
    EXPECT_GT(g.theta_error, 0.0);
    EXPECT_LT(g.theta_error, 0.1);
}

TEST(PowerLawFit, SkipsNonPositivePointsAndNeedsTwo) {
    const std::vector<double> x{0, 1, -2};
    const std::vector<double> y{1, 2, 3};
    const gran::PowerLawFit f = gran::fit_power_law(x, y, 0.25);
    EXPECT_EQ(f.points, 1u);
    EXPECT_FALSE(f.valid);
    EXPECT_TRUE(std::isnan(f.theta));
}

}  // namespace

namespace {

// A YAML complex key (`? [a, b]`) where a name is expected is a study error at its line, not
// yaml-cpp's "bad conversion" escaping (the scene loader's fuzzing found the same in scenes).
TEST_F(Study, ComplexKeysAreRefusedAtTheirLine) {
    EXPECT_NE(error_of("? [a, b]\n: 3\n").find("study.yaml:2:3: expected a key name"),
              std::string::npos)
        << error_of("? [a, b]\n: 3\n");
    const std::string in_set = error_of("set:\n  ? [run.measurement]\n  : 10\n");
    EXPECT_NE(in_set.find("study.yaml:3:5: set: expected a key name"), std::string::npos) << in_set;
}

}  // namespace
