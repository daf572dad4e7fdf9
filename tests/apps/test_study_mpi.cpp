// `mpirun -np 2 gran study` (issue 18, apps/gran/study_mpi.cpp): the runs spread over two ranks,
// each run recording its rank, and a merged study whose observables are bit for bit those of the
// same study run locally. Built only when CMake found MPI (GRAN_MPIEXEC).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "libgran/core/h5.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

#ifdef GRAN_MPIEXEC
namespace {

namespace fs = std::filesystem;
using gran::testing::run_command;
using gran::testing::run_gran;

class StudyMpi : public gran::testing::TempDirTest {
  protected:
    StudyMpi() : TempDirTest("gran_study_mpi") {}
    void SetUp() override {
        TempDirTest::SetUp();
        std::ofstream(path("gas.yaml")) << "dimension: 2\nspecies: [{name: a, count: 100}]\n"
                                           "interactions: {alpha: 0.9}\n"
                                           "box: {packing_fraction: 0.05}\n"
                                           "drivers: [{type: stochastic_thermostat, strength: "
                                           "0.01}]\nobservables: [{type: temperatures}]\n"
                                           "run: {equilibration: 10, measurement: 300}\n";
        std::ofstream(path("study.yaml"))
            << "scene: gas.yaml\nreplicas: 3\ngrid: {interactions.alpha: [0.8, 0.9]}\n";
    }
    // mpirun as root needs its consent; --oversubscribe: more ranks than this machine's slots.
    gran::testing::Outcome mpirun(const std::vector<std::string>& args) const {
        // A sanitized build: OpenMPI's own never-freed allocations are not gran's leaks.
        const std::string lsan =
            "LSAN_OPTIONS=fast_unwind_on_malloc=0:suppressions=" + std::string(GRAN_SOURCE_DIR) +
            "/tests/support/lsan_openmpi.supp";
        std::vector<std::string> all{"env",
                                     "OMPI_ALLOW_RUN_AS_ROOT=1",
                                     "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                                     lsan,
                                     GRAN_MPIEXEC,
                                     "-np",
                                     "2",
                                     "--oversubscribe",
                                     gran::testing::kGran};
        all.insert(all.end(), args.begin(), args.end());
        return run_command(all);
    }
};

TEST_F(StudyMpi, TwoRanksMergeObservablesBitIdenticalToALocalStudyAndRecordTheirRanks) {
    const auto local = run_gran({"-q", "study", path("study.yaml"), "-o", path("local")});
    ASSERT_EQ(local.exit_code, 0) << local.output;
    const auto mpi = mpirun({"-q", "study", path("study.yaml"), "-o", path("mpi")});
    ASSERT_EQ(mpi.exit_code, 0) << mpi.output;
    EXPECT_NE(mpi.output.find("6 ran, 0 reused, 0 failed; 2 MPI ranks"), std::string::npos)
        << mpi.output;
    // Every run's observables, datasets and attributes, bit for bit.
    const auto same =
        run_command({"/usr/bin/python3",
                     std::string(GRAN_SOURCE_DIR) + "/tests/regression/compare_result_dirs.py",
                     path("mpi"), path("local")});
    EXPECT_EQ(same.exit_code, 0) << same.output;
    EXPECT_NE(same.output.find("6 of 6 common runs bit-identical"), std::string::npos)
        << same.output;
    // The merged summary: the same numbers, and where each run ran (-1: no MPI).
    gran::h5::File a = gran::h5::File::open_read(path("local") + "/study.study.h5");
    gran::h5::File b = gran::h5::File::open_read(path("mpi") + "/study.study.h5");
    const std::string t = "summary/quantities/observables.temperatures.T_mixture/value";
    EXPECT_EQ(a.root().read_doubles(t), b.root().read_doubles(t));
    const auto local_ranks = a.root().read_int64s("summary/placement/mpi_rank");
    EXPECT_TRUE(std::all_of(local_ranks.begin(), local_ranks.end(),
                            [](std::int64_t r) { return r == -1; }));
    const auto ranks = b.root().read_int64s("summary/placement/mpi_rank");
    ASSERT_EQ(ranks.size(), 6u);
    for (std::int64_t r : ranks) EXPECT_TRUE(r == 0 || r == 1) << r;
    // Run again under mpirun: every result is reused, nothing runs.
    const auto again = mpirun({"-q", "study", path("study.yaml"), "-o", path("mpi")});
    EXPECT_NE(again.output.find("0 ran, 6 reused, 0 failed"), std::string::npos) << again.output;
}

TEST_F(StudyMpi, AFailingRunIsRecordedAndTheOthersGoOn) {
    // Every scene is valid (a bad one is refused before anything runs); one run fails at run
    // time instead: a folder stands where it writes its result.
    std::ofstream(path("study.yaml")) << "scene: gas.yaml\nreplicas: 3\n";
    fs::create_directories(path("mpi"));
    fs::create_directories(path("mpi") + "/gas_r2.h5.part");  // gas_r2 cannot write its result
    const auto mpi = mpirun({"-q", "study", path("study.yaml"), "-o", path("mpi")});
    EXPECT_EQ(mpi.exit_code, 1) << mpi.output;
    EXPECT_NE(mpi.output.find("2 ran, 0 reused, 1 failed"), std::string::npos) << mpi.output;
    EXPECT_TRUE(fs::exists(path("mpi") + "/gas_r1.h5"));
    EXPECT_TRUE(fs::exists(path("mpi") + "/gas_r3.h5"));
}

}  // namespace
#endif
