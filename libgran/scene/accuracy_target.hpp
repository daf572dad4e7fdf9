#pragma once
// Runs that stop when they are accurate enough (issue 17): `run.target_error` names summary
// quantities and the error bar each must reach; `run.max_cost` caps what the run may spend;
// `run.min_effective_samples` the statistics an error bar needs before it is believed. Read and
// checked with the scene (engine-free); the run loop (libgran/run/target_run.hpp) measures.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "libgran/core/scene_error.hpp"

namespace gran {

// One quantity's target: `quantity` as named in a run summary and a study table
// ("observables.temperatures.ratios.light_over_heavy.gamma"), the error bar to reach, absolute
// (in the quantity's unit) or relative to |value| ("1%" -> 0.01).
struct TargetError {
    std::string quantity;
    double error = 0;
    bool relative = false;
    std::string text;      // as written ("0.002", "1%")
    std::string location;  // "file:line:col: run.target_error.<quantity>" for later errors
    // The error bar this target asks of a quantity measured at `value`.
    double absolute(double value) const;
};

// The cost cap: CPU seconds, or engine work (events on the event-driven engine, steps on dem).
struct CostCap {
    double cpu_seconds = std::numeric_limits<double>::infinity();
    std::uint64_t work = UINT64_MAX;
    std::string unit;  // "s", "events", "steps"; empty: no cap
    std::string text;  // as written ("600 s")
};

struct AccuracyTarget {
    std::vector<TargetError> targets;  // empty: a run of fixed length
    CostCap max_cost;
    std::int64_t min_effective_samples = 20;
    // Looks at the error bars after the minimum measurement (run.measurement) and then each time
    // the measurement has grown by this factor: few, geometrically spaced looks keep the bias of
    // stopping on a lucky error small (docs/choosing-speed-or-accuracy.md, "Runs with a target").
    double look_ratio = 1.5;
    bool active() const { return !targets.empty(); }
};

// One error bar, a positive number (0.002) or a percentage below 100 ("1%", "0.5 %"), for
// `quantity`; SceneError at `w` otherwise. Also read by a study's `tradeoff.target_error`.
TargetError read_target_error(const std::string& quantity, const YAML::Node& v, const Where& w);

// Reads run.target_error (a map quantity -> "0.002" or "1%"), run.max_cost ("600 s",
// "1e9 events", "1e8 steps", or a number of CPU seconds) and run.min_effective_samples from the
// `run` section node; SceneError naming file, line and key on bad input. `engine_work_unit` is
// "events" or "steps" (the other one is refused in max_cost).
AccuracyTarget read_accuracy_target(const YAML::Node& run, const Where& where,
                                    const std::string& engine_work_unit);

// The resolved form written to /parameters/scene (run.target_error as written, the cap's text).
YAML::Node resolved_target(const AccuracyTarget& target);

}  // namespace gran
