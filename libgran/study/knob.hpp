#pragma once
// Fidelity knobs of `gran tradeoff` as plugins: each knob is declared, with a static initialiser,
// by the plugin that owns the setting it turns (the DEM engine its time step, the soft-contact
// laws their stiffness, the stochastic thermostat its kick interval; the particle number and the
// measurement length are generic, libgran/study/generic_knobs.cpp). The ladder
// (tradeoff_ladder.cpp) asks every registered knob, in `order`, what it makes of a scene: a Knob
// with its levels, or the reason it does not apply.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "libgran/core/registry.hpp"
#include "libgran/study/tradeoff_ladder.hpp"

namespace gran {

struct Scene;  // libgran/scene/scene.hpp

// What a knob may read about the scene of a trade-off.
struct KnobContext {
    const TradeoffRequest& request;
    const Scene& scene;          // loaded with the request's --set overrides
    const YAML::Node& resolved;  // scene.resolved
    const YAML::Node& raw;       // the scene file as written (null when it cannot be read)
};

// A knob that applies to the scene, or why it does not (the reason without the knob's name:
// "the event-driven engine has no time step").
using KnobOutcome = std::variant<Knob, std::string>;

struct KnobPlugin : PluginInfo {
    // Position in the ladder (and in the study's points): smaller first.
    int order = 0;
    std::function<KnobOutcome(const KnobContext&)> make;
};

using KnobRegistry = Registry<KnobPlugin>;

// Registers a knob (no schema: a knob has no scene keys of its own).
bool register_knob(std::string name, int order, std::string summary,
                   std::function<KnobOutcome(const KnobContext&)> make);

// The registered knobs in ladder order, and their names joined by ", " in that order.
std::vector<const KnobPlugin*> knobs_in_order();
std::string knob_names();

// Helpers of the knobs' level ladders.
namespace knobs {

// A level's value as written into the study file ({:.6g}).
std::string number(double x);
// n[key] as a number; `fallback` when absent or not a number.
double real_at(const YAML::Node& n, const char* key, double fallback = 0);
// True when one of the request's --set overrides sets `key`.
bool has_set(const std::vector<std::string>& sets, const std::string& key);
// "x1", "x1/4", "x2": a level given as a fraction of the scene's own value.
std::string fraction_label(double f);
// Levels base * factor (factors from cheapest to most accurate), each setting `key`, except the
// base level where factor == 1 (it sets nothing); levels above max_value are left out.
Knob scaled(const std::string& name, const std::string& doc, const std::string& key, double base,
            const std::vector<double>& factors, double max_value = INFINITY);
// The resolved scene's engine.type ("" when absent).
std::string engine_type(const KnobContext& c);

}  // namespace knobs

}  // namespace gran
