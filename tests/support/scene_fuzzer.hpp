#pragma once
// Fuzzing of the scene loader (issue 13): a seeded mutator of scene files, and one trial that
// loads a mutant the way `gran check` does. A trial passes when the mutant is accepted, or refused
// with a SceneError (the file:line:key message of every invalid input); anything else (another
// exception escaping, a crash, a hang) is a defect. Used by the in-suite run
// (tests/libgran/scene/test_scene_fuzz.cpp) and the long campaigns of `make fuzz`
// (tests/fuzz/fuzz_scenes.cpp, under ASan and UBSan).
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "libgran/core/scene_error.hpp"
#include "libgran/run/run.hpp"
#include "libgran/scene/scene.hpp"

namespace gran::testing {

// Every .yaml file under the given folders (sorted: the same corpus gives the same mutants).
inline std::vector<std::string> read_corpus(const std::vector<std::filesystem::path>& folders) {
    std::vector<std::filesystem::path> files;
    for (const auto& dir : folders) {
        if (!std::filesystem::is_directory(dir)) continue;
        for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
            if (e.is_regular_file() && e.path().extension() == ".yaml") files.push_back(e.path());
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<std::string> texts;
    for (const auto& f : files) {
        std::ifstream in(f, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        texts.push_back(s.str());
    }
    return texts;
}

// The seeds of a campaign: every scene of the project under `root` (studies, test scenes, the
// committed fuzz corpus), and the bad-scene corpus; the valid scenes are repeated until they make
// up three quarters of the seeds, so that most mutants reach the checks past the syntax.
inline std::vector<std::string> project_corpus(const std::string& root) {
    const auto good = read_corpus(
        {root + "/studies", root + "/tests/data/checkpoint", root + "/tests/data/fuzz_corpus"});
    const auto bad = read_corpus({root + "/tests/data/bad_scenes"});
    std::vector<std::string> all;
    while (!good.empty() && all.size() < 3 * bad.size())
        all.insert(all.end(), good.begin(), good.end());
    all.insert(all.end(), bad.begin(), bad.end());
    return all;
}

// Mutations that keep a scene close to valid, so the validation deep inside is reached: values
// replaced by edge cases, lines deleted, duplicated, swapped, re-indented or spliced from another
// scene, keys inserted, bytes flipped.
class SceneMutator {
  public:
    SceneMutator(std::uint64_t seed, const std::vector<std::string>& corpus)
        : rng_(seed), corpus_(corpus) {}

    std::string next() {
        std::string text = corpus_[pick(corpus_.size())];
        const std::size_t n = 1 + pick(4);
        for (std::size_t k = 0; k < n; ++k) text = mutate(text);
        return text;
    }

  private:
    std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }

    static std::vector<std::string> lines_of(const std::string& text) {
        std::vector<std::string> lines;
        std::istringstream in(text);
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        return lines;
    }
    static std::string joined(const std::vector<std::string>& lines) {
        std::string s;
        for (const auto& l : lines) s += l + "\n";
        return s;
    }

    // A value after a ':' or in a flow list replaced by an edge case.
    std::string replace_value(std::string text) {
        static const char* const kValues[] = {"0",
                                              "-1",
                                              "1e308",
                                              "-1e308",
                                              "1e-308",
                                              ".nan",
                                              ".inf",
                                              "-.inf",
                                              "1e300",
                                              "2",
                                              "3",
                                              "4",
                                              "1.0000000001",
                                              "\"\"",
                                              "[]",
                                              "{}",
                                              "~",
                                              "true",
                                              "abc",
                                              "[1, 2, 3, 4]",
                                              "{a: 1}",
                                              "9223372036854775807",
                                              "18446744073709551616",
                                              "0.5",
                                              "-0",
                                              "1e-300",
                                              "x",
                                              "both",
                                              "upper",
                                              "z",
                                              "dem",
                                              "tc"};
        std::vector<std::size_t> at;
        for (std::size_t i = 0; i + 1 < text.size(); ++i) {
            if ((text[i] == ':' || text[i] == ',' || text[i] == '[') && text[i + 1] == ' ')
                at.push_back(i + 2);
        }
        if (at.empty()) return text;
        const std::size_t start = at[pick(at.size())];
        std::size_t end = start;
        while (end < text.size() && text[end] != ',' && text[end] != '}' && text[end] != ']' &&
               text[end] != '\n' && text[end] != '#')
            ++end;
        return text.substr(0, start) + kValues[pick(std::size(kValues))] + text.substr(end);
    }

    std::string insert_key(std::string text) {
        static const char* const kKeys[] = {
            "particles: 0",
            "dimension: 4",
            "seed: -3",
            "gravity: [0, 0, -1]",
            "box: {lengths: [1, 1]}",
            "box: {packing_fraction: 0.99}",
            "engine: {type: dem}",
            "drivers: [{type: stochastic_thermostat, interval: 1e-12}]",
            "observables: [{type: profiles, axis: z}]",
            "output: {frames: 1000000}",
            "run: {measurement: 1e30}",
            "species: []",
            "interactions: {law: hertz_mindlin}",
            "initial: {placement: lattice}",
            "units: SI",
            "title: [1, 2]"};
        auto lines = lines_of(text);
        lines.insert(lines.begin() + std::ptrdiff_t(pick(lines.size() + 1)),
                     kKeys[pick(std::size(kKeys))]);
        return joined(lines);
    }

    std::string mutate(const std::string& text) {
        auto lines = lines_of(text);
        switch (pick(9)) {
            case 0:
            case 1:
            case 2:
                return replace_value(text);
            case 3:
                if (!lines.empty()) lines.erase(lines.begin() + std::ptrdiff_t(pick(lines.size())));
                return joined(lines);
            case 4:
                if (!lines.empty()) {
                    const std::size_t i = pick(lines.size());
                    lines.insert(lines.begin() + std::ptrdiff_t(i), lines[i]);
                }
                return joined(lines);
            case 5:
                if (lines.size() > 1)
                    std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
                return joined(lines);
            case 6: {  // splice a line of another scene
                const auto other = lines_of(corpus_[pick(corpus_.size())]);
                if (!other.empty())
                    lines.insert(lines.begin() + std::ptrdiff_t(pick(lines.size() + 1)),
                                 other[pick(other.size())]);
                return joined(lines);
            }
            case 7:
                if (!lines.empty()) {
                    std::string& l = lines[pick(lines.size())];
                    l = pick(2) ? "  " + l
                                : l.substr(l.find_first_not_of(' ') == std::string::npos
                                               ? 0
                                               : l.find_first_not_of(' '));
                }
                return joined(lines);
            default: {
                if (pick(2)) return insert_key(text);
                std::string t = text;
                if (!t.empty()) t[pick(t.size())] = char(pick(256));
                return t;
            }
        }
    }

    std::mt19937_64 rng_;
    const std::vector<std::string>& corpus_;
};

struct FuzzTrial {
    enum class Result { Accepted, Refused, Escaped, Slow };
    Result result = Result::Refused;
    std::string what;  // the escaped exception's message
    double seconds = 0;
};

// Loads `text` as `gran check` does: the scene with every validation, and the initial placement
// when it is small (placing 1e9 particles is not the loader's business).
inline FuzzTrial fuzz_trial(const std::string& text, double slow_seconds) {
    FuzzTrial t;
    const auto start = std::chrono::steady_clock::now();
    try {
        const Scene scene = load_scene_text(text, "fuzz.yaml");
        if (scene.species.total_count() <= 2000) check_scene(scene);
        t.result = FuzzTrial::Result::Accepted;
    } catch (const SceneError&) {
        t.result = FuzzTrial::Result::Refused;
    } catch (const std::exception& e) {
        t.result = FuzzTrial::Result::Escaped;
        t.what = std::string(typeid(e).name()) + ": " + e.what();
    }
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t.result != FuzzTrial::Result::Escaped && t.seconds > slow_seconds)
        t.result = FuzzTrial::Result::Slow;
    return t;
}

}  // namespace gran::testing
