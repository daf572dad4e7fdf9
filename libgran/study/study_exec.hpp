#pragma once
// The pieces of `gran study` that a distributed runner composes (apps/gran/study_mpi.cpp runs a
// study over MPI ranks with them): which runs are still to do, starting one run as a child
// process, and the merge. run_study (study_run.cpp) is the local composition of the same pieces.
#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

#include "libgran/study/study.hpp"
#include "libgran/study/study_merge.hpp"

namespace gran {

struct StudyPlan {
    std::string outdir;
    int jobs = 1;  // runs at a time on this machine (StudyOptions, the study's `jobs`, the cores)
    RunFiles files;
    std::vector<bool> have;         // complete (reused, or run and completed)
    std::vector<std::size_t> todo;  // the runs to do, in the order given
    StudyReport report;
    std::chrono::steady_clock::time_point started;
};

// The runs first, ..., first + count - 1 of a study (a SLURM array task's share).
struct RunRange {
    std::size_t first = 0;
    std::size_t count = std::size_t(-1);
};

// The runs at a time on this machine: StudyOptions::jobs, else the study's `jobs`, else the
// cores.
int study_jobs(const Study& st, const StudyOptions& opt);

// Creates the output folder and finds the reusable results among the runs of `range` (counted
// in report.reused; the runs outside it are neither checked nor to do).
StudyPlan plan_study(const Study& st, const StudyOptions& opt, RunRange range = {});

// The runs of `todo` with the largest expected work first (StudyRun::expected_work; equal or
// unknown work keeps the study's order).
void longest_first(const Study& st, std::vector<std::size_t>& todo);

// Starts run i as `gran run` (its log: files.log[i]); throws std::runtime_error when the program
// cannot be started.
pid_t start_study_run(const Study& st, const StudyOptions& opt, const RunFiles& files,
                      std::size_t i);

// A run's exit as `gran study` counts it: 0 completed (marked in plan.have), 3 after a stop of
// the study (interrupted, kept incomplete), anything else failed (its log named).
void record_run_exit(const Study& st, std::size_t i, int code, bool stopping, StudyPlan& plan);

// Runs plan.todo on this machine, plan.jobs at a time (children of this process), until done or
// interrupted; records every exit.
void run_locally(const Study& st, const StudyOptions& opt, StudyPlan& plan);

// Merges every complete run (docs/studies.md) and fills the report's file names.
void finish_study(const Study& st, StudyPlan& plan);

// The exit status of a wait: the code, or 128 + the signal.
int exit_code_of(int wait_status);

}  // namespace gran
