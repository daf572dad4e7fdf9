#pragma once
// The ladder of fidelity settings `gran tradeoff SCENE.yaml` runs (docs/studies.md, "Trade-off"):
// from the scene it derives the knobs that apply, each with levels from cheapest to most accurate,
// and writes a study file that runs the base scene, every other level of one knob at a time, and
// the reference (every knob at its most accurate level). The study is an ordinary study file:
// it can be edited and rerun with `gran study`.
#include <string>
#include <utility>
#include <vector>

namespace gran {

struct KnobLevel {
    std::string label;                                     // e.g. "0.01", "x1/4", "event_driven"
    std::vector<std::pair<std::string, std::string>> set;  // scene key -> value
};

// One fidelity knob: levels ordered from cheapest to most accurate; `base` is the level the scene
// itself has (or -1 when none of the levels is the scene's own setting).
struct Knob {
    std::string name;
    std::string doc;  // what it trades, for the generated study's comments
    std::vector<KnobLevel> levels;
    int base = -1;
};

struct TradeoffRequest {
    std::string scene;               // path of the scene file
    std::vector<std::string> sets;   // base overrides "key=value"
    std::vector<std::string> knobs;  // automatic knobs; empty: all
    std::vector<std::pair<std::string, std::vector<std::string>>> custom;  // key -> levels
    std::vector<std::string> quantities;                   // empty: the default patterns
    std::vector<std::pair<std::string, double>> analytic;  // quantity -> exact value
    std::vector<std::string> target_error;                 // "quantity=error bar" (0.002 or 1%)
};

// The automatic knobs of a scene: every registered knob (KnobRegistry, libgran/study/knob.hpp;
// each declared by the plugin that owns its setting) in ladder order, or only those named in
// `request.knobs` (each must be registered: SceneError otherwise). Knobs that do not apply to the
// scene, and levels the scene refuses, are skipped with a note in `skipped`.
std::vector<Knob> automatic_knobs(const TradeoffRequest& request,
                                  std::vector<std::string>& skipped);

// The study file text (YAML) for the request; `output` is the result folder it names.
std::string tradeoff_study_text(const TradeoffRequest& request, const std::string& output);

}  // namespace gran
