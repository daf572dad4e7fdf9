// Advisory file locks (libgran/core/file_lock.hpp). flock(2) locks belong to an open file
// description, so two opens in one process conflict as two processes would: the tests hold the
// "other process's" lock through a second ExclusiveFileLock.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <memory>
#include <thread>

#include "libgran/core/file_lock.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace gran {
namespace {

class FileLock : public gran::testing::TempDirTest {
  protected:
    FileLock() : TempDirTest("gran_file_lock") {}
};

TEST_F(FileLock, AFileIsSeenLockedOnlyWhileAnotherHolderHasIt) {
    const std::string file = path("result.h5");
    EXPECT_FALSE(file_locked_by_another(file)) << "no file: no writer";
    std::ofstream(file) << "data";
    EXPECT_FALSE(file_locked_by_another(file));
    {
        const ExclusiveFileLock held(file);
        ASSERT_EQ(held.outcome(), ExclusiveFileLock::Outcome::Held);
        EXPECT_TRUE(file_locked_by_another(file));
    }
    EXPECT_FALSE(file_locked_by_another(file)) << "the lock is released with its holder";
    std::ifstream in(file);
    std::string text;
    in >> text;
    EXPECT_EQ(text, "data") << "neither the probe nor the lock changes the file";
}

TEST_F(FileLock, ASecondLockWaitsForTheFirstHolderAndThenHoldsTheFile) {
    const std::string file = path(".study.merge.lock");
    std::atomic<bool> waiting{false}, released{false};
    auto first = std::make_unique<ExclusiveFileLock>(file);
    ASSERT_TRUE(first->held());
    std::thread holder([&] {
        // (Bounded: a second lock that does not wait must fail the test, not hang it.)
        for (int ms = 0; !waiting.load() && ms < 10000; ++ms)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the second one blocks
        released = true;
        first.reset();
    });
    const ExclusiveFileLock second(file, [&] { waiting = true; });
    holder.join();
    EXPECT_EQ(second.outcome(), ExclusiveFileLock::Outcome::HeldAfterWait);
    EXPECT_TRUE(released.load()) << "the second lock was granted before the first was released";
    EXPECT_TRUE(file_locked_by_another(file));
}

TEST_F(FileLock, ALockInAFolderThatDoesNotExistIsNotHeldAndSaysWhy) {
    const ExclusiveFileLock lock(path("no/such/folder.lock"));
    EXPECT_FALSE(lock.held());
    EXPECT_EQ(lock.outcome(), ExclusiveFileLock::Outcome::Unavailable);
    EXPECT_NE(lock.error().find("No such file"), std::string::npos) << lock.error();
}

}  // namespace
}  // namespace gran
