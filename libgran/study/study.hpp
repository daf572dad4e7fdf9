#pragma once
// Studies: one base scene run at many points (explicit points, a grid, zipped lists, replicas),
// several runs at a time on the local cores, merged into one HDF5 file with a group per run and a
// summary table. A run whose result is complete and was produced by the same resolved scene is not
// run again (resume). The file format is documented in docs/studies.md.
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "libgran/scene/accuracy_target.hpp"

namespace gran {

// One run of a study: a named point with its scene-key overrides ("a.b.0.c=value").
struct StudyRun {
    std::string name;   // file-name safe: point name, grid/zip suffixes, _r<k> for replicas
    std::string point;  // the point it came from
    int replica = 0;    // 1..replicas when replicas > 1, else 0
    std::vector<std::pair<std::string, std::string>> overrides;  // key, value (YAML text)
    YAML::Node metadata;  // extra keys of the point (e.g. `paper:` values), kept in the result
    std::string resolved_scene;  // the resolved scene text the run will record (for resume)
    // The engine's estimate of the run's work (`gran check`: events or particle-steps; 0: none),
    // to start the longest runs first when a study is spread over MPI ranks.
    double expected_work = 0;
};

// The run's overrides as `--set` assignments "key=value".
std::vector<std::string> assignments(const StudyRun& run);
// The value the run gives a scene key, "" when it does not override it.
std::string override_value(const StudyRun& run, const std::string& key);

// A least-squares power-law fit over the runs: log y = theta log x + c (McNamara & Falcon 2005,
// Sec. IV: an exponent is reported only when every point lies within `tolerance` of the fit in
// natural log).
struct StudyFit {
    std::string name;
    std::string x;  // a swept scene key ("drivers.0.velocity") or a summary quantity
    std::string y;  // a summary quantity ("observables.lid.pressure")
    // Optional scene keys (or `point`, the point's name): one fit per distinct combination.
    std::vector<std::string> group_by;
    double tolerance = 0.25;
};

// A speed-versus-accuracy analysis over the runs (docs/studies.md, "Trade-off"): every run is one
// fidelity setting; each chosen quantity is compared with a reference (an analytic value, else the
// run named `reference`, the most accurate setting) against the run's CPU time.
struct StudyTradeoff {
    std::string reference = "reference";  // the point whose runs are the reference
    std::vector<std::string> quantities;  // summary quantities; empty: the default patterns
    std::vector<std::pair<std::string, double>> analytic;  // quantity -> exact value
    std::string cost = "performance.cpu_time";
    // The error bars each setting's cost is forecast to reach (as run.target_error: absolute or
    // "1%"); a quantity without one gets the error bar of the base runs (else the reference runs).
    std::vector<TargetError> target_error;
};

struct Study {
    std::string file;                     // the study file
    std::string scene;                    // base scene path (resolved relative to the study file)
    std::string output_dir;               // default results/<study file stem>
    int jobs = 0;                         // 0: all cores
    std::vector<std::string> swept_keys;  // every key some run overrides, in first-seen order
    std::vector<StudyRun> runs;
    std::vector<StudyFit> fits;
    bool has_tradeoff = false;
    StudyTradeoff tradeoff;
    std::string text;  // the study file as written, stored in the merged result
};

// Reads and validates a study file; errors (SceneError) name file:line:col and key. Every run's
// scene is loaded and validated too, so a bad override is refused before anything runs.
Study load_study(const std::string& path);

struct StudyOptions {
    std::string output_dir;   // overrides Study::output_dir when not empty
    int jobs = 0;             // overrides Study::jobs when > 0
    std::string gran_binary;  // the program that runs one scene (`gran run`)
    // Reuse complete results made by another code version (a warning names each); by default
    // they are rerun.
    bool reuse_any_version = false;
    bool progress = true;
    const std::atomic<bool>* interrupt = nullptr;
    // Run nothing but a pilot of each point whose runs have run.target_error (`gran check`'s
    // first look) and report what the study's targets are forecast to cost
    // (libgran/study/study_forecast.hpp).
    bool forecast = false;
    // Run nothing: merge the complete runs (the merge job of a SLURM study).
    bool merge_only = false;
};

// Where a study writes: StudyOptions::output_dir when given, else the study's own.
inline std::string study_output_dir(const Study& st, const StudyOptions& opt) {
    return opt.output_dir.empty() ? st.output_dir : opt.output_dir;
}

struct StudyReport {
    int ran = 0;
    int reused = 0;
    int failed = 0;
    bool interrupted = false;
    std::string merged;      // OUTDIR/<study stem>.study.h5
    std::string table;       // OUTDIR/<study stem>.study.csv
    int max_concurrent = 0;  // largest number of runs in flight at once
    std::string tradeoff;    // OUTDIR/<study stem>.tradeoff.md when the study has `tradeoff`
    std::string pooled;      // OUTDIR/<study stem>.pooled.csv when the study has replicas
    std::string forecast;    // OUTDIR/<study stem>.forecast.md with StudyOptions::forecast
};

StudyReport run_study(const Study& study, const StudyOptions& options);

}  // namespace gran
