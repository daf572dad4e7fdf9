// End-to-end tests of the `gran` program: broken scenes are refused with a message naming
// file:line and the key, runs are reproducible, an interrupted run leaves a valid result, a failed
// run never clobbers an existing result, `gran list` documents the plugins and `--set` works.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "libgran/core/h5.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;

using gran::testing::kGran;
const std::string kDemo = std::string(GRAN_SOURCE_DIR) + "/studies/demo/binary-thermostat-2d.yaml";
const std::string kBadScenes = std::string(GRAN_TEST_DATA) + "/bad_scenes";

// Overrides that turn the demo into a run of a fraction of a second.
const std::vector<std::string> kShortDemo = {
    "--set", "run.measurement=50", "--set", "run.equilibration=5", "--set", "particles=200"};

using gran::testing::Outcome;
using gran::testing::run_gran;

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

using gran::testing::read_text;

// A fresh directory per test, named after the process and the test.
class CliTest : public gran::testing::TempDirTest {
  protected:
    CliTest() : TempDirTest("gran_cli") {}
};

class BadScenes : public CliTest {};
class GoodScene : public CliTest {};
class Run : public CliTest {};
class Cli : public CliTest {};

struct Expectation {
    std::string file;
    int exit_code = 0;
    std::string substring;
    std::string line;  // "-" when the message names no line
};

std::vector<Expectation> read_manifest() {
    std::vector<Expectation> rows;
    std::ifstream in(kBadScenes + "/expected.tsv");
    std::string text;
    while (std::getline(in, text)) {
        if (text.empty() || text[0] == '#') continue;
        std::vector<std::string> cols;
        std::size_t start = 0;
        while (true) {
            const auto tab = text.find('\t', start);
            cols.push_back(text.substr(start, tab - start));
            if (tab == std::string::npos) break;
            start = tab + 1;
        }
        EXPECT_EQ(cols.size(), 4u) << "expected.tsv: bad row: " << text;
        if (cols.size() != 4) continue;
        rows.push_back({cols[0], std::stoi(cols[1]), cols[2], cols[3]});
    }
    return rows;
}

// Names of the datasets below `group` in an HDF5 file (the project's reader has no listing).
std::vector<std::string> dataset_names(const std::string& file, const std::string& group) {
    std::vector<std::string> names;
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) {
        ADD_FAILURE() << "cannot open " << file;
        return names;
    }
    const hid_t g = H5Gopen2(f, group.c_str(), H5P_DEFAULT);
    if (g >= 0) {
        auto visit = [](hid_t loc, const char* name, const H5L_info_t*, void* data) -> herr_t {
            const hid_t obj = H5Oopen(loc, name, H5P_DEFAULT);
            if (obj >= 0) {
                if (H5Iget_type(obj) == H5I_DATASET) {
                    static_cast<std::vector<std::string>*>(data)->push_back(name);
                }
                H5Oclose(obj);
            }
            return 0;
        };
        H5Lvisit(g, H5_INDEX_NAME, H5_ITER_INC, visit, &names);
        H5Gclose(g);
    } else {
        ADD_FAILURE() << "no group " << group << " in " << file;
    }
    H5Fclose(f);
    return names;
}

// Every dataset under /observables, read with gran::h5, keyed by its path.
std::vector<std::pair<std::string, std::vector<double>>> observables_of(const std::string& file) {
    std::vector<std::pair<std::string, std::vector<double>>> out;
    const auto names = dataset_names(file, "/observables");
    auto f = gran::h5::File::open_read(file);
    const gran::h5::Group obs = f.root().group("observables");
    for (const auto& n : names) out.emplace_back(n, obs.read_doubles(n));
    return out;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST_F(BadScenes, EachIsRefusedWithItsExpectedMessageAndExitCode) {
    const auto rows = read_manifest();
    ASSERT_GE(rows.size(), 18u);

    // The manifest lists every scene of the corpus, and each scene says what is wrong with it.
    std::size_t scenes = 0;
    for (const auto& e : fs::directory_iterator(kBadScenes)) {
        if (e.path().extension() != ".yaml") continue;
        ++scenes;
        const std::string name = e.path().filename().string();
        EXPECT_TRUE(std::any_of(rows.begin(), rows.end(), [&](auto& r) { return r.file == name; }))
            << name << " is not listed in expected.tsv";
        EXPECT_EQ(read_text(e.path()).rfind("# ", 0), 0u)
            << name << " does not start with a comment saying what is wrong";
    }
    EXPECT_EQ(scenes, rows.size());

    for (const auto& row : rows) {
        SCOPED_TRACE(row.file);
        const std::string scene = kBadScenes + "/" + row.file;
        ASSERT_TRUE(fs::exists(scene));
        ASSERT_NE(row.exit_code, 0);
        const std::string output = path(fs::path(row.file).stem().string() + ".h5");
        for (const bool run : {false, true}) {
            SCOPED_TRACE(run ? "gran run" : "gran check");
            const Outcome o =
                run ? run_gran({"-q", "run", scene, "-o", output}) : run_gran({"check", scene});
            ASSERT_FALSE(o.signaled) << "killed by signal " << o.signal << "\n" << o.output;
            EXPECT_EQ(o.exit_code, row.exit_code) << o.output;
            EXPECT_NE(o.output.find(row.substring), std::string::npos)
                << "expected the message to contain: " << row.substring << "\ngot: " << o.output;
            if (row.line != "-") {
                const std::string at = scene + ":" + row.line + ":";
                EXPECT_NE(o.output.find(at), std::string::npos)
                    << "expected the message to name " << at << "\ngot: " << o.output;
            }
            EXPECT_FALSE(fs::exists(output)) << "a refused scene left a result file";
            EXPECT_FALSE(fs::exists(output + ".part"));
        }
    }
}

TEST_F(GoodScene, CheckAcceptsTheDemoScene) {
    const Outcome o = run_gran({"check", kDemo});
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find(kDemo + ": ok (2D, "), std::string::npos) << o.output;
}

// `gran check` prints the engine's cost estimate and how long it takes at the rate measured on
// this build, in the engine's unit of work.
TEST_F(GoodScene, CheckPrintsTheEventDrivenCostInEventsAtTheMeasuredRate) {
    const Outcome o = run_gran(concat({"check", kDemo}, kShortDemo));
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("expected cost: about "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find(" events/s measured now"), std::string::npos) << o.output;
}

TEST_F(GoodScene, CheckPrintsTheDemCostInParticleStepsAtTheMeasuredRate) {
    // 40 grains over 150 + 600 time units: particle-steps = 40 x 750 / dt.
    const std::string scene =
        std::string(GRAN_SOURCE_DIR) + "/studies/bhateja-2016/canonical-2d.yaml";
    const Outcome o = run_gran({"check", scene});
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 0) << o.output;
    const std::size_t at = o.output.find("expected cost: about ");
    ASSERT_NE(at, std::string::npos) << o.output;
    double work = 0, steps = 0, dt = 0;
    int particles = 0;
    ASSERT_EQ(std::sscanf(o.output.c_str() + at,
                          "expected cost: about %lf particle-steps (%d particles x %lf steps of "
                          "dt = %lf,",
                          &work, &particles, &steps, &dt),
              4)
        << o.output;
    EXPECT_EQ(particles, 40);
    EXPECT_NEAR(steps * dt / 750, 1.0, 0.05) << o.output;  // printed to 2 and 3 digits
    EXPECT_NEAR(work / (40 * 750 / dt), 1.0, 0.05) << o.output;
    EXPECT_NE(o.output.find(" particle-steps/s measured now"), std::string::npos) << o.output;
}

TEST_F(Run, SameSceneAndSeedGiveIdenticalResults) {
    const std::string a = path("a.h5"), b = path("b.h5"), c = path("c.h5");
    for (const auto& [out, seed] : {std::pair{a, "7"}, std::pair{b, "7"}, std::pair{c, "8"}}) {
        const Outcome o = run_gran(concat(
            {"-q", "run", kDemo, "-o", out, "--set", std::string("seed=") + seed}, kShortDemo));
        ASSERT_FALSE(o.signaled) << o.output;
        ASSERT_EQ(o.exit_code, 0) << o.output;
        ASSERT_TRUE(fs::exists(out));
    }
    const auto ra = observables_of(a), rb = observables_of(b), rc = observables_of(c);
    ASSERT_FALSE(ra.empty());
    ASSERT_EQ(ra.size(), rb.size());
    bool any_difference_with_other_seed = false;
    bool saw_temperature_series = false;
    for (std::size_t k = 0; k < ra.size(); ++k) {
        ASSERT_EQ(ra[k].first, rb[k].first);
        EXPECT_TRUE(bitwise_equal(ra[k].second, rb[k].second))
            << "/observables/" << ra[k].first << " differs between two runs with the same seed";
        if (ra[k].first == "temperatures/series/T_mixture/value") {
            saw_temperature_series = true;
            EXPECT_FALSE(ra[k].second.empty());
        }
        if (k < rc.size() && rc[k].first == ra[k].first &&
            !bitwise_equal(ra[k].second, rc[k].second)) {
            any_difference_with_other_seed = true;
        }
    }
    EXPECT_TRUE(saw_temperature_series);
    EXPECT_TRUE(any_difference_with_other_seed) << "seeds 7 and 8 gave identical observables";
}

// Starts a long run of the demo (with `extra` overrides), sends `sig` once it has been running
// for 1.5 s and checks that it stops promptly with exit code 3 and a valid partial result, in
// long.h5, or in long.partial.h5 beside it when long.h5 already holds a completed result.
void expect_sigterm_leaves_valid_result(const fs::path& dir, const std::vector<std::string>& extra,
                                        int sig = SIGTERM) {
    const std::string out = (dir / "long.h5").string();
    const bool beside_completed = fs::exists(out);
    const std::string partial = beside_completed ? (dir / "long.partial.h5").string() : out;
    const std::string log = (dir / "long.log").string();
    // Long enough never to finish within the test; the equilibration is short so that the
    // measurement (and sampling) is under way when the signal arrives.
    std::vector<std::string> args = concat({kGran, "run", kDemo, "-o", out, "--set",
                                            "run.measurement=1e7", "--set", "run.equilibration=5"},
                                           extra);
    std::vector<char*> argv;
    for (auto& s : args) argv.push_back(s.data());
    argv.push_back(nullptr);

    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0) << "fork failed";
    if (pid == 0) {
        std::FILE* f = std::freopen(log.c_str(), "w", stdout);
        if (f) ::dup2(::fileno(stdout), STDERR_FILENO);
        ::execv(args[0].c_str(), argv.data());
        ::_exit(127);
    }

    // Let it run: it must still be going after 1.5 s.
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) != 0) {
        FAIL() << "gran ended before it was interrupted:\n" << read_text(log);
    }
    ASSERT_EQ(::kill(pid, sig), 0);

    // It must stop promptly (it writes what it measured so far); do not hang the suite if not.
    pid_t done = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 &&
           std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (done == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        FAIL() << "gran did not stop within 10 s of SIGTERM\n" << read_text(log);
    }
    ASSERT_TRUE(WIFEXITED(status)) << "gran died by signal " << WTERMSIG(status) << "\n"
                                   << read_text(log);
    EXPECT_EQ(WEXITSTATUS(status), 3) << read_text(log);
    EXPECT_FALSE(fs::exists(out + ".part"));
    ASSERT_TRUE(fs::exists(partial)) << read_text(log);

    auto file = gran::h5::File::open_read(partial);
    const gran::h5::Group root = file.root();
    EXPECT_EQ(root.read_int64s("performance/interrupted"), std::vector<std::int64_t>{1});
    EXPECT_EQ(root.read_int64s("performance/completed"), std::vector<std::int64_t>{0});
    const auto collisions = root.read_int64s("performance/collisions");
    ASSERT_EQ(collisions.size(), 1u);
    EXPECT_GT(collisions[0], 0);
    const auto t = root.read_doubles("observables/temperatures/series/T_mixture/value");
    const auto time = root.read_doubles("observables/temperatures/series/T_mixture/time");
    EXPECT_FALSE(t.empty());
    EXPECT_EQ(t.size(), time.size());
    for (double x : t) EXPECT_TRUE(x > 0 && std::isfinite(x)) << x;
}

TEST_F(Run, InterruptedBySigtermLeavesValidResult) {
    expect_sigterm_leaves_valid_result(dir_, {});
}

// Frequent thermostat kicks and samples make every EventDrivenEngine::advance call short (fewer
// than 1024 events); the interrupt must still be noticed. Disabled until the engine checks the
// interrupt flag across calls (advance() counts events in a local variable, so short calls never
// look at the flag and SIGTERM is ignored). Run with --gtest_also_run_disabled_tests.
TEST_F(Run, InterruptedBySigtermEvenWithFrequentDriverKicks) {
    expect_sigterm_leaves_valid_result(
        dir_, {"--set", "drivers.0.interval=0.2", "--set", "run.sample_interval=0.5"});
}

// A closed terminal (SIGHUP), a batch system's warning (SIGUSR1) and the CPU-time limit (SIGXCPU)
// end a run the way SIGTERM does, never by the default action that loses everything.
TEST_F(Run, HangupUser1AndCpuLimitStopTheRunLikeSigterm) {
    for (const int sig : {SIGHUP, SIGUSR1, SIGXCPU}) {
        SCOPED_TRACE(strsignal(sig));
        expect_sigterm_leaves_valid_result(dir_, {}, sig);
        fs::remove(path("long.h5"));
    }
}

// The docs promise that a run which did not complete never replaces a result: an interrupted
// rerun writes long.partial.h5 and leaves the completed long.h5 byte for byte.
TEST_F(Run, InterruptedRerunKeepsTheCompletedResultAndWritesBesideIt) {
    const std::string out = path("long.h5");
    const Outcome first = run_gran(concat({"-q", "run", kDemo, "-o", out}, kShortDemo));
    ASSERT_EQ(first.exit_code, 0) << first.output;
    const std::string before = read_text(out),
                      summary_before = read_text(path("long.summary.yaml"));
    expect_sigterm_leaves_valid_result(dir_, {});
    EXPECT_EQ(read_text(out), before);
    EXPECT_EQ(read_text(path("long.summary.yaml")), summary_before);
    const YAML::Node partial = YAML::LoadFile(path("long.partial.summary.yaml"));
    EXPECT_EQ(partial["status"].as<std::string>(), "interrupted");
    EXPECT_EQ(partial["result"].as<std::string>(), path("long.partial.h5"));
}

TEST_F(Run, FailedRunDoesNotClobberExistingResult) {
    const std::string out = path("precious.h5");
    const std::string content = "an earlier result that must survive\n";
    {
        std::ofstream f(out, std::ios::binary);
        f << content;
    }
    const Outcome o =
        run_gran({"-q", "run", kBadScenes + "/random_placement_unreachable.yaml", "-o", out});
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find("random placement failed"), std::string::npos) << o.output;
    EXPECT_EQ(read_text(out), content);
    EXPECT_FALSE(fs::exists(out + ".part"));
}

TEST_F(Cli, ListDocumentsEveryPlugin) {
    const Outcome o = run_gran({"list"});
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 0) << o.output;
    for (const char* name :
         {"stochastic_thermostat", "temperatures", "velocity_pdf", "constant_restitution"}) {
        EXPECT_NE(o.output.find(std::string("  ") + name + ":"), std::string::npos)
            << name << " is not documented:\n"
            << o.output;
    }
    // A parameter line (name, type and range, default) followed by its doc line.
    EXPECT_NE(o.output.find("alpha              a real number in (0, 1] (default 1)"),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("normal restitution coefficient alpha_ij"), std::string::npos);

    const Outcome bad = run_gran({"list", "bogus"});
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
}

TEST_F(Cli, SetOverridesAKey) {
    const std::string out = path("set.h5");
    const Outcome o = run_gran(concat(
        {"-q", "run", kDemo, "-o", out, "--set", "seed=4242"},
        {"--set", "run.measurement=20", "--set", "run.equilibration=2", "--set", "particles=300"}));
    ASSERT_FALSE(o.signaled) << o.output;
    ASSERT_EQ(o.exit_code, 0) << o.output;

    auto file = gran::h5::File::open_read(out);
    const YAML::Node scene = YAML::Load(file.root().read_string("parameters/scene"));
    EXPECT_EQ(scene["seed"].as<std::uint64_t>(), 4242u);
    EXPECT_EQ(scene["particles"].as<std::int64_t>(), 300);
    EXPECT_DOUBLE_EQ(scene["run"]["measurement"].as<double>(), 20.0);
    std::int64_t total = 0;
    for (const auto& s : scene["species"]) total += s["count"].as<std::int64_t>();
    EXPECT_EQ(total, 300);

    for (const auto& cmd : {std::string("check"), std::string("run")}) {
        std::vector<std::string> args = {"-q", cmd, kDemo, "--set", "seed4242"};
        if (cmd == "run") args = concat(args, {"-o", path("bad_set.h5")});
        const Outcome bad = run_gran(args);
        ASSERT_FALSE(bad.signaled) << bad.output;
        EXPECT_EQ(bad.exit_code, 2) << cmd << ": " << bad.output;
        EXPECT_NE(bad.output.find("--set 'seed4242': expected key=value"), std::string::npos)
            << bad.output;
    }
    EXPECT_FALSE(fs::exists(path("bad_set.h5")));
}

}  // namespace
