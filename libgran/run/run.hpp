#pragma once
// Running a scene: build the initial state, equilibrate, measure, write the HDF5 result and the
// human-readable summary. Interruptible (SIGINT/SIGTERM): what was measured so far is written.
#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "libgran/scene/scene.hpp"

namespace gran {

struct RunOptions {
    std::string output;  // result file (.h5); the summary goes beside it (.summary.yaml)
    bool progress = true;
    bool terminal = false;  // redraw a progress line (stderr is a terminal)
    std::vector<std::string> command_line;
    const std::atomic<bool>* interrupt = nullptr;
    // Resuming: write the result from the checkpoint's state as an interrupted run, without
    // running (`gran run --recover`); the checkpoint is kept for a later --resume.
    bool recover_only = false;
    // Called after every measurement sample with the samples taken and the simulated time (the
    // Python module's callbacks); may set *interrupt to stop the run.
    std::function<void(std::size_t samples, double time)> on_sample;
    // A run with a target stops after its first look (the pilot of `gran check`: what reaching
    // the targets will cost).
    bool pilot = false;
};

struct RunReport {
    bool completed = false;  // false when interrupted or stopped
    std::string error;       // non-empty: the watchdog stopped the run (what, when, what to change)
    std::string output;
    std::string summary_file;
    YAML::Node summary;
    // A run with a target: its status (TargetOutcome::status) and why; empty without a target.
    std::string target_status;
    std::string target_reason;
};

// Everything short of running: places the particles (throws SceneError naming the box on
// failure) and builds every driver and observable (whose constructors check cross-references such
// as species names). `gran check` uses it to refuse impossible scenes before running.
void check_scene(const Scene& scene);

RunReport run_scene(const Scene& scene, const RunOptions& options);

// Continues the run to options.output from its checkpoint (OUT.h5.checkpoint, written every
// run.checkpoint.interval seconds and when a run is interrupted): the result is bit for bit the
// one an uninterrupted run gives. The scene comes from the checkpoint; `given` (optional) must
// resolve to the same scene. CheckpointError (libgran/run/checkpoint.hpp) when there is no
// usable checkpoint, or it was written by other code or for another scene.
// With options.recover_only, writes the data measured up to the checkpoint (status
// `interrupted`) and keeps the checkpoint: what a killed run had measured, readable without
// continuing it.
RunReport resume_run(const RunOptions& options, const Scene* given = nullptr);

}  // namespace gran
