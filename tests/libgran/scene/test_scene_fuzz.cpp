// The scene loader under a fixed-seed fuzzing run (tests/support/scene_fuzzer.hpp): mutants of
// every scene of the project (studies, test scenes, the bad-scene corpus and the committed fuzz
// corpus tests/data/fuzz_corpus) are each accepted or refused with a SceneError, none escapes
// with another exception or takes seconds. Long campaigns under the sanitizers: `make fuzz`.
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <string>

#include "tests/support/scene_fuzzer.hpp"

namespace gran::testing {
namespace {

TEST(SceneLoaderFuzz, SeededMutantsOfEveryProjectSceneAreAcceptedOrRefusedWithASceneError) {
    const std::string root = GRAN_SOURCE_DIR;
    const auto corpus = project_corpus(root);
    ASSERT_GE(corpus.size(), 50u);
    spdlog::set_level(spdlog::level::off);  // placements log; the verdicts are what is tested
    SceneMutator mutator(2026, corpus);
    int accepted = 0, refused = 0;
    for (int k = 0; k < 20000; ++k) {
        const std::string text = mutator.next();
        const FuzzTrial t = fuzz_trial(text, 5.0);
        ASSERT_NE(t.result, FuzzTrial::Result::Escaped) << t.what << "\nmutant " << k << ":\n"
                                                        << text;
        ASSERT_NE(t.result, FuzzTrial::Result::Slow) << t.seconds << " s\nmutant " << k << ":\n"
                                                     << text;
        (t.result == FuzzTrial::Result::Accepted ? accepted : refused) += 1;
    }
    spdlog::set_level(spdlog::level::info);
    // Mutants must reach past the YAML syntax: some are valid scenes.
    EXPECT_GT(accepted, 200) << refused << " refused";
    RecordProperty("accepted", accepted);
    RecordProperty("refused", refused);
}

}  // namespace
}  // namespace gran::testing
