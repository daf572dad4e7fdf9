// End-to-end tests of what surrounds a run (issue 13): `gran --version` and the provenance of a
// result, command-line errors exit 2 like the README says, output paths are checked before the run
// starts, and a full disk is an error naming the path that leaves any earlier result intact.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "libgran/core/build_info.hpp"
#include "libgran/core/h5.hpp"
#include "tests/support/run_gran.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace {

namespace fs = std::filesystem;
using gran::testing::Outcome;
using gran::testing::run_gran;

const std::string kDemo = std::string(GRAN_SOURCE_DIR) + "/studies/demo/binary-thermostat-2d.yaml";
const std::vector<std::string> kShort = {
    "--set", "run.measurement=20", "--set", "run.equilibration=2", "--set", "particles=100"};

std::vector<std::string> with_short(std::vector<std::string> args) {
    args.insert(args.end(), kShort.begin(), kShort.end());
    return args;
}

using gran::testing::read_text;

class CliSafety : public gran::testing::TempDirTest {
  protected:
    CliSafety() : TempDirTest("gran_cli_safety") {}
};

TEST_F(CliSafety, VersionPrintsVersionCommitAndBuildType) {
    const Outcome o = run_gran({"--version"});
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const gran::BuildInfo& b = gran::build_info();
    EXPECT_NE(o.output.find(std::string("gran ") + b.version), std::string::npos) << o.output;
    EXPECT_TRUE(std::regex_search(o.output, std::regex("commit ([0-9a-f]{40}|unknown)")))
        << o.output;
    EXPECT_NE(o.output.find(std::string("build ") + b.build_type), std::string::npos) << o.output;
}

TEST_F(CliSafety, EveryResultRecordsTheCodeThatMadeIt) {
    const std::string out = path("r.h5");
    const Outcome o = run_gran(with_short({"-q", "run", kDemo, "-o", out}));
    ASSERT_EQ(o.exit_code, 0) << o.output;
    gran::h5::File f = gran::h5::File::open_read(out);
    gran::h5::Group code = f.root().group("provenance");
    const gran::BuildInfo& b = gran::build_info();
    EXPECT_EQ(code.read_attr_string("code_id"), b.code_id());
    EXPECT_EQ(code.read_attr_string("commit"), b.commit);
    EXPECT_EQ(code.read_attr_string("build_type"), b.build_type);
    EXPECT_EQ(code.read_attr_double("dirty"), b.dirty ? 1.0 : 0.0);
    const YAML::Node s = YAML::LoadFile(path("r.summary.yaml"));
    EXPECT_EQ(s["code"]["commit"].as<std::string>(), b.commit);
    EXPECT_EQ(s["code"]["dirty"].as<bool>(), b.dirty);
}

// CLI11's own exit codes (106 for a missing argument, 109 for an extra one) are not the README's.
TEST_F(CliSafety, CommandLineErrorsExitTwoWithAMessage) {
    const std::vector<std::vector<std::string>> wrong = {
        {"run"},                                  // the scene is required
        {"run", kDemo, "surplus"},                // an extra argument
        {"bogus"},                                // no such command
        {"run", kDemo, "--no-such-option"},       // no such option
        {"--log-level", "bogus", "check", kDemo}  // no such log level
    };
    for (const auto& args : wrong) {
        SCOPED_TRACE(args.front());
        const Outcome o = run_gran(args);
        ASSERT_FALSE(o.signaled) << o.output;
        EXPECT_EQ(o.exit_code, 2) << o.output;
        EXPECT_FALSE(o.output.empty());
    }
    const Outcome level = run_gran({"--log-level", "bogus", "check", kDemo});
    EXPECT_NE(level.output.find("bogus"), std::string::npos) << level.output;
    EXPECT_EQ(run_gran({"--help"}).exit_code, 0);
}

TEST_F(CliSafety, DirectoryOrMissingSceneIsNamedAsSuch) {
    const Outcome dir = run_gran({"check", dir_.string()});
    EXPECT_EQ(dir.exit_code, 2) << dir.output;
    EXPECT_NE(dir.output.find(dir_.string() + ": is a directory; expected a scene file"),
              std::string::npos)
        << dir.output;
    const Outcome missing = run_gran({"check", path("nowhere.yaml")});
    EXPECT_EQ(missing.exit_code, 2) << missing.output;
    EXPECT_NE(missing.output.find("cannot open the scene file: no such file"), std::string::npos)
        << missing.output;
}

// Each refusal comes before the run: a scene of 10^7 time units would take minutes otherwise.
TEST_F(CliSafety, UnwritableOutputIsRefusedBeforeTheRunStarts) {
    const std::string scene = path("scene.yaml");
    fs::copy_file(kDemo, scene);
    const std::string text = read_text(scene);
    fs::create_directories(path("folder.h5"));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {path("folder.h5"), "is a directory"},
        {dir_.string(), "expected a result file name ending in .h5"},
        {scene, "expected a result file name ending in .h5"},
        {"/proc/gran.h5", "cannot write in the folder '/proc'"},
    };
    for (const auto& [out, message] : cases) {
        SCOPED_TRACE(out);
        const Outcome o = run_gran({"-q", "run", scene, "-o", out, "--set", "run.measurement=1e7"});
        ASSERT_FALSE(o.signaled) << o.output;
        EXPECT_EQ(o.exit_code, 1) << o.output;
        EXPECT_NE(o.output.find("output '" + out + "': " + message), std::string::npos) << o.output;
    }
    EXPECT_EQ(read_text(scene), text) << "the scene file was overwritten";
}

// Two runs writing one result: HDF5 alone truncates a file it creates before finding another
// process's lock on it, which emptied half of a merged study file in CI (docs/cluster.md). The
// second run is refused before it runs and the first one's file keeps what it holds.
TEST_F(CliSafety, ARunWhoseResultAnotherProcessIsWritingIsRefusedAndThatFileKept) {
    const std::string out = path("r.h5");
    // The other run, here this test: a run's result is OUT.h5.part while it runs.
    const std::vector<double> data(1 << 17, 1.5);  // beyond HDF5's sieve buffer: on disk
    gran::h5::File other = gran::h5::File::create(out + ".part");
    other.root().write("x", data);
    other.flush();
    const Outcome o = run_gran(with_short({"-q", "run", kDemo, "-o", out}));
    ASSERT_FALSE(o.signaled) << o.output;
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_NE(o.output.find("'" + out + ".part': another process has it open"), std::string::npos)
        << o.output;
    EXPECT_FALSE(fs::exists(out));
    other.root().write_scalar("after", 2.0);
    other.close();
    const gran::h5::File kept = gran::h5::File::open_read(out + ".part");
    EXPECT_EQ(kept.root().read_doubles("x"), data);
    EXPECT_EQ(kept.root().read_doubles("after"), std::vector<double>{2.0});
}

// A tmpfs of 64 KiB fills up while the result is written. Mounting needs root (CAP_SYS_ADMIN);
// elsewhere the test is skipped and says why.
class DiskFull : public CliSafety {
  protected:
    void SetUp() override {
        CliSafety::SetUp();
        mnt_ = path("small");
        fs::create_directories(mnt_);
        if (::geteuid() != 0) GTEST_SKIP() << "mounting a 64 KiB tmpfs needs root";
        if (::mount("tmpfs", mnt_.c_str(), "tmpfs", 0, "size=64k") != 0)
            GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
        mounted_ = true;
        // 56 of the 64 KiB taken: any result overflows the 8 KiB left, whatever its size.
        std::ofstream(mnt_ + "/filler", std::ios::binary) << std::string(56 * 1024, 'x');
    }
    void TearDown() override {
        if (mounted_) ::umount2(mnt_.c_str(), MNT_DETACH);
        CliSafety::TearDown();
    }
    std::string mnt_;
    bool mounted_ = false;
};

TEST_F(DiskFull, RunExitsOneNamingThePathAndKeepsTheEarlierResult) {
    const std::string out = mnt_ + "/r.h5";
    const std::string earlier = "an earlier completed result\n";
    std::ofstream(out) << earlier;
    std::ofstream(mnt_ + "/r.summary.yaml") << "status: completed\n";
    const Outcome o = run_gran(with_short({"-q", "run", kDemo, "-o", out}));
    ASSERT_FALSE(o.signaled) << "killed by signal " << o.signal << "\n" << o.output;
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_NE(o.output.find(out + ".part"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("No space left on device"), std::string::npos) << o.output;
    EXPECT_EQ(read_text(out), earlier);
    EXPECT_EQ(read_text(mnt_ + "/r.summary.yaml"), "status: completed\n");
}

TEST_F(DiskFull, NoFileIsLeftAtTheFinalName) {
    const std::string out = mnt_ + "/r.h5";
    const Outcome o = run_gran(with_short({"-q", "run", kDemo, "-o", out}));
    ASSERT_FALSE(o.signaled) << "killed by signal " << o.signal << "\n" << o.output;
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(mnt_ + "/r.summary.yaml"));
}

}  // namespace

// std::bad_alloc (here: 10^9 particles under a 1 GB address-space limit, `ulimit -v`) is a clear
// error naming the stage and the keys that set the memory, exit 1, not an abort. Skipped under the
// address sanitizer, which reserves terabytes of address space at start.
TEST_F(CliSafety, OutOfMemoryIsAClearErrorNamingTheKeysThatSetTheSize) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "ulimit -v and the address sanitizer do not mix";
#endif
    for (const std::string command : {"check", "run"}) {
        const std::string gran =
            gran::testing::shell_quote(gran::testing::kGran) + " -q " + command + " " +
            gran::testing::shell_quote(kDemo) + " --set particles=1000000000" +
            (command == "run" ? " -o " + gran::testing::shell_quote(path("r.h5")) : "");
        const Outcome o =
            gran::testing::run_command({"/bin/sh", "-c", "ulimit -v 1000000 && exec " + gran});
        ASSERT_FALSE(o.signaled) << o.output;
        EXPECT_EQ(o.exit_code, 1) << o.output;
        EXPECT_NE(o.output.find("gran: error: out of memory while"), std::string::npos) << o.output;
        EXPECT_NE(o.output.find("`particles`"), std::string::npos) << o.output;
        EXPECT_NE(o.output.find("1000000000 particles, 2 species"), std::string::npos) << o.output;
        EXPECT_FALSE(std::filesystem::exists(path("r.h5")));
    }
}
