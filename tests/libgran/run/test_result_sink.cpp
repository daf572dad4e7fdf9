// The result sink (libgran/run/result_sink.hpp): one description of each quantity lands in the HDF5
// file and in the summary with equal values; series grow while the run goes on; the result is
// OUT.h5.part until finish() renames it, so a failed run never touches an earlier result.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/run.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace gran {
namespace {

namespace fs = std::filesystem;

class ResultSinkTest : public testing::TempDirTest {
  protected:
    ResultSinkTest() : TempDirTest("gran_sink") {}
};

// One of every kind of description.
void write_examples(ResultGroup g, const Estimate& e) {
    g.estimate("T", e, "energy");
    g.estimate("middle/gamma", e.affine(2.0), "");
    g.value("pressure", 0.75, "force/length");
    g.value("W", 1.5);
    g.value("collisions", std::uint64_t{12345});
    g.flag("relaxing", true);
    g.text("note", "a note");
    g.group("pairs").group("a-b").estimate("frequency_a", e, "1/time");
    g.group("a", {"species", "a"}).value("count", 7);
    g.file_only().value("bin_width", 0.5, "length");
    g.array("profile", std::vector<double>{1, 2, 3}, "length");
    g.histogram("h_", std::vector<double>{0, 1, 2}, std::vector<double>{0.5, 0.5},
                std::vector<double>{0.1, 0.1}, "velocity");
}

TEST_F(ResultSinkTest, OneDescriptionLandsInHdf5AndSummaryWithEqualValues) {
    const std::string out = path("r.h5");
    const Estimate e{2.5, 0.125, 3.0, 41.7, 250, false};  // value, error, tau_int, n_eff, ...
    {
        ResultSink sink(out);
        write_examples(sink.root().group("observables").group("obs"), e);
        sink.finish();
    }
    const YAML::Node s = YAML::LoadFile(summary_path_for(out))["observables"]["obs"];
    h5::File f = h5::File::open_read(out);
    const h5::Group g = f.root().group("observables/obs");

    // Estimates: value and error attributes in HDF5, {value, error, unit, n_eff} in the summary.
    EXPECT_EQ(g.read_doubles("T").at(0), s["T"]["value"].as<double>());
    EXPECT_EQ(s["T"]["error"].as<double>(), 0.125);
    EXPECT_EQ(s["T"]["unit"].as<std::string>(), "energy");
    EXPECT_EQ(s["T"]["n_eff"].as<double>(), 42);  // rounded in the summary
    EXPECT_FALSE(s["T"]["converged"].as<bool>());
    // A name with '/' nests in HDF5 and is one key of the summary.
    EXPECT_EQ(g.read_doubles("middle/gamma").at(0), 5.0);
    EXPECT_EQ(s["middle/gamma"]["value"].as<double>(), 5.0);
    EXPECT_FALSE(s["middle/gamma"]["unit"]);  // dimensionless: no unit in the summary
    // Plain values: {value, unit} with a unit, a bare number without.
    EXPECT_EQ(g.read_doubles("pressure").at(0), s["pressure"]["value"].as<double>());
    EXPECT_EQ(s["pressure"]["unit"].as<std::string>(), "force/length");
    EXPECT_EQ(g.read_doubles("W").at(0), s["W"].as<double>());
    EXPECT_EQ(g.read_int64s("collisions").at(0), 12345);
    EXPECT_EQ(s["collisions"].as<std::int64_t>(), 12345);
    EXPECT_EQ(g.read_int64s("relaxing").at(0), 1);
    EXPECT_TRUE(s["relaxing"].as<bool>());
    EXPECT_EQ(g.read_attr_string("note"), s["note"].as<std::string>());
    // Sub-groups nest in both, or where the summary keys say.
    EXPECT_EQ(g.read_doubles("pairs/a-b/frequency_a").at(0),
              s["pairs"]["a-b"]["frequency_a"]["value"].as<double>());
    EXPECT_EQ(g.read_int64s("a/count").at(0), s["species"]["a"]["count"].as<std::int64_t>());
    EXPECT_FALSE(s["a"]);
    // HDF5 only: file_only values, arrays, histograms.
    EXPECT_EQ(g.read_doubles("bin_width").at(0), 0.5);
    EXPECT_FALSE(s["bin_width"]);
    EXPECT_FALSE(s["profile"]);
    EXPECT_EQ(g.read_doubles("profile"), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(g.read_doubles("h_density"), (std::vector<double>{0.5, 0.5}));
    EXPECT_FALSE(s["h_edges"]);
}

// The wrapper reads attributes of groups only; those of a dataset through the C API.
double dataset_attr(const std::string& file, const std::string& object, const std::string& name) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t a = H5Aopen_by_name(f, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    double v = std::nan("");
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    H5Fclose(f);
    return v;
}

TEST_F(ResultSinkTest, EstimateCarriesWhatItsErrorRestsOn) {
    const std::string out = path("r.h5");
    const Estimate e{1.0, 0.5, 2.0, 10.4, 42, true};
    const Estimate unknown{3.0, std::nan("")};
    {
        ResultSink sink(out);
        sink.root().estimate("x", e, "length");
        sink.root().estimate("y", unknown, "");
        sink.finish();
    }
    EXPECT_EQ(dataset_attr(out, "x", "error"), 0.5);
    EXPECT_EQ(dataset_attr(out, "x", "tau_int"), 2.0);
    EXPECT_EQ(dataset_attr(out, "x", "n_eff"), 10.4);  // rounded in the summary only
    EXPECT_EQ(dataset_attr(out, "x", "samples"), 42.0);
    EXPECT_EQ(dataset_attr(out, "x", "converged"), 1.0);
    const YAML::Node s = YAML::LoadFile(summary_path_for(out));
    EXPECT_EQ(s["x"]["n_eff"].as<double>(), 10);
    EXPECT_FALSE(s["x"]["converged"]);  // only when the error is a lower bound
    EXPECT_FALSE(s["y"]["n_eff"]);      // unknown: left out of the summary
    EXPECT_TRUE(std::isnan(s["y"]["error"].as<double>()));
    EXPECT_TRUE(std::isnan(dataset_attr(out, "y", "n_eff")));
}

TEST_F(ResultSinkTest, SeriesGrowRowByRowAndReadBack) {
    const std::string out = path("r.h5");
    {
        ResultSink sink(out);
        {
            ResultGroup g = sink.root().group("series");
            h5::Appendable t = g.series<double>("time", {}, "time");
            h5::Appendable xy = g.series<double>("xy", {2});
            for (int k = 0; k < 5; ++k) {
                const double tk = 0.5 * k;
                t.append(std::span<const double>(&tk, 1));
                xy.append(std::vector<double>{double(k), -double(k)});
                EXPECT_EQ(xy.rows(), std::size_t(k + 1));
            }
        }
        sink.finish();
    }
    h5::File f = h5::File::open_read(out);
    const h5::Group g = f.root().group("series");
    EXPECT_EQ(g.read_doubles("time"), (std::vector<double>{0, 0.5, 1, 1.5, 2}));
    EXPECT_EQ(g.shape("xy"), (std::vector<std::size_t>{5, 2}));
    EXPECT_EQ(g.read_doubles("xy"), (std::vector<double>{0, 0, 1, -1, 2, -2, 3, -3, 4, -4}));
    EXPECT_FALSE(YAML::LoadFile(summary_path_for(out))["series"]);
}

TEST_F(ResultSinkTest, PartFileExistsWhileWritingAndIsRenamedAtTheEnd) {
    const std::string out = path("sub/dir/r.h5");  // the folder is made
    ResultSink sink(out);
    EXPECT_EQ(sink.part(), out + ".part");
    EXPECT_TRUE(fs::exists(out + ".part"));
    EXPECT_FALSE(fs::exists(out));
    sink.root().value("x", 1.0);
    sink.finish();
    EXPECT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".part"));
    EXPECT_TRUE(fs::exists(path("sub/dir/r.summary.yaml")));
}

TEST_F(ResultSinkTest, FinishRefusesWhileGroupsAreStillOpen) {
    ResultSink sink(path("r.h5"));
    ResultGroup g = sink.root().group("g");
    EXPECT_THROW(sink.finish(), std::logic_error);
}

TEST_F(ResultSinkTest, UnfinishedResultLeavesTheEarlierOneIntact) {
    const std::string out = path("r.h5");
    {
        ResultSink sink(out);
        sink.root().value("x", 1.0);
        sink.finish();
    }
    {
        ResultSink sink(out);  // a run that fails before finishing (an exception, a crash)
        sink.root().value("x", 2.0);
    }
    EXPECT_EQ(h5::File::open_read(out).root().read_doubles("x").at(0), 1.0);
    EXPECT_EQ(YAML::LoadFile(summary_path_for(out))["x"].as<double>(), 1.0);
    EXPECT_EQ(h5::File::open_read(out + ".part").root().read_doubles("x").at(0), 2.0);
}

// A completed result as a run writes it: performance/completed and the summary's status.
void write_result(const std::string& out, bool completed, double x) {
    ResultSink sink(out);
    sink.summary()["status"] = completed ? "completed" : "interrupted";
    sink.root().group("performance").file_only().flag("completed", completed);
    sink.root().value("x", x);
    sink.finish(completed);
}

TEST_F(ResultSinkTest, RunThatDidNotCompleteGoesBesideACompletedResult) {
    const std::string out = path("r.h5");
    write_result(out, true, 1.0);
    ResultSink sink(out);
    sink.summary()["status"] = "interrupted";
    sink.root().value("x", 2.0);
    sink.finish(false);
    EXPECT_EQ(sink.written(), path("r.partial.h5"));
    EXPECT_EQ(sink.summary_file(), path("r.partial.summary.yaml"));
    EXPECT_EQ(h5::File::open_read(out).root().read_doubles("x").at(0), 1.0);
    EXPECT_EQ(YAML::LoadFile(summary_path_for(out))["x"].as<double>(), 1.0);
    EXPECT_EQ(h5::File::open_read(path("r.partial.h5")).root().read_doubles("x").at(0), 2.0);
    EXPECT_EQ(YAML::LoadFile(path("r.partial.summary.yaml"))["x"].as<double>(), 2.0);
    EXPECT_FALSE(fs::exists(out + ".part"));
}

TEST_F(ResultSinkTest, RunThatDidNotCompleteReplacesAnEarlierIncompleteResult) {
    const std::string out = path("r.h5");
    write_result(out, false, 1.0);
    write_result(out, false, 2.0);
    EXPECT_EQ(h5::File::open_read(out).root().read_doubles("x").at(0), 2.0);
    EXPECT_FALSE(fs::exists(path("r.partial.h5")));
}

TEST_F(ResultSinkTest, NonFiniteErrorBarMakesACompletedRunUnreliableAndNamesTheQuantity) {
    const std::string out = path("r.h5");
    {
        ResultSink sink(out);
        sink.summary()["status"] = "completed";
        sink.root()
            .group("observables")
            .group("t")
            .estimate("T", Estimate{1.0, std::numeric_limits<double>::infinity()}, "");
        sink.root().estimate("fine", Estimate{1.0, 0.1}, "");
        EXPECT_EQ(sink.unreliable(), std::vector<std::string>{"/observables/t/T"});
        sink.finish();
    }
    const YAML::Node s = YAML::LoadFile(summary_path_for(out));
    EXPECT_EQ(s["status"].as<std::string>(), "unreliable");
    ASSERT_EQ(s["unreliable"].size(), 1u);
    EXPECT_EQ(s["unreliable"][0].as<std::string>(), "/observables/t/T");
}

TEST_F(ResultSinkTest, FiniteErrorBarsKeepTheStatus) {
    const std::string out = path("r.h5");
    {
        ResultSink sink(out);
        sink.summary()["status"] = "completed";
        sink.root().estimate("x", Estimate{1.0, 0.1}, "");
        sink.finish();
    }
    EXPECT_EQ(YAML::LoadFile(summary_path_for(out))["status"].as<std::string>(), "completed");
}

std::string output_refusal(const std::string& out, const std::vector<std::string>& inputs = {}) {
    try {
        check_output_path(out, inputs);
    } catch (const OutputError& e) {
        return e.what();
    }
    return "";
}

TEST_F(ResultSinkTest, OutputPathIsCheckedBeforeTheRun) {
    EXPECT_EQ(output_refusal(path("new/folder/r.h5")), "");  // the folder is made
    EXPECT_TRUE(fs::is_directory(path("new/folder")));
    EXPECT_NE(output_refusal(dir_.string()).find("expected a result file name ending in .h5"),
              std::string::npos);
    fs::create_directories(path("d.h5"));
    EXPECT_NE(output_refusal(path("d.h5")).find("is a directory"), std::string::npos);
    std::ofstream(path("scene.yaml")) << "dimension: 2\n";
    EXPECT_NE(output_refusal(path("scene.yaml"), {path("scene.yaml")}).find("ending in .h5"),
              std::string::npos);
    std::ofstream(path("in.h5")) << "x";
    EXPECT_NE(output_refusal(path("in.h5"), {path("in.h5")}).find("is the input file"),
              std::string::npos);
    // /proc refuses new files even to root: the probe catches what access(2) would not.
    EXPECT_NE(output_refusal("/proc/gran-test.h5").find("cannot write in the folder '/proc'"),
              std::string::npos);
}

// ---- Through a run ----------------------------------------------------------------------------

const char* kGas = R"(
dimension: 2
seed: 5
species: [{name: a, count: 50}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.1}
drivers: [{type: stochastic_thermostat, strength: 1}]
observables: [{type: temperatures}]
output: {frames: 4}
run: {equilibration: 5, measurement: 20, sample_interval: 1}
)";

RunReport run_text(const std::string& yaml, const std::string& out) {
    RunOptions opt;
    opt.output = out;
    opt.progress = false;
    return run_scene(parse_scene(YAML::Load(yaml), "gas.yaml"), opt);
}

TEST_F(ResultSinkTest, RunAppendsFramesInH5mdLayoutAndRenamesTheResult) {
    const std::string out = path("gas.h5");
    const RunReport rep = run_text(kGas, out);
    ASSERT_TRUE(rep.completed);
    EXPECT_FALSE(fs::exists(out + ".part"));
    h5::File f = h5::File::open_read(out);
    h5::Group all = f.root().group("particles/all");
    EXPECT_EQ(all.shape("position/value"), (std::vector<std::size_t>{4, 50, 2}));
    EXPECT_EQ(all.shape("velocity/value"), (std::vector<std::size_t>{4, 50, 2}));
    // The real step: the engine's events at each frame (after the equilibration's, increasing).
    const auto steps = all.read_int64s("position/step");
    ASSERT_EQ(steps.size(), 4u);
    EXPECT_GT(steps[0], 0);
    for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_GT(steps[k], steps[k - 1]);
    // The frames live in the trajectory beside the result; /particles links to it.
    EXPECT_TRUE(fs::exists(path("gas.trajectory.h5")));
    EXPECT_TRUE(fs::exists(path("gas.trajectory.xdmf")));
    EXPECT_FALSE(fs::exists(path("gas.trajectory.h5.part")));
    EXPECT_EQ(all.read_doubles("velocity/time"), all.read_doubles("position/time"));
    EXPECT_EQ(all.read_int64s("species"), std::vector<std::int64_t>(50, 0));
    EXPECT_EQ(all.group("box").read_attr_double("dimension"), 2.0);
    // Each performance figure once: the same name and value in HDF5 and summary.
    const h5::Group perf = f.root().group("performance");
    const YAML::Node ps = rep.summary["performance"];
    EXPECT_EQ(perf.read_doubles("cpu_time").at(0), ps["cpu_time"]["value"].as<double>());
    EXPECT_EQ(ps["cpu_time"]["unit"].as<std::string>(), "s");
    EXPECT_EQ(perf.read_doubles("wall_time").at(0), ps["wall_time"]["value"].as<double>());
    EXPECT_EQ(perf.read_int64s("events").at(0), ps["events"].as<std::int64_t>());
    EXPECT_EQ(perf.read_attr_string("engine"), ps["engine"].as<std::string>());
    EXPECT_FALSE(ps["cpu_time_s"]);
}

TEST_F(ResultSinkTest, RefusedRunLeavesAnEarlierResultIntact) {
    const std::string out = path("gas.h5");
    ASSERT_TRUE(run_text(kGas, out).completed);
    const auto before = fs::last_write_time(out);
    // Refused (at load: the dem engine has no thermostat) before anything is written.
    std::string dem = kGas;
    dem.replace(dem.find("interactions: {alpha: 0.9}"), 26,
                "interactions: {law: linear_dashpot, stiffness: 100000}\nengine: {type: dem}");
    dem.replace(dem.find("run: {") + 6, 0, "unit: time, ");
    try {
        run_text(dem, out);
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("not available on the dem engine"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(fs::last_write_time(out), before);
    EXPECT_FALSE(fs::exists(out + ".part"));
    EXPECT_EQ(h5::File::open_read(out).root().shape("particles/all/position/value").at(0), 4u);
}

}  // namespace
}  // namespace gran
