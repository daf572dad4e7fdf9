#pragma once
// `gran study` and `gran tradeoff`: what the command line asks of a study, and the commands.
#include <string>
#include <vector>

#include "libgran/study/study_slurm.hpp"
#include "libgran/study/tradeoff_ladder.hpp"

namespace gran::app {

// What `gran study` is asked to do (CLI11 writes into these fields).
struct StudyCommand {
    std::string file, out;
    int jobs = 0;
    bool quiet = false, reuse_any_version = false, forecast = false, merge_only = false;
    bool status = false, slurm = false;
    int slurm_task = -1;  // an array task of a SLURM study (the scripts pass it)
    gran::SlurmOptions slurm_options;
};

// `gran study`: locally, under mpirun (an MPI build), as a SLURM array, one array task, a
// forecast, a status or a merge. Returns the exit status.
int cmd_study(const StudyCommand& c);

// `gran tradeoff`: writes the ladder's study file into the result folder, then runs it.
int cmd_tradeoff(gran::TradeoffRequest treq, const std::vector<std::string>& knob_ladders,
                 const std::vector<std::string>& analytic, std::string out, int jobs, bool quiet,
                 bool dry_run);

}  // namespace gran::app
