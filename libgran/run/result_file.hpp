#pragma once
// The parts of a run's result that the run loop itself writes (the plugins and runners write
// theirs): provenance (/h5md, /parameters), the run's part of /performance, and the summary's
// header (scene, status, ...).
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/run/result_sink.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

// /h5md (version [1, 1], author, creator) and /parameters (the resolved scene as YAML text, its
// file, packing fraction, command line and units); file only, written when the run starts.
void write_provenance(ResultGroup root, const Scene& sc,
                      const std::vector<std::string>& command_line);

// How the run went, whatever the engine.
struct RunTotals {
    double wall_time = 0;  // s
    double cpu_time = 0;   // s
    // s of cpu_time spent measuring (after equilibration): what a longer measurement scales,
    // read by the cost forecasts of `gran tradeoff` (libgran/run/target_run.hpp)
    double cpu_time_measuring = 0;
    double final_time = 0;
    double measured_time = 0;
    double measured_collisions_per_particle = 0;
    std::size_t samples = 0;  // measurement samples taken
    bool completed = false;
    bool interrupted = false;
    std::string watchdog_stop;      // why the watchdog stopped the run (empty: it did not)
    std::uint64_t checkpoints = 0;  // checkpoints written (all sessions of a resumed run)
    std::uint64_t resumes = 0;      // times the run was resumed from a checkpoint
    double checkpoint_time = 0;     // wall-clock s spent writing checkpoints
};

// wall_time, cpu_time and cpu_time_measuring (HDF5 and summary), the rest in HDF5 only (the summary
// has `status`).
void write_run_performance(ResultGroup& performance, const RunTotals& totals);

// The summary's header: scene, title, result, status, error, dimension, particles, packing
// fraction. `status` says why a run that did not complete stopped.
void write_summary_header(YAML::Node& summary, const Scene& sc, const std::string& output,
                          const std::string& status, const std::string& error,
                          std::size_t particles);

}  // namespace gran
