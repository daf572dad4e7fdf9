// Running a study: every run is `gran run` in a child process, several at a time; a run whose
// result is complete and came from the same resolved scene is reused (resume). The completed
// runs are then merged (study_merge.cpp).
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "libgran/core/build_info.hpp"
#include "libgran/core/h5.hpp"
#include "libgran/run/checkpoint.hpp"
#include "libgran/study/study.hpp"
#include "libgran/study/study_exec.hpp"
#include "libgran/study/study_forecast.hpp"
#include "libgran/study/study_merge.hpp"

extern char** environ;

namespace gran {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// A result that completed, came from exactly this resolved scene and was made by this code
// (provenance code_id) needs no new run; `any_version` also reuses one made by other code and says
// so. Results older than provenance records count as other code.
bool reusable(const std::string& file, const std::string& resolved, bool any_version) {
    if (!fs::exists(file)) return false;
    try {
        h5::File f = h5::File::open_read(file);
        h5::Group r = f.root();
        if (r.read_int64s("performance/completed").at(0) != 1 ||
            r.read_string("parameters/scene") != resolved) {
            return false;
        }
        const std::string mine = build_info().code_id();
        const std::string theirs = r.exists("provenance")
                                       ? r.group("provenance").read_attr_string("code_id")
                                       : "unrecorded (before provenance)";
        if (theirs == mine) return true;
        if (any_version) {
            spdlog::warn("{}: reusing a result made by code {} (this is {})", file, theirs, mine);
            return true;
        }
        spdlog::info("{}: made by code {}, rerun with this code ({})", file, theirs, mine);
        return false;
    } catch (const std::exception&) {
        return false;
    }
}

// A checkpoint of this run, by this code, for this run's resolved scene: an interrupted run
// (a stopped study, a batch job at its time limit) that `gran run --resume` continues.
bool resumable(const std::string& out, const StudyRun& run) {
    const std::string path = checkpoint_path_for(out);
    if (!fs::exists(path)) return false;
    try {
        const Checkpoint c = read_checkpoint(path);
        return c.header.code_id == build_info().code_id() &&
               c.header.resolved == run.resolved_scene;
    } catch (const std::exception&) {
        return false;
    }
}

// `gran run` of the run to `out` (resumed from its checkpoint when it has one), or (pilot)
// `gran check` with its pilot's result kept at `out`.
pid_t spawn_run(const std::string& binary, const std::string& scene, const std::string& out,
                const StudyRun& run, const std::string& log, bool pilot) {
    std::vector<std::string> args{binary, "--quiet", pilot ? "check" : "run"};
    if (!pilot && resumable(out, run)) {
        args.insert(args.end(), {"--resume", out});
    } else {
        args.insert(args.end(), {scene, pilot ? "--pilot-output" : "-o", out});
        for (const auto& a : assignments(run)) {
            args.push_back("--set");
            args.push_back(a);
        }
    }
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, binary.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        throw std::runtime_error(
            fmt::format("study: cannot start '{}': {}", binary, std::strerror(rc)));
    }
    return pid;
}

// The runs to do; the reusable ones are marked in `have` and counted in rep.reused.
std::vector<std::size_t> runs_to_do(const Study& st, const RunFiles& files, bool any_version,
                                    RunRange range, std::vector<bool>& have, StudyReport& rep) {
    std::vector<std::size_t> todo;
    const std::size_t end =
        std::min(st.runs.size(), range.first + std::min(range.count, st.runs.size()));
    for (std::size_t i = range.first; i < end; ++i) {
        if (reusable(files.result[i], st.runs[i].resolved_scene, any_version) &&
            fs::exists(files.summary[i])) {
            have[i] = true;
            ++rep.reused;
        } else {
            todo.push_back(i);
        }
    }
    return todo;
}

// A run's exit: completed (marked in `have`), interrupted by a stop of the study, or failed.
void count_exit(const Study& st, const RunFiles& files, std::size_t i, int code, bool stopping,
                std::vector<bool>& have, StudyReport& rep) {
    if (code == 0) {
        have[i] = true;
        ++rep.ran;
    } else if (code == 3 && stopping) {
        if (resumable(files.result[i], st.runs[i]))
            spdlog::warn("{}: interrupted; the next run of the study resumes it from {}",
                         st.runs[i].name, checkpoint_path_for(files.result[i]));
        else
            spdlog::warn("{}: interrupted; partial result {} (run again next time)",
                         st.runs[i].name, files.result[i]);
    } else {
        ++rep.failed;
        spdlog::error("{} failed (exit {}); see {}", st.runs[i].name, code, files.log[i]);
    }
}

// Runs `todo` with at most `jobs` children at a time, until all finished or an interrupt
// stopped them; a completed run is marked in `have`.
class RunPool {
  public:
    RunPool(const Study& st, const StudyOptions& opt, const RunFiles& files,
            std::vector<std::size_t> todo, int jobs, std::vector<bool>& have, StudyReport& rep,
            Clock::time_point t0)
        : st_(st),
          opt_(opt),
          files_(files),
          todo_(std::move(todo)),
          jobs_(jobs),
          have_(have),
          rep_(rep),
          t0_(t0) {}

    void run() {
        while (next_ < todo_.size() || !running_.empty()) {
            stop_on_interrupt();
            start_runs();
            if (running_.empty()) break;
            wait_for_one();
        }
        // A stop that came as the last runs ended interrupted nothing: a batch task then exits 0
        // and is not resubmitted.
        if (stop_)
            rep_.interrupted =
                std::any_of(todo_.begin(), todo_.end(), [&](std::size_t i) { return !have_[i]; });
    }

  private:
    void stop_on_interrupt() {
        if (!opt_.interrupt || !opt_.interrupt->load() || stop_) return;
        stop_ = true;
        spdlog::warn("study interrupted: stopping {} running runs (they keep what they measured)",
                     running_.size());
        for (const auto& [pid, r] : running_) kill(pid, SIGTERM);
    }

    void start_runs() {
        while (!stop_ && next_ < todo_.size() && int(running_.size()) < jobs_) {
            const std::size_t i = todo_[next_++];
            pid_t pid = -1;
            try {
                pid = spawn_run(opt_.gran_binary, st_.scene, files_.result[i], st_.runs[i],
                                files_.log[i], opt_.forecast);
            } catch (const std::exception& e) {
                // E.g. the binary is being rebuilt: this run fails, the others go on.
                ++rep_.failed;
                spdlog::error("{}: {}", st_.runs[i].name, e.what());
                continue;
            }
            running_[pid] = {i, Clock::now()};
            rep_.max_concurrent = std::max(rep_.max_concurrent, int(running_.size()));
        }
    }

    void wait_for_one() {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) return;
            throw std::runtime_error(
                fmt::format("study: waitpid failed: {}", std::strerror(errno)));
        }
        auto it = running_.find(pid);
        if (it == running_.end()) return;
        const auto [i, started] = it->second;
        running_.erase(it);
        ++finished_;
        const double secs = std::chrono::duration<double>(Clock::now() - started).count();
        finished(i, exit_code_of(status), secs);
    }

    void finished(std::size_t i, int code, double secs) {
        if (code == 0 && opt_.progress) {
            const double el = std::chrono::duration<double>(Clock::now() - t0_).count();
            const double eta = el / double(finished_) * double(todo_.size() - finished_);
            spdlog::info("[{}/{}] {} done in {:.1f} s (study ETA {:.0f} s)", finished_,
                         todo_.size(), st_.runs[i].name, secs, eta);
        }
        count_exit(st_, files_, i, code, stop_, have_, rep_);
    }

    const Study& st_;
    const StudyOptions& opt_;
    const RunFiles& files_;
    const std::vector<std::size_t> todo_;
    const int jobs_;
    std::vector<bool>& have_;
    StudyReport& rep_;
    const Clock::time_point t0_;                                          // the study's start (ETA)
    std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running_;  // pid -> run, start
    std::size_t next_ = 0, finished_ = 0;
    bool stop_ = false;
};

}  // namespace

namespace {

// The pilots of a study (StudyOptions::forecast): one per point whose runs have a target, run
// like the study's runs, their results under OUTDIR/pilots; the report of what they forecast.
StudyReport run_pilots(const Study& st, const StudyOptions& opt, const std::string& outdir,
                       int jobs) {
    StudyReport rep;
    const fs::path dir = fs::path(outdir) / "pilots";
    fs::create_directories(dir / "logs");
    const std::vector<std::size_t> piloted = runs_to_pilot(st);
    RunFiles files = run_files(st, dir.string());
    spdlog::info(
        "study {}: forecast from {} pilots (one per point with run.target_error) on {} "
        "cores; pilots in {}",
        st.file, piloted.size(), jobs, dir.string());
    std::vector<bool> have(st.runs.size(), false);
    RunPool(st, opt, files, piloted, jobs, have, rep, Clock::now()).run();
    const std::string stem = fs::path(st.file).stem().string();
    rep.forecast = (fs::path(outdir) / (stem + ".forecast.md")).string();
    std::vector<std::string> summaries(st.runs.size());
    for (std::size_t i : piloted)
        if (have[i]) summaries[i] = files.summary[i];
    std::ofstream(rep.forecast) << study_forecast_report(st, summaries, jobs);
    return rep;
}

}  // namespace

int exit_code_of(int status) {
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int study_jobs(const Study& st, const StudyOptions& opt) {
    return opt.jobs > 0  ? opt.jobs
           : st.jobs > 0 ? st.jobs
                         : int(std::max(1u, std::thread::hardware_concurrency()));
}

StudyPlan plan_study(const Study& st, const StudyOptions& opt, RunRange range) {
    StudyPlan p;
    p.outdir = study_output_dir(st, opt);
    p.jobs = study_jobs(st, opt);
    fs::create_directories(fs::path(p.outdir) / "logs");
    p.files = run_files(st, p.outdir);
    p.have.assign(st.runs.size(), false);
    p.todo = runs_to_do(st, p.files, opt.reuse_any_version, range, p.have, p.report);
    p.started = Clock::now();
    return p;
}

void longest_first(const Study& st, std::vector<std::size_t>& todo) {
    std::stable_sort(todo.begin(), todo.end(), [&](std::size_t a, std::size_t b) {
        return st.runs[a].expected_work > st.runs[b].expected_work;
    });
}

pid_t start_study_run(const Study& st, const StudyOptions& opt, const RunFiles& files,
                      std::size_t i) {
    return spawn_run(opt.gran_binary, st.scene, files.result[i], st.runs[i], files.log[i], false);
}

void record_run_exit(const Study& st, std::size_t i, int code, bool stopping, StudyPlan& plan) {
    count_exit(st, plan.files, i, code, stopping, plan.have, plan.report);
}

void finish_study(const Study& st, StudyPlan& plan) {
    const StudyMergeLock lock(st, plan.outdir);
    merge_study(st, plan.outdir, plan.files, plan.have, plan.started, plan.report);
}

namespace {

// `--merge-only` (a SLURM merge job): the complete runs are found under the merge lock, so of two
// merges of one study the one that writes last has seen every run that ended before it started.
StudyReport merge_complete_runs(const Study& st, const StudyOptions& opt) {
    const StudyMergeLock lock(st, study_output_dir(st, opt));
    StudyPlan plan = plan_study(st, opt);
    spdlog::info("study {}: merging the {} complete runs of {}", st.file, plan.report.reused,
                 st.runs.size());
    merge_study(st, plan.outdir, plan.files, plan.have, plan.started, plan.report);
    return plan.report;
}

}  // namespace

StudyReport run_study(const Study& st, const StudyOptions& opt) {
    if (opt.forecast) return run_pilots(st, opt, study_output_dir(st, opt), study_jobs(st, opt));
    if (opt.merge_only) return merge_complete_runs(st, opt);
    StudyPlan plan = plan_study(st, opt);
    spdlog::info("study {}: {} runs, {} already complete, {} to run on {} cores; results in {}",
                 st.file, st.runs.size(), plan.report.reused, plan.todo.size(), plan.jobs,
                 plan.outdir);
    run_locally(st, opt, plan);
    finish_study(st, plan);
    return plan.report;
}

void run_locally(const Study& st, const StudyOptions& opt, StudyPlan& plan) {
    RunPool(st, opt, plan.files, plan.todo, plan.jobs, plan.have, plan.report, plan.started).run();
}

}  // namespace gran
