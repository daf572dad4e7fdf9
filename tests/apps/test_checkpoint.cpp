// Checkpoint and resume through the command line (issue 13; docs/reliability.md): a run killed
// with SIGKILL at seeded random moments and resumed each time gives the result of a run never
// interrupted, bit for bit (observables, drivers and trajectory frames;
// libgran/run/checkpoint.hpp). Both engines: a thermostat, moving walls with rotation (rough
// spheres, event-driven) and with friction and contact history (DEM); every driver and observable
// is in one of the scenes.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/run/checkpoint.hpp"
#include "tests/support/gran_process.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::GranProcess;
using gran::testing::read_text;
using gran::testing::run_gran;

const std::string kScenes = std::string(GRAN_TEST_DATA) + "/checkpoint/";

class Checkpoint : public gran::testing::TempDirTest {
  protected:
    Checkpoint() : TempDirTest("gran_checkpoint") {}

    // The uninterrupted run, without checkpoints, into ref/; its wall-clock time in reference_s_.
    void run_reference(const std::string& scene) {
        fs::create_directories(dir_ / "ref");
        const auto start = std::chrono::steady_clock::now();
        const auto r = run_gran({"run", kScenes + scene, "-o", path("ref/r.h5"), "-q", "--set",
                                 "run.checkpoint.interval=0"});
        reference_s_ =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    double reference_s_ = 0;

    // Bit identity of run/r.h5 and ref/r.h5: every dataset and attribute under /observables,
    // /drivers and /particles (tests/regression/compare_result_dirs.py).
    void expect_identical_to_reference() {
        const auto r = gran::testing::run_command(
            {"/usr/bin/python3",
             std::string(GRAN_SOURCE_DIR) + "/tests/regression/compare_result_dirs.py", path("run"),
             path("ref")});
        EXPECT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("1 of 1 common runs bit-identical"), std::string::npos) << r.output;
    }

    std::int64_t performance(const std::string& name) const {
        const auto f = gran::h5::File::open_read(path("run/r.h5"));
        return f.root().read_int64s("performance/" + name).at(0);
    }

    // Waits until the run has written its first checkpoint (at most 60 s), or has ended.
    static void wait_for_first_checkpoint(GranProcess& p, const std::string& out) {
        for (int poll = 0; poll < 6000 && !fs::exists(gran::checkpoint_path_for(out)); ++poll)
            if (p.wait_up_to(0.01)) return;  // ended: nothing left to kill
    }

    // Starts the run (or resumes it once a checkpoint exists), kills it with SIGKILL after a
    // seeded random delay, `kills` times, then lets the last resume finish. Returns the kills
    // that hit a running process. The delays scale with the reference run's wall-clock time, so
    // that the 20 sessions cover at most about two thirds of the run on a fast or a slow machine
    // (each session makes less progress than its delay: start-up, and the work since its last
    // checkpoint, checkpoints every 0.05 s).
    int kill_loop(const std::string& scene, int kills, std::uint64_t seed) {
        fs::create_directories(dir_ / "run");
        const std::string out = path("run/r.h5"), log = path("run/log");
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> delay(0.06 + 0.01 * reference_s_,
                                                     0.06 + 0.05 * reference_s_);  // s
        int killed = 0;
        for (int attempt = 0; attempt < 10 * kills; ++attempt) {
            const bool resume = fs::exists(gran::checkpoint_path_for(out));
            const std::vector<std::string> args =
                resume ? std::vector<std::string>{"run", "--resume", out, "-q"}
                       : std::vector<std::string>{"run", kScenes + scene, "-o", out, "-q"};
            GranProcess p(args, log);
            // Under load (ctest -j2 beside a heavy test) start-up can outlast every drawn delay;
            // then all kills land before the first checkpoint and the loop never resumes. So once
            // half the kills have passed without a checkpoint, a fresh session first waits for its
            // first checkpoint (or its end), then draws its delay.
            if (!resume && killed >= kills / 2 && killed < kills) wait_for_first_checkpoint(p, out);
            if (killed < kills && !p.wait_up_to(delay(rng))) {
                p.send(SIGKILL);
                EXPECT_TRUE(p.wait_up_to(60));
                EXPECT_EQ(p.signal(), SIGKILL);
                ++killed;
                continue;
            }
            EXPECT_TRUE(p.wait_up_to(600)) << "the last resume did not finish";
            EXPECT_EQ(p.exit_code(), 0) << read_text(log);
            break;
        }
        EXPECT_FALSE(fs::exists(gran::checkpoint_path_for(out))) << "left behind after the end";
        EXPECT_FALSE(fs::exists(out + ".frames.part")) << "left behind after the end";
        return killed;
    }

    void expect_kill_loop_bit_identical(const std::string& scene, std::uint64_t seed) {
        run_reference(scene);
        if (HasFatalFailure()) return;
        const int killed = kill_loop(scene, 20, seed);
        EXPECT_EQ(killed, 20) << "the run ended before it was killed 20 times: lengthen " << scene;
        expect_identical_to_reference();
        EXPECT_GE(performance("resumes"), 1);
        EXPECT_GE(performance("checkpoints"), performance("resumes"));
    }
};

TEST_F(Checkpoint, ThermostatRunKilledTwentyTimesIsBitIdenticalOnTheEventDrivenEngine) {
    expect_kill_loop_bit_identical("thermostat_event_driven.yaml", 1);
}

TEST_F(Checkpoint, VibratedRoughSpheresKilledTwentyTimesAreBitIdenticalOnTheEventDrivenEngine) {
    expect_kill_loop_bit_identical("vibrated_rough_event_driven.yaml", 2);
}

TEST_F(Checkpoint, VibratedFrictionalBedKilledTwentyTimesIsBitIdenticalOnTheDemEngine) {
    expect_kill_loop_bit_identical("vibrated_frictional_dem.yaml", 3);
}

// SIGTERM: the run writes its partial result (exit 3) and a checkpoint; the resume completes it.
void interrupt_then_resume(const std::string& scene, const std::string& out, const std::string& log,
                           double after) {
    {
        GranProcess p({"run", kScenes + scene, "-o", out, "-q"}, log);
        ASSERT_FALSE(p.wait_up_to(after)) << "ended before the signal: " << read_text(log);
        // And not before the run is under way (its partial result exists, so its signal handler
        // is in place): a sanitized build takes longer than `after` to start (0.7 s for
        // `gran --version` under ASan), and a signal before main() kills the process.
        for (int poll = 0; poll < 6000 && !fs::exists(out + ".part"); ++poll)
            ASSERT_FALSE(p.wait_up_to(0.01)) << "ended before the signal: " << read_text(log);
        p.send(SIGTERM);
        ASSERT_TRUE(p.wait_up_to(60));
        ASSERT_EQ(p.exit_code(), 3) << read_text(log);
    }
    ASSERT_TRUE(fs::exists(gran::checkpoint_path_for(out)));
    const auto r = run_gran({"run", "--resume", out, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(Checkpoint, InterruptedRunWithThermalSawtoothAndStaticWallsResumesBitIdentically) {
    run_reference("walls_event_driven.yaml");
    fs::create_directories(dir_ / "run");
    interrupt_then_resume("walls_event_driven.yaml", path("run/r.h5"), path("run/log"), 0.8);
    expect_identical_to_reference();
    EXPECT_EQ(performance("resumes"), 1);
}

// A run with a target (run.target_error) interrupted between its looks and resumed stops at the
// same look with the same observables as a run never interrupted: the looks, the target's state
// and the open-ended blocks of the velocity distributions are in the checkpoint.
TEST_F(Checkpoint, InterruptedRunWithATargetStopsAtTheSameLookAsAnUninterruptedOne) {
    run_reference("target_event_driven.yaml");
    if (HasFatalFailure()) return;
    fs::create_directories(dir_ / "run");
    interrupt_then_resume("target_event_driven.yaml", path("run/r.h5"), path("run/log"),
                          0.1 + 0.3 * reference_s_);
    expect_identical_to_reference();
    EXPECT_EQ(performance("resumes"), 1);
    const YAML::Node ref = YAML::LoadFile(path("ref/r.summary.yaml"))["target"];
    const YAML::Node run = YAML::LoadFile(path("run/r.summary.yaml"))["target"];
    EXPECT_EQ(run["status"].as<std::string>(), "reached");
    EXPECT_EQ(run["looks"].as<int>(), ref["looks"].as<int>());
    EXPECT_GE(ref["looks"].as<int>(), 4);
    EXPECT_EQ(run["measured"]["value"].as<double>(), ref["measured"]["value"].as<double>());
}

// The threads of a dem run change no bit (docs/performance.md), so a resume may ask for another
// number: interrupted with one thread, resumed with engine.threads=2 and the scene given beside
// the checkpoint. (This scene is smaller than one thread's share, so it still runs on one; the
// split itself across a checkpoint is
// DemThreads.CheckpointOfOneThreadContinuesBitIdenticallyOnTwo.)
TEST_F(Checkpoint, DemRunResumesBitIdenticallyWithAnotherThreadCount) {
    run_reference("vibrated_frictional_dem.yaml");
    if (HasFatalFailure()) return;
    fs::create_directories(dir_ / "run");
    const std::string out = path("run/r.h5"), log = path("run/log");
    {
        GranProcess p({"run", kScenes + "vibrated_frictional_dem.yaml", "-o", out, "-q"}, log);
        ASSERT_FALSE(p.wait_up_to(0.1 + 0.4 * reference_s_)) << "ended early: " << read_text(log);
        p.send(SIGTERM);
        ASSERT_TRUE(p.wait_up_to(60));
        ASSERT_EQ(p.exit_code(), 3) << read_text(log);
    }
    const auto r = run_gran({"run", "--resume", out, kScenes + "vibrated_frictional_dem.yaml",
                             "--set", "engine.threads=2", "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_identical_to_reference();
    EXPECT_EQ(performance("resumes"), 1);
}

TEST_F(Checkpoint, InterruptedFreeCoolingResumesBitIdentically) {
    run_reference("free_cooling_event_driven.yaml");
    fs::create_directories(dir_ / "run");
    interrupt_then_resume("free_cooling_event_driven.yaml", path("run/r.h5"), path("run/log"), 0.5);
    expect_identical_to_reference();
}

// SIGKILL leaves no result, only the checkpoint: --recover writes what was measured up to it
// (the uninterrupted run's first samples, bit for bit) without running, keeps the checkpoint,
// and --resume still completes the run bit-identically.
TEST_F(Checkpoint, KilledRunIsRecoveredUpToItsCheckpointAndStillResumesBitIdentically) {
    run_reference("thermostat_event_driven.yaml");
    if (HasFatalFailure()) return;
    fs::create_directories(dir_ / "run");
    const std::string out = path("run/r.h5");
    {
        GranProcess p({"run", kScenes + "thermostat_event_driven.yaml", "-o", out, "-q"},
                      path("run/log"));
        ASSERT_FALSE(p.wait_up_to(0.1 + 0.4 * reference_s_)) << read_text(path("run/log"));
        p.send(SIGKILL);
        ASSERT_TRUE(p.wait_up_to(60));
    }
    ASSERT_FALSE(fs::exists(out));
    const auto rec = run_gran({"run", "--recover", out, "-q"});
    ASSERT_EQ(rec.exit_code, 3) << rec.output;
    EXPECT_NE(read_text(path("run/r.summary.yaml")).find("status: interrupted"), std::string::npos);
    EXPECT_TRUE(fs::exists(gran::checkpoint_path_for(out))) << "recover must keep the checkpoint";
    {
        const auto got = gran::h5::File::open_read(out).root();
        const auto ref = gran::h5::File::open_read(path("ref/r.h5")).root();
        const std::int64_t samples = got.read_int64s("performance/samples").at(0);
        EXPECT_GT(samples, 0) << "killed before the first measurement sample: kill later";
        EXPECT_LT(samples, ref.read_int64s("performance/samples").at(0));
        const auto e = got.read_doubles("observables/kinetic_energy/energy_per_particle/value");
        const auto e_ref = ref.read_doubles("observables/kinetic_energy/energy_per_particle/value");
        ASSERT_EQ(e.size(), std::size_t(50 + samples));  // 100 / 2 equilibration samples
        EXPECT_TRUE(std::equal(e.begin(), e.end(), e_ref.begin()));
    }
    const auto r = run_gran({"run", "--resume", out, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_identical_to_reference();
}

TEST_F(Checkpoint, ResumeRefusesAMissingCheckpointNamingIt) {
    const auto r = run_gran({"run", "--resume", path("none.h5")});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(path("none.h5.checkpoint") + ": no checkpoint to resume from"),
              std::string::npos)
        << r.output;
}

// A checkpoint of the thermostat scene, interrupted.
class WrittenCheckpoint : public Checkpoint {
  protected:
    void SetUp() override {
        Checkpoint::SetUp();
        interrupt_then_resume_prefix();
    }
    void interrupt_then_resume_prefix() {
        GranProcess p({"run", kScenes + "thermostat_event_driven.yaml", "-o", path("r.h5"), "-q"},
                      path("log"));
        ASSERT_FALSE(p.wait_up_to(0.6)) << read_text(path("log"));
        p.send(SIGTERM);
        ASSERT_TRUE(p.wait_up_to(60));
        ASSERT_EQ(p.exit_code(), 3) << read_text(path("log"));
        ckpt_ = gran::checkpoint_path_for(path("r.h5"));
        ASSERT_TRUE(fs::exists(ckpt_));
    }
    std::string ckpt_;
};

TEST_F(WrittenCheckpoint, ResumeRefusesACheckpointOfAnotherCodeVersion) {
    gran::Checkpoint c = gran::read_checkpoint(ckpt_);
    c.header.code_id = "0.0.1+000000000000";
    gran::write_checkpoint(ckpt_, c);
    const auto r = run_gran({"run", "--resume", path("r.h5")});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("written by gran 0.0.1+000000000000"), std::string::npos) << r.output;
}

TEST_F(WrittenCheckpoint, ResumeRefusesADamagedCheckpoint) {
    std::string bytes = read_text(ckpt_);
    bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x10);
    std::ofstream(ckpt_, std::ios::binary) << bytes;
    const auto r = run_gran({"run", "--resume", path("r.h5")});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("damaged checkpoint"), std::string::npos) << r.output;
}

TEST_F(WrittenCheckpoint, ResumeRefusesAnotherSceneNamingTheDifference) {
    const auto r = run_gran({"run", "--resume", path("r.h5"),
                             kScenes + "thermostat_event_driven.yaml", "--set", "seed=8"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("the scene differs from the checkpoint's"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("seed: 7"), std::string::npos) << r.output;
}

TEST_F(WrittenCheckpoint, ResumeAcceptsTheSameSceneWithAnotherCheckpointInterval) {
    const auto r =
        run_gran({"run", "--resume", path("r.h5"), kScenes + "thermostat_event_driven.yaml",
                  "--set", "run.checkpoint.interval=600", "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_FALSE(fs::exists(ckpt_));
}

}  // namespace
