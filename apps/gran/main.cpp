// gran: the command-line program. `gran run`, `gran study`, `gran check`, `gran list`.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <stop_token>
#include <thread>

#include "apps/gran/signals.hpp"
#include "apps/gran/study_commands.hpp"
#include "libgran/core/build_info.hpp"
#include "libgran/core/huge_pages.hpp"
#include "libgran/run/checkpoint.hpp"
#include "libgran/run/run.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/run/xyz_export.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/scene/scene_reference.hpp"
#include "libgran/study/knob.hpp"
#include "libgran/study/tradeoff_ladder.hpp"

namespace {

using gran::app::g_interrupt;
using gran::app::stop_on_signals;
using gran::app::StudyCommand;

// `gran --version`: what `/provenance` records in every result.
std::string version_text() {
    const gran::BuildInfo& b = gran::build_info();
    return fmt::format(
        "gran {}\ncommit {}{}\nbuild {} ({})", b.version, b.commit,
        b.dirty ? fmt::format(" with uncommitted changes (diff {})", b.diff_hash) : std::string(),
        b.build_type, b.compiler);
}

// The last section of docs/scene-reference.md: the commands, which this file defines.
const char* const kCommandLineReference =
    R"md(
## Command line

`gran --version`: the version, the git commit (and whether the tree had uncommitted changes) and the
build type, as recorded in every result's `/provenance` group and summary (`code`). Exit codes of
every command: 0 success, 1 a run or an output failed, 2 an invalid scene, study or command line,
3 interrupted.

Environment: where the kernel gives transparent huge pages only on request (THP mode `madvise`),
`gran` sets `GLIBC_TUNABLES=glibc.malloc.hugetlb=1` and re-executes itself once at start-up (same
process and arguments), so that its particle arrays sit on 2 MiB pages: about 1.2x faster at 10^6
particles (0.96-1.41x in paired runs), no result changed (docs/performance.md, "Huge pages"). `GRAN_HUGE_PAGES=0`
turns this off; a `GLIBC_TUNABLES` that already names `glibc.malloc.hugetlb` is left as it is.

`gran run SCENE.yaml [-o OUT.h5] [--set key=value ...] [-q] [--log-level LEVEL]`: `--set` takes a
dotted path with list indices, e.g. `--set species.1.mass=10 --set drivers.0.strength=0.1`. Output
defaults to `results/<scene name>.h5`; the summary is written beside it as `<name>.summary.yaml`.
`OUT` must end in `.h5` (or `.hdf5`), must not be a folder or an input, and its folder must be
writable: all checked before the run starts (exit 1 otherwise). The result is written to
`OUT.h5.part` and renamed when complete, so a failed run never replaces an existing result; a run
that did not complete (interrupted, stopped by the watchdog) while `OUT.h5` holds a completed
result is written beside it as `OUT.partial.h5` and `OUT.partial.summary.yaml`. SIGINT, SIGTERM,
SIGHUP, SIGUSR1 and SIGXCPU stop a run and write what was measured (exit 3) and a checkpoint.

`gran run --resume OUT.h5 [SCENE.yaml]`: continues the run to `OUT.h5` from `OUT.h5.checkpoint`,
written every `run.checkpoint.interval` seconds (default 300) and when a run is interrupted. The
result is bit for bit the one an uninterrupted run gives. The checkpoint holds the scene; a scene
given beside it must resolve to the same one (the checkpoint interval and a dem run's
`engine.threads` may differ). A checkpoint written by another code version, for another scene,
damaged or missing is refused (exit 2). See [reliability.md](reliability.md).

`gran run --recover OUT.h5`: writes what a killed run had measured up to its last checkpoint to
`OUT.h5` (status `interrupted`, exit 3) without running; the checkpoint is kept, so
`gran run --resume OUT.h5` still continues the run, bit for bit.

`output.frames` writes the trajectory beside the result: `OUT.trajectory.h5` (H5MD: positions,
velocities, periodic images, angular velocities, box, species, mass, diameter; MDAnalysis reads it)
and `OUT.trajectory.xdmf` (ParaView opens it); `/particles` of `OUT.h5` links to it. See
[python.md](python.md#trajectories).

`gran export --xyz OUT.h5 [-o FILE.xyz]`: the trajectory as extended XYZ for OVITO, ASE or VMD
(default `OUT.xyz`): per frame the box (`Lattice`, `pbc`), time and step, then species, position,
velocity and radius of every particle.

`gran check SCENE.yaml [--set ...]`: every check `gran run` makes (the contacts, what the engine can
do, the drivers' and observables' cross-references, the initial placement), without running.

`gran study STUDY.yaml [-o OUTDIR] [-j JOBS] [--reuse-any-version]`: runs a study (one scene swept
over points, grids, zipped lists and replicas) several runs at a time, merges them into
`OUTDIR/study.h5` with a summary table `study.csv` and power-law fits; a second invocation reuses
every complete run made by the same code (`gran --version`); results of other code are rerun
unless `--reuse-any-version` is given (each reused one is named). See [studies.md](studies.md).)md";

int cmd_list(const std::string& what, bool markdown) {
    try {
        std::cout << gran::scene_reference(
            what, markdown ? gran::ReferenceFormat::markdown : gran::ReferenceFormat::text);
    } catch (const std::invalid_argument& e) {
        std::cerr << "gran list: " << e.what() << "\n";
        return 2;
    }
    if (markdown && what.empty()) std::cout << kCommandLineReference << "\n";
    return 0;
}

std::string default_output(const std::string& scene) {
    std::filesystem::path p(scene);
    return (std::filesystem::path("results") / p.stem()).string() + ".h5";
}

// The summary's headline (libgran/run/headline.hpp): the temperature ratios gamma.
void print_headline(const YAML::Node& summary) {
    const YAML::Node h = summary["headline"];
    if (!h || !h.IsMap()) return;
    for (auto it = h.begin(); it != h.end(); ++it) {
        std::cout << fmt::format("{} = {:.4f} +- {:.4f} ({})\n", it->first.as<std::string>(),
                                 it->second["value"].as<double>(), it->second["error"].as<double>(),
                                 it->second["from"].as<std::string>());
    }
}

// What the command line asks for; CLI11 writes into these fields.
struct CommandLine {
    std::string log_level = "info";
    bool quiet = false;
    // run, check
    std::string scene_file, output, resume, recover;
    std::vector<std::string> sets;
    StudyCommand study;
    int jobs = 0;  // tradeoff
    std::string pilot_output;
    // tradeoff
    gran::TradeoffRequest treq;
    std::string tout;
    bool dry_run = false;
    std::vector<std::string> knob_ladders, analytic;
    // list
    std::string what;
    bool markdown = false;
    // export
    std::string export_input, export_output;
    bool xyz = false;
};

CLI::App* add_run(CLI::App& app, CommandLine& cl) {
    auto* run = app.add_subcommand("run", "run a scene and write OUT.h5 plus OUT.summary.yaml");
    run->add_option("scene", cl.scene_file,
                    "scene file (YAML); with --resume optional (the checkpoint holds the scene)");
    auto* output =
        run->add_option("-o,--output", cl.output, "result file (default results/<scene>.h5)");
    run->add_option("--set", cl.sets,
                    "override a scene key, e.g. --set run.measurement=100 (repeatable)");
    run->add_option("--resume", cl.resume,
                    "continue the run to OUT.h5 from its checkpoint OUT.h5.checkpoint; the result "
                    "is bit for bit that of an uninterrupted run")
        ->excludes(output);
    run->add_option("--recover", cl.recover,
                    "write what the run to OUT.h5 had measured at its last checkpoint (status "
                    "interrupted) without running; --resume can still continue it")
        ->excludes(output)
        ->excludes("--resume");
    run->fallthrough();
    return run;
}

CLI::App* add_check(CLI::App& app, CommandLine& cl) {
    auto* check =
        app.add_subcommand("check", "validate a scene (and its initial placement) without running");
    check->add_option("scene", cl.scene_file, "scene file (YAML)")->required();
    check->add_option("--set", cl.sets, "override a scene key (repeatable)");
    check->add_option("--pilot-output", cl.pilot_output,
                      "with run.target_error: keep the pilot's result (and its summary) here");
    check->fallthrough();
    return check;
}

CLI::App* add_study(CLI::App& app, CommandLine& cl) {
    auto* study = app.add_subcommand(
        "study", "run a study (a scene swept over points, grids and replicas) on all cores");
    study->add_option("study", cl.study.file, "study file (YAML), see docs/studies.md")->required();
    study->add_option("-o,--output", cl.study.out, "result folder (default results/<study>)");
    study->add_option("-j,--jobs", cl.study.jobs,
                      "runs at a time (default: the study's `jobs`, else all cores; one per MPI "
                      "rank or SLURM task)");
    study->add_flag("--forecast", cl.study.forecast,
                    "run only a pilot of each point with run.target_error and write what the "
                    "study is forecast to cost (OUTDIR/<study>.forecast.md)");
    study->add_flag("--reuse-any-version", cl.study.reuse_any_version,
                    "reuse complete results made by another code version (each is named); by "
                    "default they are rerun");
    study->add_flag("--status", cl.study.status,
                    "say which runs are complete, checkpointed, started or not started, and "
                    "what the SLURM queue holds of the study's jobs; run nothing");
    study->add_flag("--merge-only", cl.study.merge_only, "run nothing: merge the complete runs");
    study->add_flag("--slurm", cl.study.slurm,
                    "write a SLURM job array (a task per --runs-per-task runs) and a merge job "
                    "after it, and submit both with sbatch (docs/cluster.md)");
    study->add_option("--partition", cl.study.slurm_options.partition,
                      "with --slurm: the partition (default: the cluster's)");
    study->add_option("--time", cl.study.slurm_options.time,
                      "with --slurm: each task's time limit (default 1:00:00)");
    study
        ->add_option("--runs-per-task", cl.study.slurm_options.runs_per_task,
                     "with --slurm: runs per array task (default 1)")
        ->check(CLI::PositiveNumber);
    study
        ->add_option("--signal-seconds", cl.study.slurm_options.warning_seconds,
                     "with --slurm: seconds before the time limit at which the runs checkpoint "
                     "and stop (default 120)")
        ->check(CLI::PositiveNumber);
    study->add_flag("--dry-run", cl.study.slurm_options.dry_run,
                    "with --slurm: write and print the scripts, submit nothing");
    study
        ->add_option("--slurm-task", cl.study.slurm_task,
                     "run the runs of this array task (what the --slurm scripts call)")
        ->check(CLI::NonNegativeNumber);
    study->fallthrough();
    return study;
}

CLI::App* add_tradeoff(CLI::App& app, CommandLine& cl) {
    auto* tradeoff = app.add_subcommand(
        "tradeoff",
        "run a scene at a ladder of fidelity settings and report error versus cost "
        "(docs/studies.md)");
    tradeoff->add_option("scene", cl.treq.scene, "scene file (YAML)")->required();
    tradeoff->add_option("--set", cl.treq.sets, "override a base scene key (repeatable)");
    tradeoff
        ->add_option("--knobs", cl.treq.knobs,
                     "automatic knobs to use: " + gran::knob_names() + " (default: all that apply)")
        ->delimiter(',');
    tradeoff->add_option("--knob", cl.knob_ladders,
                         "a ladder of any scene key, cheapest first: KEY=v1,v2,... (repeatable)");
    tradeoff->add_option("--quantity", cl.treq.quantities,
                         "summary quantity to compare (repeatable; default: the headline ones)");
    tradeoff->add_option("--analytic", cl.analytic,
                         "exact value of a quantity, the reference for it: QUANTITY=value");
    tradeoff->add_option("--target-error", cl.treq.target_error,
                         "error bar each setting's cost is forecast to reach: QUANTITY=0.002 or "
                         "QUANTITY=1% (repeatable; default: the base run's error bar)");
    tradeoff->add_option("-o,--output", cl.tout,
                         "result folder (default results/tradeoff-<scene>)");
    tradeoff->add_option("-j,--jobs", cl.jobs, "runs at a time (default: all cores)");
    tradeoff->add_flag("--dry-run", cl.dry_run, "write and print the study file, run nothing");
    tradeoff->fallthrough();
    return tradeoff;
}

CLI::App* add_list(CLI::App& app, CommandLine& cl) {
    auto* list =
        app.add_subcommand("list", "document scene sections and plugins with their parameters");
    list->add_option("what", cl.what,
                     "scene, laws, engines, drivers, observables or placements (default: all)");
    list->add_flag(
        "--markdown", cl.markdown,
        "print Markdown: with no category, the page docs/scene-reference.md (make docs)");
    return list;
}

CLI::App* add_export(CLI::App& app, CommandLine& cl) {
    auto* ex = app.add_subcommand(
        "export", "convert a run's trajectory frames for other tools (--xyz: extended XYZ)");
    ex->add_option("result", cl.export_input, "the result file (OUT.h5) or its OUT.trajectory.h5")
        ->required();
    ex->add_flag("--xyz", cl.xyz, "extended XYZ (OVITO, ASE, VMD)")->required();
    ex->add_option("-o,--output", cl.export_output, "the file to write (default OUT.xyz)");
    return ex;
}

// `gran export --xyz RESULT.h5 [-o OUT.xyz]`.
int cmd_export(const CommandLine& cl) {
    std::string out = cl.export_output;
    if (out.empty()) {
        std::filesystem::path p(cl.export_input);
        std::string stem = p.stem().string();
        if (stem.size() > 11 && stem.substr(stem.size() - 11) == ".trajectory")
            stem.resize(stem.size() - 11);
        out = (p.parent_path() / stem).string() + ".xyz";
    }
    try {
        const std::size_t frames = gran::export_xyz(cl.export_input, out);
        std::cout << fmt::format("{}: {} frames\n", out, frames);
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 1;
    }
}

std::string human_time(double s) {
    if (s < 120) return fmt::format("{:.2g} s", s);
    if (s < 7200) return fmt::format("{:.2g} min", s / 60);
    if (s < 2 * 86400) return fmt::format("{:.2g} h", s / 3600);
    if (s < 2 * 365 * 86400) return fmt::format("{:.2g} days", s / 86400);
    return fmt::format("{:.2g} years", s / (365.25 * 86400));
}

// `gran check`'s cost line: the engine's estimate of the work, and the time it takes at the rate
// this scene runs at on this build (a short run of about 0.3 s, nothing written). Chunks of the
// runner's work double from one: a dem step of a million grains alone takes ~0.01 s.
void print_cost(const gran::Scene& scene) {
    const gran::RunCost& cost = scene.cost;
    if (cost.text.empty()) return;
    // A bound on the measurement whatever the scene does (work that is never counted must not
    // hang `gran check`): the engines see the flag within 1024 events, a step or a kick.
    std::atomic<bool> enough{false};
    std::mutex m;
    std::condition_variable_any cv;
    const std::jthread timer([&](const std::stop_token& st) {
        std::unique_lock lock(m);
        cv.wait_for(lock, st, std::chrono::seconds(2), [] { return false; });
        enough = true;
    });
    gran::Simulation sim(scene, &enough);
    const auto start = std::chrono::steady_clock::now();
    double secs = 0;
    for (std::uint64_t chunk = 1; secs < 0.3 && chunk < (std::uint64_t(1) << 40); chunk *= 2) {
        if (sim.advance({.work = chunk}) != gran::Advance::Reached) break;
        secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    std::cout << cost.text;
    if (secs > 0 && sim.work() > 0) {
        const double rate = double(sim.work()) * cost.per_runner_work / secs;
        std::cout << fmt::format("; about {} at the {:.3g} {}/s measured now",
                                 human_time(cost.work / rate), rate, cost.unit);
    }
    std::cout << "\n";
}

// A run with a target: the first look's forecast against what it cost, per quantity and in all.
// A summary number: {value: x, unit: ...} or a plain x.
double summary_number(const YAML::Node& n) {
    return n.IsMap() ? n["value"].as<double>() : n.as<double>();
}

void print_target(const YAML::Node& summary) {
    const YAML::Node t = summary["target"];
    if (!t) return;
    std::cout << fmt::format("target: {}", t["status"].as<std::string>());
    if (t["reason"]) std::cout << " (" << t["reason"].as<std::string>() << ")";
    std::cout << "\n";
    for (auto it = t["quantities"].begin(); it != t["quantities"].end(); ++it) {
        const YAML::Node q = it->second;
        if (!q["error"]) continue;
        std::cout << fmt::format("  {} = {:.6g} +- {:.3g} (target {:.3g}, n_eff {})",
                                 it->first.as<std::string>(), summary_number(q["value"]),
                                 summary_number(q["error"]), summary_number(q["target"]),
                                 q["n_eff"] ? fmt::format("{:.0f}", summary_number(q["n_eff"]))
                                            : std::string("unknown: fixed blocks"));
        if (q["forecast_cpu_seconds"])
            std::cout << fmt::format(
                "; first-look forecast to reach it: about {:.3g} CPU s (+-{:.0f}%)",
                summary_number(q["forecast_cpu_seconds"]),
                100 * summary_number(q["forecast_uncertainty"]));
        std::cout << "\n";
    }
    if (const YAML::Node f = t["forecast"])
        std::cout << fmt::format(
            "  forecast (first look): {:.3g} CPU s in all ({:.3g}-{:.3g}), {:.3g} at the look "
            "where it stops; spent {:.3g}\n",
            summary_number(f["cpu_seconds"]), summary_number(f["cpu_seconds_low"]),
            summary_number(f["cpu_seconds_high"]), summary_number(f["cpu_seconds_at_stop_look"]),
            summary_number(t["cpu_seconds"]));
}

// The run's result and exit status: 0 completed, 1 stopped by the watchdog, 3 interrupted, 2 a
// target that names no quantity of the run's summary.
int report_run(const gran::RunReport& rep) {
    print_headline(rep.summary);
    print_target(rep.summary);
    std::cout << fmt::format("result: {}\nsummary: {}\n", rep.output, rep.summary_file);
    if (rep.target_status == "unknown_quantity") {
        std::cerr << "gran: error: " << rep.target_reason << "\n";
        return 2;
    }
    if (!rep.error.empty()) {
        // The watchdog stopped the run: a failure (exit 1), with what was measured written.
        std::cerr << "gran: error: " << rep.error << "\n";
        return 1;
    }
    if (!rep.completed) {
        spdlog::warn("run did not complete; the result holds the data measured so far");
        return 3;
    }
    return 0;
}

gran::RunOptions run_options(const CommandLine& cl, int argc, char** argv) {
    gran::RunOptions opt;
    opt.output = !cl.resume.empty()    ? cl.resume
                 : !cl.recover.empty() ? cl.recover
                 : cl.output.empty()   ? default_output(cl.scene_file)
                                       : cl.output;
    opt.recover_only = !cl.recover.empty();
    opt.progress = !cl.quiet;
    opt.terminal = isatty(STDERR_FILENO) != 0;
    opt.command_line.assign(argv, argv + argc);
    opt.interrupt = &g_interrupt;
    return opt;
}

// `gran run --resume OUT.h5 [SCENE.yaml]` (or --recover): the scene, if given, must be the
// checkpoint's.
int cmd_resume(const CommandLine& cl, int argc, char** argv) {
    std::optional<gran::Scene> given;
    if (!cl.scene_file.empty()) given = gran::load_scene(cl.scene_file, cl.sets);
    if (!cl.sets.empty() && !given)
        throw gran::SceneError("gran run --resume: --set needs the scene file it changes");
    const gran::RunOptions opt = run_options(cl, argc, argv);
    spdlog::info("{} {} from {}", opt.recover_only ? "recovering" : "resuming", opt.output,
                 gran::checkpoint_path_for(opt.output));
    return report_run(gran::resume_run(opt, given ? &*given : nullptr));
}

// std::bad_alloc: a clear message (not a crash, not a bare "std::bad_alloc") naming what was being
// built and the scene keys that set the memory it needs, with this scene's values when known.
int out_of_memory(const char* stage, const gran::Scene* scene) {
    std::string sizes =
        "the memory follows from `particles` (or the species' `count`), the number of species, "
        "the observables' histogram `bins` and `frames`, and `run.measurement` over "
        "`run.sample_interval` (time series are kept in memory)";
    if (scene) {
        std::string observables;
        for (const auto& o : scene->observables)
            observables += (observables.empty() ? "" : ", ") + o.name;
        sizes += fmt::format(
            "; this scene: {} particles, {} species ({} pair contacts stored), {} frames, "
            "observables [{}]",
            scene->species.total_count(), scene->species.size(), scene->contacts.pair_contacts(),
            scene->frames, observables);
    }
    std::cerr << "gran: error: out of memory while " << stage << "; " << sizes
              << ". Make the scene smaller or run it on a machine with more memory.\n";
    return 1;
}

// `gran check` of a scene with run.target_error: a pilot run to the first look (equilibration and
// the minimum measurement), in a temporary folder unless `keep` names its result (`gran study
// --forecast` reads the pilot's summary), and its forecast of what the targets cost.
int run_pilot(const gran::Scene& scene, const std::string& keep) {
    const auto dir = std::filesystem::temp_directory_path() /
                     fmt::format("gran-pilot-{}", static_cast<long>(getpid()));
    if (keep.empty()) std::filesystem::create_directories(dir);
    gran::RunOptions opt;
    opt.output = keep.empty() ? (dir / "pilot.h5").string() : keep;
    opt.progress = false;
    opt.pilot = true;
    opt.interrupt = &g_interrupt;
    std::cout << "pilot: equilibration and the first look of the measurement, to forecast the "
                 "targets' cost\n";
    const gran::RunReport rep = gran::run_scene(scene, opt);
    print_target(rep.summary);
    std::error_code ec;
    if (keep.empty()) std::filesystem::remove_all(dir, ec);
    if (rep.target_status == "unknown_quantity") {
        std::cerr << "gran: error: " << rep.target_reason << "\n";
        return 2;
    }
    return rep.completed ? 0 : 3;
}

// `gran run` and `gran check` (check_only).
int cmd_run(const CommandLine& cl, bool check_only, int argc, char** argv) {
    const char* stage = "reading the scene (species, contacts, plugins)";
    std::optional<gran::Scene> loaded;
    // From the start, not once the scene is loaded: a signal while a large scene loads (or a
    // slow, sanitized build starts) stops the run at its first check, writing its (empty) result
    // with exit 3, instead of killing it.
    if (!check_only) stop_on_signals();
    try {
        if (!check_only && (!cl.resume.empty() || !cl.recover.empty())) {
            stage = "resuming the run from its checkpoint";
            return cmd_resume(cl, argc, argv);
        }
        if (cl.scene_file.empty())
            throw gran::SceneError("gran run: give a scene file, or --resume OUT.h5");
        gran::Scene& scene = loaded.emplace(gran::load_scene(cl.scene_file, cl.sets));
        stage = check_only ? "checking the scene (placing the particles, building the engine)"
                           : "building and running the scene (engine, drivers, observables)";
        if (check_only) {
            gran::check_scene(scene);
            std::cout << fmt::format("{}: ok ({}D, {} particles, packing fraction {:.4g})\n",
                                     cl.scene_file, scene.dimension, scene.species.total_count(),
                                     scene.packing_fraction);
            print_cost(scene);
            if (scene.target.active()) return run_pilot(scene, cl.pilot_output);
            if (!cl.pilot_output.empty())
                throw gran::SceneError(
                    "--pilot-output: the scene has no run.target_error, so "
                    "there is no pilot to run");
            return 0;
        }
        const gran::RunOptions opt = run_options(cl, argc, argv);
        spdlog::info("running {} ({}D, {} particles, packing fraction {:.4g})", cl.scene_file,
                     scene.dimension, scene.species.total_count(), scene.packing_fraction);
        if (!scene.cost.text.empty()) spdlog::info("{}", scene.cost.text);
        return report_run(gran::run_scene(scene, opt));
    } catch (const gran::SceneError& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 2;
    } catch (const gran::CheckpointError& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        return out_of_memory(stage, loaded ? &*loaded : nullptr);
    } catch (const std::exception& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    gran::use_huge_pages(argv);  // may re-execute this program once (huge_pages.hpp)
    CLI::App app{
        "gran: event-driven simulations of granular gases (inelastic hard disks and spheres)"};
    app.require_subcommand(1);
    CommandLine cl;
    app.set_version_flag("--version", version_text);
    app.add_option("--log-level", cl.log_level, "trace, debug, info, warn, error, off")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}))
        ->capture_default_str();
    app.add_flag("-q,--quiet", cl.quiet, "no progress line and only warnings");
    add_run(app, cl);
    const CLI::App* check = add_check(app, cl);
    const CLI::App* study = add_study(app, cl);
    const CLI::App* tradeoff = add_tradeoff(app, cl);
    const CLI::App* list = add_list(app, cl);
    const CLI::App* exporter = add_export(app, cl);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; every command-line error exits 2, like an invalid scene
        // (CLI11's own codes, 106 or 109, are not what the README documents).
        return app.exit(e) == 0 ? 0 : 2;
    }
    spdlog::set_level(cl.quiet ? spdlog::level::warn : spdlog::level::from_str(cl.log_level));
    spdlog::set_pattern("[%H:%M:%S] [%^%l%$] %v");

    if (list->parsed()) return cmd_list(cl.what, cl.markdown);
    if (exporter->parsed()) return cmd_export(cl);
    if (study->parsed()) {
        cl.study.quiet = cl.quiet;
        return gran::app::cmd_study(cl.study);
    }
    if (tradeoff->parsed())
        return gran::app::cmd_tradeoff(cl.treq, cl.knob_ladders, cl.analytic, cl.tout, cl.jobs,
                                       cl.quiet, cl.dry_run);
    return cmd_run(cl, check->parsed(), argc, argv);
}
