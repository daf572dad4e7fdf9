#include "apps/gran/study_commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/gran/signals.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/study/study.hpp"
#ifdef GRAN_HAVE_MPI
#include "apps/gran/study_mpi.hpp"
#endif

namespace gran::app {

namespace {

// The PNG of error versus cost (studies/plot_tradeoff.py, Debian's python3 with matplotlib). The
// script imports the package gran from python/, found through PYTHONPATH as everywhere else.
void plot_tradeoff(const gran::StudyReport& rep) {
    const std::filesystem::path source(GRAN_SOURCE_DIR);
    const std::filesystem::path script = source / "studies" / "plot_tradeoff.py";
    const std::string png = rep.merged.substr(0, rep.merged.size() - 9) + ".tradeoff.png";
    if (!std::filesystem::exists(script) || !std::filesystem::exists("/usr/bin/python3")) {
        spdlog::warn("no plot: {} or /usr/bin/python3 is missing", script.string());
        return;
    }
    const std::string cmd =
        fmt::format("PYTHONPATH='{}' /usr/bin/python3 '{}' '{}' -o '{}'",
                    (source / "python").string(), script.string(), rep.merged, png);
    if (std::system(cmd.c_str()) == 0)
        std::cout << "plot: " << png << "\n";
    else
        spdlog::warn("the trade-off plot failed: {}", cmd);
}

// `gran study --slurm`: the scripts, submitted unless --dry-run.
int submit_to_slurm(const gran::Study& st, const StudyCommand& c, const std::string& outdir) {
    gran::SlurmOptions so = c.slurm_options;
    so.study_command = std::filesystem::read_symlink("/proc/self/exe").string();
    const gran::SlurmSubmission sub = gran::submit_slurm_study(st, c.file, outdir, so);
    std::cout << fmt::format("job array: {} ({} tasks of up to {} runs)\nmerge job: {}\n",
                             sub.array_script, sub.tasks, so.runs_per_task, sub.merge_script);
    if (so.dry_run) {
        for (const std::string& f : {sub.array_script, sub.merge_script}) {
            std::ifstream in(f);
            std::cout << "\n# " << f << "\n" << in.rdbuf();
        }
        return 0;
    }
    std::cout << fmt::format(
        "submitted: array job {}, merge job {} (after it)\nstatus: gran study "
        "{} -o {} --status\n",
        sub.array_job, sub.merge_job, c.file, outdir);
    return 0;
}

}  // namespace

int cmd_study(const StudyCommand& c) {
    try {
        const gran::Study st = gran::load_study(c.file);
        gran::StudyOptions opt;
        opt.output_dir = c.out;
        opt.jobs = c.jobs;
        opt.gran_binary = std::filesystem::read_symlink("/proc/self/exe").string();
        opt.progress = !c.quiet;
        opt.reuse_any_version = c.reuse_any_version;
        opt.forecast = c.forecast;
        opt.merge_only = c.merge_only;
        opt.interrupt = &g_interrupt;
        const std::string outdir = gran::study_output_dir(st, opt);
        if (c.status) {
            std::cout << gran::study_status(st, outdir);
            return 0;
        }
        if (c.slurm) return submit_to_slurm(st, c, outdir);
        stop_on_signals();
        if (c.slurm_task >= 0)
            return gran::run_slurm_task(st, opt, c.slurm_task, c.slurm_options.runs_per_task);
        const bool forecast = c.forecast;
#ifdef GRAN_HAVE_MPI
        if (gran::launched_by_mpirun()) {
            if (forecast)
                throw gran::SceneError(
                    "--forecast runs its pilots on one machine: run it without mpirun");
            return gran::run_study_mpi(st, opt);
        }
#endif
        const gran::StudyReport rep = gran::run_study(st, opt);
        if (forecast) {
            std::ifstream md(rep.forecast);
            std::cout << md.rdbuf() << "forecast: " << rep.forecast << "\n";
            if (rep.interrupted) return 3;
            return rep.failed > 0 ? 1 : 0;
        }
        std::cout << fmt::format(
            "{} ran, {} reused, {} failed{}; at most {} at a time\nresult: {}\ntable: {}\n",
            rep.ran, rep.reused, rep.failed, rep.interrupted ? " (interrupted)" : "",
            rep.max_concurrent, rep.merged, rep.table);
        if (!rep.pooled.empty()) std::cout << "replicas pooled: " << rep.pooled << "\n";
        if (!rep.tradeoff.empty()) {
            std::ifstream md(rep.tradeoff);
            std::cout << md.rdbuf() << "table: " << rep.tradeoff << "\n";
            plot_tradeoff(rep);
        }
        if (rep.interrupted) return 3;
        return rep.failed > 0 ? 1 : 0;
    } catch (const gran::SceneError& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 1;
    }
}

int cmd_tradeoff(gran::TradeoffRequest treq, const std::vector<std::string>& knob_ladders,
                 const std::vector<std::string>& analytic, std::string out, int jobs, bool quiet,
                 bool dry_run) {
    std::string file;
    try {
        for (const auto& k : knob_ladders) {
            const auto eq = k.find('=');
            if (eq == std::string::npos || eq == 0 || eq + 1 >= k.size())
                throw gran::SceneError("--knob expects KEY=v1,v2,..., got '" + k + "'");
            std::vector<std::string> levels;
            std::stringstream ss(k.substr(eq + 1));
            for (std::string v; std::getline(ss, v, ',');) levels.push_back(v);
            treq.custom.emplace_back(k.substr(0, eq), levels);
        }
        for (const auto& a : analytic) {
            const auto eq = a.find('=');
            double v = 0;
            try {
                if (eq == std::string::npos || eq == 0) throw std::invalid_argument(a);
                v = std::stod(a.substr(eq + 1));
            } catch (const std::exception&) {
                throw gran::SceneError("--analytic expects QUANTITY=number, got '" + a + "'");
            }
            treq.analytic.emplace_back(a.substr(0, eq), v);
        }
        const std::string stem = std::filesystem::path(treq.scene).stem().string();
        if (out.empty()) out = "results/tradeoff-" + stem;
        const std::string text = gran::tradeoff_study_text(treq, out);
        std::filesystem::create_directories(out);
        file = (std::filesystem::path(out) / (stem + ".yaml")).string();
        std::ofstream(file) << text;
        std::cout << "study: " << file << "\n";
        if (dry_run) {
            std::cout << text;
            return 0;
        }
    } catch (const gran::SceneError& e) {
        std::cerr << "gran: error: " << e.what() << "\n";
        return 2;
    }
    StudyCommand c;
    c.file = file;
    c.out = out;
    c.jobs = jobs;
    c.quiet = quiet;
    return cmd_study(c);
}

}  // namespace gran::app
