#pragma once
// A study on a SLURM cluster (issue 18, docs/cluster.md): `gran study STUDY.yaml --slurm` writes
// a job array (task t runs the study's runs t K .. t K + K - 1, each a `gran run` with its
// checkpoints) and a merge job that waits for the array (afterany), and submits both with
// sbatch. The batch system's warning before the time limit (--signal=B:TERM@SECONDS) makes the
// runs checkpoint and stop; the task then resubmits itself (and a merge after it), and the
// resubmitted task resumes them. `gran study --status` says what is done.
#include <string>
#include <vector>

#include "libgran/study/study.hpp"

namespace gran {

struct SlurmOptions {
    std::string partition;         // empty: the cluster's default
    std::string time = "1:00:00";  // each task's limit (sbatch --time)
    int runs_per_task = 1;         // K
    int warning_seconds = 120;     // --signal=B:TERM@this before the limit
    bool dry_run = false;          // write and print the scripts, submit nothing
    std::string study_command;     // how a task calls gran: the binary (absolute)
};

struct SlurmSubmission {
    std::string array_script, merge_script;  // OUTDIR/slurm/<stem>.{array,merge}.sh
    int tasks = 0;
    std::string array_job, merge_job;  // job ids (empty with dry_run)
};

// The array task count for `runs` runs at K per task.
int slurm_task_count(std::size_t runs, int runs_per_task);

// Writes both scripts (and OUTDIR/slurm/logs), submits them unless dry_run, and records the job
// ids in OUTDIR/slurm/jobs.txt. Throws std::runtime_error when sbatch fails (its output named).
SlurmSubmission submit_slurm_study(const Study& st, const std::string& study_path,
                                   const std::string& outdir, const SlurmOptions& opt);

// Array task `task`: the runs task K .. task K + K - 1 that are not complete, run here one at a
// time (more with StudyOptions::jobs), resumed from their checkpoints when they have one. Returns
// the exit status of `gran study` (0 all complete, 1 a run failed, 3 interrupted).
int run_slurm_task(const Study& st, const StudyOptions& opt, int task, int runs_per_task);

// What `gran study --status` prints: per state (complete, checkpointed, failed: its log has
// gran's error line, started: running or killed, not started)
// the count and the runs, and the queue's view of the jobs recorded in OUTDIR/slurm/jobs.txt
// (squeue, when there is one).
std::string study_status(const Study& st, const std::string& outdir);

}  // namespace gran
