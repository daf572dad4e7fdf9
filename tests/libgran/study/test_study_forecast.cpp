// `gran study --forecast`: one pilot per point whose runs have run.target_error, the forecast of
// runs with a target read from each pilot, multiplied by the point's runs, and a report that names
// the points without a target; nothing of the study itself runs.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "libgran/study/study.hpp"
#include "libgran/study/study_forecast.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::run_gran;

// studies/targets/heated-mixture.yaml: 200 disks that reach their first look (50 collisions per
// particle) in a fraction of a second, with a target of 0.01 on gamma.
const char* kStudy = R"(scene: )" GRAN_SOURCE_DIR R"(/studies/targets/heated-mixture.yaml
replicas: 3
points:
  - {name: loose}
  - {name: tight, set: {run.target_error: {observables.temperatures.ratios.light_over_heavy.gamma: 0.004}}}
  - {name: fixed, set: {run.target_error: null}}
)";

class StudyForecast : public gran::testing::TempDirTest {
  protected:
    StudyForecast() : TempDirTest("gran_study_forecast") {}
    void SetUp() override {
        TempDirTest::SetUp();
        std::ofstream(path("study.yaml")) << kStudy;
    }
};

TEST_F(StudyForecast, PilotsTheFirstRunOfEveryPointWithATargetOnly) {
    const gran::Study st = gran::load_study(path("study.yaml"));
    ASSERT_EQ(st.runs.size(), 9u);
    const auto piloted = gran::runs_to_pilot(st);
    ASSERT_EQ(piloted.size(), 2u);
    EXPECT_EQ(st.runs[piloted[0]].name, "loose_r1");
    EXPECT_EQ(st.runs[piloted[1]].name, "tight_r1");
}

// The CPU seconds per run at the stopping look in a point's row of the report.
double at_stop_in_report(const std::string& report, const std::string& point) {
    std::smatch m;
    const std::regex row("\\| " + point +
                         " \\| 3 \\| [a-z ]+ \\| [0-9.e+-]+ \\([0-9.e+-]+-[0-9.e+-]+\\) \\| "
                         "([0-9.e+-]+) \\| ([0-9.e+-]+) \\|");
    if (!std::regex_search(report, m, row)) return -1;
    EXPECT_NEAR(std::stod(m[2]), 3 * std::stod(m[1]), 0.01 * std::stod(m[2])) << m[0];
    return std::stod(m[1]);
}

// The pilot's own forecast, as its summary records it.
double pilot_at_stop(const fs::path& summary) {
    const YAML::Node f = YAML::LoadFile(summary.string())["target"]["forecast"];
    return f["cpu_seconds_at_stop_look"]["value"].as<double>();
}

TEST_F(StudyForecast, ReportsEachPointsForecastTimesItsRunsAndRunsNothingElse) {
    const std::string out = path("out");
    const auto r = run_gran({"-q", "study", path("study.yaml"), "--forecast", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string report = gran::testing::read_text(fs::path(out) / "study.forecast.md");
    EXPECT_NE(r.output.find("# Forecast"), std::string::npos) << r.output;
    // Each row is its pilot's forecast (3 significant digits), times the point's 3 runs.
    const fs::path pilots = fs::path(out) / "pilots";
    const double loose = at_stop_in_report(report, "loose");
    const double tight = at_stop_in_report(report, "tight");
    ASSERT_GT(loose, 0) << report;
    EXPECT_NEAR(loose, pilot_at_stop(pilots / "loose_r1.summary.yaml"), 0.005 * loose);
    EXPECT_NEAR(tight, pilot_at_stop(pilots / "tight_r1.summary.yaml"), 0.005 * tight);
    // The same trajectory to the first look (same seed): a target 2.5 times tighter needs up to
    // 6.25 times its measurement.
    EXPECT_GT(tight, 1.5 * loose) << report;
    EXPECT_NE(report.find("total for the 6 runs with a forecast"), std::string::npos) << report;
    EXPECT_NE(report.find("points without a target (fixed length, not forecast): fixed (3 runs)"),
              std::string::npos)
        << report;
    // Only the pilots ran: their results under pilots/, no run of the study, no merged file.
    EXPECT_TRUE(fs::exists(pilots / "loose_r1.summary.yaml"));
    EXPECT_FALSE(fs::exists(pilots / "loose_r2.summary.yaml"));
    EXPECT_FALSE(fs::exists(fs::path(out) / "loose_r1.h5"));
    EXPECT_FALSE(fs::exists(fs::path(out) / "study.study.h5"));
}

TEST_F(StudyForecast, CheckRefusesAPilotOutputForASceneWithoutTarget) {
    const auto r =
        run_gran({"check", std::string(GRAN_SOURCE_DIR) + "/studies/targets/heated-mixture.yaml",
                  "--set", "run.target_error=null", "--pilot-output", path("p.h5")});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("no run.target_error"), std::string::npos) << r.output;
}

}  // namespace
