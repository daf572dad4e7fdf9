#pragma once
// Test helper: run a scene given as YAML text through the same path as `gran run` and return its
// summary (values with errors).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "libgran/run.hpp"
#include "libgran/scene.hpp"

namespace gran::testing {

inline std::filesystem::path temp_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    auto dir = std::filesystem::temp_directory_path() /
               (std::string("gran_test_") + std::to_string(::getpid()) + "_" +
                info->test_suite_name() + "_" + info->name());
    std::filesystem::create_directories(dir);
    return dir;
}

inline YAML::Node run_yaml(const std::string& yaml, const std::string& tag = "run") {
    const Scene scene = parse_scene(YAML::Load(yaml), tag + ".yaml");
    RunOptions opt;
    opt.output = (temp_dir() / (tag + ".h5")).string();
    opt.progress = false;
    return run_scene(scene, opt).summary;
}

inline double value(const YAML::Node& n) {
    return n["value"].as<double>();
}
inline double error(const YAML::Node& n) {
    return n["error"].as<double>();
}

}  // namespace gran::testing
