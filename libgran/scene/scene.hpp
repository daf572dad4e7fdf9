#pragma once
// A scene file, validated and resolved: every key checked against its declaration, defaults filled
// in, the box derived, the initial configuration described. `resolved` is written to results so a
// run can be repeated exactly.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"
#include "libgran/engines/dem/contact_table.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/run/watchdog.hpp"
#include "species/species.hpp"

namespace gran {

struct PluginEntry {
    std::string type;
    std::string name;  // result group name (defaults to type)
    Params params;
};

enum class ScheduleUnit { CollisionsPerParticle, Time };

struct Schedule {
    ScheduleUnit unit = ScheduleUnit::CollisionsPerParticle;
    double equilibration = 0;
    double measurement = 0;
    double sample_interval = 1;
};

// engine.type: dem. Pair restitution comes from the species pair laws (alpha); `pair` holds the
// rest of a grain-grain contact, `wall` of a grain-wall contact (e_w from the wall drivers).
struct DemSceneSettings {
    DemLaw law = DemLaw::linear_dashpot;
    DemContactSpec pair, wall;
    DemSettings settings;
    double probe_speed = 1;  // impact speed of the isolated test collisions reported by a run
};

struct Scene {
    std::string file;
    YAML::Node resolved;
    std::string title;
    std::string units = "reduced";  // or "SI"
    int dimension = 2;
    std::uint64_t seed = 1;
    SpeciesTable species;
    std::vector<double> box_length;
    std::vector<bool> periodic;
    double packing_fraction = 0;
    std::string placement = "random";
    double temperature = 1;
    EngineSettings engine;
    std::string engine_type = "event_driven";  // or "dem"
    DemSceneSettings dem;
    Schedule schedule;
    WatchdogSettings watchdog;  // run.watchdog
    std::vector<PluginEntry> drivers;
    std::vector<PluginEntry> observables;
    std::size_t frames = 0;
    double progress_interval = 10;
    std::string box_location;     // "file:line:col: box" for errors found when placing particles
    std::string engine_location;  // "file:line:col: engine" for errors found building the engine
};

// Reads and validates a scene file; `overrides` are "dotted.key=value" (--set) applied first.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
// Validates an already parsed YAML document (file names errors).
Scene parse_scene(const YAML::Node& root, const std::string& file);
// Applies one "a.b.0.c=value" override to a YAML document.
void apply_override(YAML::Node& root, const std::string& assignment);

// Schemas of the scene sections, for `gran list scene`, with the prose of docs/scene-reference.md
// (`gran list --markdown`). Defined in scene_sections.cpp.
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
