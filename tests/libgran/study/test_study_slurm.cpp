// `gran study --slurm` without a cluster (libgran/study/study_slurm.hpp): the scripts it writes
// (array size, time-limit warning, resubmission, merge after the array), an array task running
// exactly its runs, `--status`, and merge jobs that run at the same time. The real cluster is `make
// test-cluster` (tests/cluster/test_slurm_study.sh).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "libgran/study/study_merge.hpp"
#include "libgran/study/study_slurm.hpp"
#include "tests/support/gran_process.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::read_text;
using gran::testing::run_gran;

class StudySlurm : public gran::testing::TempDirTest {
  protected:
    StudySlurm() : TempDirTest("gran_study_slurm") {}
    void SetUp() override {
        TempDirTest::SetUp();
        std::ofstream(path("gas.yaml")) << "dimension: 2\nspecies: [{name: a, count: 50}]\n"
                                           "box: {packing_fraction: 0.05}\n"
                                           "drivers: [{type: stochastic_thermostat, strength: "
                                           "0.01}]\nobservables: [{type: temperatures}]\n"
                                           "run: {equilibration: 5, measurement: 50}\n";
        std::ofstream(path("study.yaml")) << "scene: gas.yaml\nreplicas: 5\n";
    }
};

TEST(SlurmTasks, CountRoundsUpToWholeTasks) {
    EXPECT_EQ(gran::slurm_task_count(5, 1), 5);
    EXPECT_EQ(gran::slurm_task_count(5, 2), 3);
    EXPECT_EQ(gran::slurm_task_count(6, 2), 3);
    EXPECT_EQ(gran::slurm_task_count(1, 4), 1);
}

TEST_F(StudySlurm, DryRunWritesAnArrayThatCheckpointsResubmitsAndAMergeAfterIt) {
    const auto r = run_gran({"study", path("study.yaml"), "-o", path("out"), "--slurm",
                             "--runs-per-task", "2", "--time", "0:30:00", "--partition", "short",
                             "--signal-seconds", "90", "--dry-run"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string array = read_text(fs::path(path("out")) / "slurm" / "study.array.sh");
    const std::string merge = read_text(fs::path(path("out")) / "slurm" / "study.merge.sh");
    EXPECT_NE(array.find("#SBATCH --array=0-2\n"), std::string::npos) << array;  // 5 runs, 2 each
    EXPECT_NE(array.find("#SBATCH --time=0:30:00\n"), std::string::npos) << array;
    EXPECT_NE(array.find("#SBATCH --partition=short\n"), std::string::npos) << array;
    EXPECT_NE(array.find("#SBATCH --signal=B:TERM@90\n"), std::string::npos) << array;
    EXPECT_NE(array.find("--slurm-task \"$SLURM_ARRAY_TASK_ID\" --runs-per-task 2"),
              std::string::npos)
        << array;
    // Stopped by the warning (exit 3): the task and a merge after it are submitted again.
    EXPECT_NE(array.find("if [ \"$code\" -eq 3 ]"), std::string::npos) << array;
    EXPECT_NE(array.find("sbatch --parsable --array=\"$SLURM_ARRAY_TASK_ID\""), std::string::npos)
        << array;
    EXPECT_NE(merge.find("--merge-only"), std::string::npos) << merge;
    // Nothing submitted, nothing run.
    EXPECT_FALSE(fs::exists(fs::path(path("out")) / "slurm" / "jobs.txt"));
    EXPECT_FALSE(fs::exists(fs::path(path("out")) / "gas_r1.h5"));
}

TEST_F(StudySlurm, AnArrayTaskRunsItsRunsOnlyAndStatusCountsThem) {
    const auto r = run_gran({"-q", "study", path("study.yaml"), "-o", path("out"), "--slurm-task",
                             "1", "--runs-per-task", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (int k = 1; k <= 5; ++k) {
        const bool mine = k == 3 || k == 4;  // task 1 of 2 runs each: runs 2 and 3 (from 0)
        EXPECT_EQ(fs::exists(path("out") + "/gas_r" + std::to_string(k) + ".h5"), mine) << k;
    }
    const auto status = run_gran({"study", path("study.yaml"), "-o", path("out"), "--status"});
    ASSERT_EQ(status.exit_code, 0) << status.output;
    EXPECT_NE(status.output.find("complete: 2"), std::string::npos) << status.output;
    EXPECT_NE(status.output.find("not started: 3 (gas_r1, gas_r2, gas_r5)"), std::string::npos)
        << status.output;
    // The merge job's command: the two complete runs, nothing run.
    const auto merge =
        run_gran({"-q", "study", path("study.yaml"), "-o", path("out"), "--merge-only"});
    ASSERT_EQ(merge.exit_code, 0) << merge.output;
    EXPECT_NE(merge.output.find("0 ran, 2 reused, 0 failed"), std::string::npos) << merge.output;
    EXPECT_FALSE(fs::exists(path("out") + "/gas_r1.h5"));
}

// The array's merge job and a resubmitted task's merge job can start together: the second waits
// for the first (StudyMergeLock) instead of writing the same merged file at once, and decides
// which runs are complete only once it has the lock, so it merges a run that ended meanwhile.
TEST_F(StudySlurm, AMergeJobWaitsForAnotherMergeOfTheStudyAndThenSeesEveryCompleteRun) {
    const auto task = run_gran({"-q", "study", path("study.yaml"), "-o", path("out"),
                                "--slurm-task", "0", "--runs-per-task", "4"});
    ASSERT_EQ(task.exit_code, 0) << task.output;
    std::optional<gran::StudyMergeLock> other;
    other.emplace(gran::load_study(path("study.yaml")), path("out"));
    gran::testing::GranProcess merge(
        {"-q", "study", path("study.yaml"), "-o", path("out"), "--merge-only"}, path("merge.log"));
    ASSERT_TRUE(merge.started());
    EXPECT_FALSE(merge.wait_up_to(1.5)) << read_text(path("merge.log"));
    EXPECT_FALSE(fs::exists(path("out") + "/study.study.h5"));
    // The fifth run ends while the merge waits.
    const auto last = run_gran({"-q", "study", path("study.yaml"), "-o", path("out"),
                                "--slurm-task", "4", "--runs-per-task", "1"});
    ASSERT_EQ(last.exit_code, 0) << last.output;
    other.reset();
    ASSERT_TRUE(merge.wait_up_to(60));
    const std::string log = read_text(path("merge.log"));
    EXPECT_EQ(merge.exit_code(), 0) << log;
    EXPECT_NE(log.find("0 ran, 5 reused, 0 failed"), std::string::npos) << log;
    EXPECT_TRUE(fs::exists(path("out") + "/study.study.h5"));
}

}  // namespace
