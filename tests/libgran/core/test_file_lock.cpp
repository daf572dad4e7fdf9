// Advisory file locks (libgran/core/file_lock.hpp). flock(2) locks belong to an open file
// description, so two opens in one process conflict as two processes would: the tests hold the
// "other process's" lock through a second ExclusiveFileLock.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "libgran/core/file_lock.hpp"

namespace gran {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("gran_file_lock_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(FileLock, AFileIsSeenLockedOnlyWhileAnotherHolderHasIt) {
    const fs::path dir = fresh_dir("probe");
    const std::string path = (dir / "result.h5").string();
    EXPECT_FALSE(file_locked_by_another(path)) << "no file: no writer";
    std::ofstream(path) << "data";
    EXPECT_FALSE(file_locked_by_another(path));
    {
        const ExclusiveFileLock held(path);
        ASSERT_EQ(held.outcome(), ExclusiveFileLock::Outcome::Held);
        EXPECT_TRUE(file_locked_by_another(path));
    }
    EXPECT_FALSE(file_locked_by_another(path)) << "the lock is released with its holder";
    std::ifstream in(path);
    std::string text;
    in >> text;
    EXPECT_EQ(text, "data") << "neither the probe nor the lock changes the file";
    fs::remove_all(dir);
}

TEST(FileLock, ASecondLockWaitsForTheFirstHolderAndThenHoldsTheFile) {
    const fs::path dir = fresh_dir("wait");
    const std::string path = (dir / ".study.merge.lock").string();
    std::atomic<bool> waiting{false}, released{false};
    auto first = std::make_unique<ExclusiveFileLock>(path);
    ASSERT_TRUE(first->held());
    std::thread holder([&] {
        // (Bounded: a second lock that does not wait must fail the test, not hang it.)
        for (int ms = 0; !waiting.load() && ms < 10000; ++ms)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the second one blocks
        released = true;
        first.reset();
    });
    const ExclusiveFileLock second(path, [&] { waiting = true; });
    holder.join();
    EXPECT_EQ(second.outcome(), ExclusiveFileLock::Outcome::HeldAfterWait);
    EXPECT_TRUE(released.load()) << "the second lock was granted before the first was released";
    EXPECT_TRUE(file_locked_by_another(path));
    fs::remove_all(dir);
}

TEST(FileLock, ALockInAFolderThatDoesNotExistIsNotHeldAndSaysWhy) {
    const fs::path dir = fresh_dir("missing");
    const ExclusiveFileLock lock((dir / "no" / "such" / "folder.lock").string());
    EXPECT_FALSE(lock.held());
    EXPECT_EQ(lock.outcome(), ExclusiveFileLock::Outcome::Unavailable);
    EXPECT_NE(lock.error().find("No such file"), std::string::npos) << lock.error();
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gran
