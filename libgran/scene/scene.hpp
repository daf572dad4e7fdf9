#pragma once
// A scene file, validated and resolved: every key checked against its declaration, defaults filled
// in, the box derived, the contacts resolved, every plugin built once to check its cross-references
// and what the chosen engine can do. Everything `gran run` would refuse is refused here (`gran
// check`), without building an engine. `resolved` is written to results so a run can be repeated
// exactly. Engine-free: no engine header is included.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"
#include "libgran/core/species.hpp"
#include "libgran/plugins/law.hpp"
#include "libgran/plugins/run_cost.hpp"
#include "libgran/plugins/scene_info.hpp"
#include "libgran/scene/accuracy_target.hpp"
#include "libgran/scene/schedule.hpp"

namespace gran {

struct EnginePlugin;
struct PlacementPlugin;

// One entry of a plugin list (drivers, observables) or a plugin chosen by a key (engine.type,
// initial.placement).
struct PluginEntry {
    std::string type;
    std::string name;  // result group name (defaults to type)
    Params params;
};

struct Scene {
    std::string file;
    std::string source;                  // the file's text as read (checkpoints keep it)
    std::vector<std::string> overrides;  // the --set assignments applied to it
    YAML::Node resolved;
    std::string title;
    std::string units = "reduced";  // or "SI"
    int dimension = 2;
    std::uint64_t seed = 1;
    SpeciesTable species;
    ContactTable contacts;  // interactions, resolved for every contact
    std::vector<double> box_length;
    std::vector<bool> periodic;
    double packing_fraction = 0;
    const PlacementPlugin* placement = nullptr;  // initial.placement
    double temperature = 1;                      // initial.temperature
    std::array<double, 3> gravity{0, 0, 0};
    const EnginePlugin* engine = nullptr;  // engine.type
    PluginEntry engine_settings;           // the `engine` section, validated by its schema
    Schedule schedule;
    AccuracyTarget target;      // run.target_error, max_cost, min_effective_samples
    Params run_settings;        // the `run` section, for errors at its keys
    WatchdogSettings watchdog;  // run.watchdog
    std::vector<PluginEntry> drivers;
    std::vector<PluginEntry> observables;
    std::size_t frames = 0;
    double progress_interval = 10;
    double checkpoint_interval = 300;   // run.checkpoint.interval: wall-clock s, 0: none
    RunCost cost;                       // the engine's estimate (work 0: none)
    std::string box_location;           // "file:line:col: box" for errors found when placing
    std::string species_location;       // "file:line:col: species"
    std::string interactions_location;  // "file:line:col: interactions"
    // What plugin factories read (index 0; peak velocity and drive period from the drivers).
    SceneInfo info;
};

// Reads and validates a scene file; `overrides` are "dotted.key=value" (--set) applied first.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
// The same from the file's text (`path` names errors): a checkpoint's scene.
Scene load_scene_text(const std::string& text, const std::string& path,
                      const std::vector<std::string>& overrides = {});
// Validates an already parsed YAML document (file names errors).
Scene parse_scene(const YAML::Node& root, const std::string& file);
// Applies one "a.b.0.c=value" override to a YAML document.
void apply_override(YAML::Node& root, const std::string& assignment);

// The SceneInfo of plugin `index` of a list.
SceneInfo plugin_info(const Scene& scene, std::size_t index);

// Schemas of the scene sections, for `gran list scene`, with the prose of docs/scene-reference.md
// (`gran list --markdown`). Defined in schemas.cpp.
struct SectionDoc {
    std::string name;
    std::string summary;
    Schema schema;
    std::string description = {};  // Markdown paragraphs; may be empty
};
std::vector<SectionDoc> scene_sections();
// What docs/scene-reference.md says before the sections: units, how errors are reported.
std::string scene_reference_introduction();

}  // namespace gran
