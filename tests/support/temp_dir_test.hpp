#pragma once
// Test fixture with a fresh directory per test, named after the process and the test (ctest runs
// tests as parallel processes), removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace gran::testing {

class TempDirTest : public ::testing::Test {
  protected:
    explicit TempDirTest(std::string prefix = "gran") : prefix_(std::move(prefix)) {}
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               (prefix_ + "_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" +
                info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::string prefix_;
    std::filesystem::path dir_;
};

}  // namespace gran::testing
