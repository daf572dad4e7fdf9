// Long fuzzing campaigns of the scene loader (`make fuzz`, under ASan and UBSan): mutants of the
// project's scenes (tests/support/scene_fuzzer.hpp) for a given time, each accepted or refused
// with a SceneError. Before each trial the mutant is written to CURRENT (a crash leaves it there);
// an escaped exception or a slow trial is saved under FINDINGS and counted.
//
//   gran_fuzz_scenes --seconds 600 --seed 1 --findings DIR ROOT
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "tests/support/scene_fuzzer.hpp"

int main(int argc, char** argv) {
    CLI::App app{"fuzz the gran scene loader"};
    double seconds = 60;
    std::uint64_t seed = 1;
    std::string findings = "fuzz-findings", root = ".";
    app.add_option("--seconds", seconds, "how long to fuzz");
    app.add_option("--seed", seed, "mutator seed");
    app.add_option("--findings", findings, "folder for inputs that failed");
    app.add_option("root", root, "the source tree (its studies/ and tests/data/)")->required();
    CLI11_PARSE(app, argc, argv);
    namespace fs = std::filesystem;
    const auto corpus = gran::testing::project_corpus(root);
    if (corpus.empty()) {
        std::cerr << "no scenes under " << root << "\n";
        return 2;
    }
    fs::create_directories(findings);
    spdlog::set_level(spdlog::level::off);
    gran::testing::SceneMutator mutator(seed, corpus);
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t trials = 0, accepted = 0, failures = 0;
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
           seconds) {
        const std::string text = mutator.next();
        std::ofstream(findings + "/CURRENT.yaml") << text;
        const auto t = gran::testing::fuzz_trial(text, 5.0);
        ++trials;
        if (t.result == gran::testing::FuzzTrial::Result::Accepted) ++accepted;
        if (t.result == gran::testing::FuzzTrial::Result::Escaped ||
            t.result == gran::testing::FuzzTrial::Result::Slow) {
            ++failures;
            const std::string name = findings + "/failure-" + std::to_string(trials) + ".yaml";
            std::ofstream(name) << "# " << (t.what.empty() ? "slow: " : t.what) << t.seconds
                                << " s\n"
                                << text;
            std::cerr << "failure (" << name << "): " << t.what << "\n";
        }
    }
    fs::remove(findings + "/CURRENT.yaml");
    std::cout << "gran_fuzz_scenes: " << trials << " mutants in " << seconds << " s (seed " << seed
              << "): " << accepted << " accepted, " << trials - accepted - failures
              << " refused with a scene error, " << failures << " failures\n";
    return failures == 0 ? 0 : 1;
}
