#pragma once
// Test helper: run a scene given as YAML text through the same path as `gran run` and return its
// summary (values with errors).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "libgran/run/run.hpp"
#include "libgran/scene/scene.hpp"

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

// Runs a scene once per test process and shares the result between tests (results go to a
// process-wide directory, the file is <shared_dir>/<tag>.h5).
inline std::filesystem::path shared_dir() {
    auto dir = std::filesystem::temp_directory_path() /
               ("gran_test_" + std::to_string(::getpid()) + "_shared");
    std::filesystem::create_directories(dir);
    return dir;
}

inline YAML::Node run_yaml_once(const std::string& yaml, const std::string& tag) {
    static std::map<std::string, YAML::Node> cache;
    auto it = cache.find(tag);
    if (it != cache.end()) return it->second;
    const Scene scene = parse_scene(YAML::Load(yaml), tag + ".yaml");
    RunOptions opt;
    opt.output = (shared_dir() / (tag + ".h5")).string();
    opt.progress = false;
    return cache[tag] = run_scene(scene, opt).summary;
}

// The vibrated monodisperse gas of Barrat & Trizac 2002, Sec. III: disks between two sawtooth walls
// (v0 = 1) at y = 0 and L, periodic in x, mean packing fraction 0.04.
inline std::string vibrated_gas(int count, double alpha, const std::string& observables) {
    return "dimension: 2\nseed: 3\nspecies: [{name: a, count: " + std::to_string(count) +
           "}]\ninteractions: {walls: {alpha: 1}, alpha: " + std::to_string(alpha) +
           "}\nbox: {packing_fraction: 0.04, periodic: [true, false]}\n"
           "drivers: [{type: sawtooth_wall, axis: y, velocity: 1}]\nobservables: " +
           observables + "\nrun: {equilibration: 200, measurement: 4000, sample_interval: 2}\n";
}

inline double value(const YAML::Node& n) {
    return n["value"].as<double>();
}
inline double error(const YAML::Node& n) {
    return n["error"].as<double>();
}

}  // namespace gran::testing
