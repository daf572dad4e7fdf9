#include "libgran/study/study_slurm.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "libgran/run/checkpoint.hpp"
#include "libgran/study/study_exec.hpp"

namespace gran {

namespace fs = std::filesystem;

namespace {

std::string shell_quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// Runs a shell command; its stdout, and false when it did not exit 0.
bool capture(const std::string& cmd, std::string& out) {
    FILE* pipe = ::popen((cmd + " 2>&1").c_str(), "r");
    if (!pipe) return false;
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
    const int status = ::pclose(pipe);
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string sbatch(const std::string& args) {
    std::string out;
    if (!capture("sbatch --parsable " + args, out))
        throw std::runtime_error("sbatch " + args + " failed: " + out);
    return out.substr(0, out.find(';'));  // "jobid[;cluster]"
}

struct Paths {
    fs::path dir, array, merge, jobs, logs;
};

Paths slurm_paths(const Study& st, const std::string& outdir) {
    const std::string stem = fs::path(st.file).stem().string();
    Paths p;
    p.dir = fs::absolute(fs::path(outdir) / "slurm");
    p.array = p.dir / (stem + ".array.sh");
    p.merge = p.dir / (stem + ".merge.sh");
    p.jobs = p.dir / "jobs.txt";
    p.logs = p.dir / "logs";
    return p;
}

// The array: each task calls `gran study --slurm-task`, forwards the time-limit warning to it
// (the runs checkpoint and stop, exit 3), and then resubmits itself and a merge after it.
std::string array_script(const Study& st, const std::string& study, const std::string& outdir,
                         const SlurmOptions& o, int tasks, const Paths& p) {
    const std::string stem = fs::path(st.file).stem().string();
    std::string s = fmt::format(
        "#!/bin/bash\n"
        "# gran study {study} as a SLURM job array, written by `gran study --slurm`: task t runs\n"
        "# the study's runs t*{k} .. t*{k}+{km1} (each a `gran run` with checkpoints; complete "
        "ones\n"
        "# are reused, checkpointed ones resumed). {warn} s before the time limit SLURM sends "
        "TERM:\n"
        "# the runs write their checkpoints and stop, and the task resubmits itself and a merge.\n"
        "#SBATCH --job-name=gran-{stem}\n"
        "#SBATCH --array=0-{last}\n"
        "#SBATCH --output={logs}/%A_%a.out\n"
        "#SBATCH --cpus-per-task=1\n"
        "#SBATCH --time={time}\n"
        "#SBATCH --signal=B:TERM@{warn}\n",
        fmt::arg("study", study), fmt::arg("k", o.runs_per_task),
        fmt::arg("km1", o.runs_per_task - 1), fmt::arg("warn", o.warning_seconds),
        fmt::arg("stem", stem), fmt::arg("last", tasks - 1), fmt::arg("logs", p.logs.string()),
        fmt::arg("time", o.time));
    if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
    s += fmt::format(
        "cd {cwd}\n"
        "{gran} study {study} -o {out} --slurm-task \"$SLURM_ARRAY_TASK_ID\" --runs-per-task {k} "
        "&\n"
        "pid=$!\n"
        "trap 'kill -TERM $pid 2>/dev/null' TERM\n"
        "wait $pid; code=$?\n"
        "while kill -0 $pid 2>/dev/null; do wait $pid; code=$?; done\n"
        "if [ \"$code\" -eq 3 ]; then\n"
        "  job=$(sbatch --parsable --array=\"$SLURM_ARRAY_TASK_ID\" {array})\n"
        "  merge=$(sbatch --parsable --dependency=afterany:${{job%%;*}} {merge})\n"
        "  echo \"task ${{SLURM_ARRAY_JOB_ID}}_${{SLURM_ARRAY_TASK_ID}} resubmitted as "
        "${{job%%;*}} (merge ${{merge%%;*}})\" >> {jobs}\n"
        "  echo \"stopped before the time limit; resubmitted as job ${{job%%;*}}\"\n"
        "fi\n"
        "exit $code\n",
        fmt::arg("cwd", shell_quoted(fs::current_path().string())),
        fmt::arg("gran", shell_quoted(o.study_command)), fmt::arg("study", shell_quoted(study)),
        fmt::arg("out", shell_quoted(outdir)), fmt::arg("k", o.runs_per_task),
        fmt::arg("array", shell_quoted(p.array.string())),
        fmt::arg("merge", shell_quoted(p.merge.string())),
        fmt::arg("jobs", shell_quoted(p.jobs.string())));
    return s;
}

std::string merge_script(const Study& st, const std::string& study, const std::string& outdir,
                         const SlurmOptions& o, const Paths& p) {
    const std::string stem = fs::path(st.file).stem().string();
    std::string s = fmt::format(
        "#!/bin/bash\n"
        "# Merges the complete runs of {study} (written by `gran study --slurm`; runs after the "
        "array).\n"
        "#SBATCH --job-name=gran-{stem}-merge\n"
        "#SBATCH --output={logs}/merge_%j.out\n"
        "#SBATCH --cpus-per-task=1\n"
        "#SBATCH --time={time}\n",
        fmt::arg("study", study), fmt::arg("stem", stem), fmt::arg("logs", p.logs.string()),
        fmt::arg("time", o.time));
    if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
    s += fmt::format("cd {}\nexec {} study {} -o {} --merge-only\n",
                     shell_quoted(fs::current_path().string()), shell_quoted(o.study_command),
                     shell_quoted(study), shell_quoted(outdir));
    return s;
}

// A run's log with gran's error line ("gran: error: ...", what a failing `gran run` prints).
bool log_says_failed(const std::string& log) {
    std::ifstream in(log);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("gran: error:", 0) == 0) return true;
    return false;
}

void write_script(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

}  // namespace

int slurm_task_count(std::size_t runs, int runs_per_task) {
    const std::size_t k = std::size_t(std::max(runs_per_task, 1));
    return int((runs + k - 1) / k);
}

SlurmSubmission submit_slurm_study(const Study& st, const std::string& study_path,
                                   const std::string& outdir, const SlurmOptions& opt) {
    const Paths p = slurm_paths(st, outdir);
    fs::create_directories(p.logs);
    fs::create_directories(fs::path(outdir) / "logs");
    SlurmSubmission sub;
    sub.tasks = slurm_task_count(st.runs.size(), opt.runs_per_task);
    const std::string study = fs::absolute(study_path).string();
    const std::string out = fs::absolute(outdir).string();
    sub.array_script = p.array.string();
    sub.merge_script = p.merge.string();
    write_script(p.array, array_script(st, study, out, opt, sub.tasks, p));
    write_script(p.merge, merge_script(st, study, out, opt, p));
    if (opt.dry_run) return sub;
    sub.array_job = sbatch(shell_quoted(sub.array_script));
    sub.merge_job =
        sbatch("--dependency=afterany:" + sub.array_job + " " + shell_quoted(sub.merge_script));
    std::ofstream(p.jobs, std::ios::app)
        << fmt::format("array {} ({} tasks) merge {}\n", sub.array_job, sub.tasks, sub.merge_job);
    return sub;
}

int run_slurm_task(const Study& st, const StudyOptions& opt, int task, int runs_per_task) {
    StudyOptions o = opt;
    if (o.jobs <= 0) o.jobs = 1;  // one CPU per task unless asked
    const std::size_t k = std::size_t(std::max(runs_per_task, 1));
    const std::size_t first = std::size_t(std::max(task, 0)) * k;
    // Only this task's runs are checked for reuse: a task of a 10^4-run study opens its own
    // few result files, not all of them.
    StudyPlan plan = plan_study(st, o, RunRange{first, k});
    spdlog::info("study {}: array task {} (runs {}-{} of {}): {} to run", st.file, task, first,
                 std::min(first + k, st.runs.size()) - 1, st.runs.size(), plan.todo.size());
    run_locally(st, o, plan);
    return plan.report.interrupted ? 3 : plan.report.failed > 0 ? 1 : 0;
}

std::string study_status(const Study& st, const std::string& outdir) {
    const RunFiles files = run_files(st, outdir);
    StudyOptions o;
    o.output_dir = outdir;
    StudyPlan plan = plan_study(st, o);
    std::map<std::string, std::vector<std::string>> by_state;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        std::string state = "not started";
        if (plan.have[i])
            state = "complete";
        else if (fs::exists(checkpoint_path_for(files.result[i])))
            state = "checkpointed (resumed when run again)";
        else if (fs::exists(files.log[i]))
            state = log_says_failed(files.log[i]) ? "failed (see its log)"
                                                  : "started (running, or killed)";
        by_state[state].push_back(st.runs[i].name);
    }
    std::string s = fmt::format("study {}: {} runs in {}\n", st.file, st.runs.size(), outdir);
    for (const auto& [state, runs] : by_state) {
        s += fmt::format("  {}: {}", state, runs.size());
        if (state != "complete" && runs.size() <= 20)
            s += " (" + fmt::format("{}", fmt::join(runs, ", ")) + ")";
        s += "\n";
    }
    const Paths p = slurm_paths(st, outdir);
    if (fs::exists(p.jobs)) {
        std::ifstream in(p.jobs);
        std::string line, ids;
        while (std::getline(in, line)) {
            s += "  submitted: " + line + "\n";
            for (const std::string& word :
                 {std::string("array "), std::string("merge "), std::string("resubmitted as ")}) {
                const auto at = line.find(word);
                if (at == std::string::npos) continue;
                std::string id;
                for (std::size_t k = at + word.size(); k < line.size(); ++k) {
                    const char c = line[k];
                    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '_') break;
                    id += c;
                }
                if (!id.empty()) ids += (ids.empty() ? "" : ",") + id;
            }
        }
        std::string queue;
        if (!ids.empty() && capture("squeue -h -o '%i %T %j' -j " + ids, queue))
            s += queue.empty() ? "  queue: none of them is pending or running\n"
                               : "  queue:\n    " + queue + "\n";
    }
    return s;
}

}  // namespace gran
