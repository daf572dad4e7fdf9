#pragma once
// `mpirun -np K gran study STUDY.yaml` (issue 18): the study's runs spread over the MPI ranks.
// Built only when CMake finds MPI (GRAN_HAVE_MPI); without mpirun, `gran study` runs locally as
// always.
#include <atomic>

#include "libgran/study/study.hpp"

namespace gran {

// True when this process is one of several ranks started by an MPI launcher (OpenMPI, PMIx or
// PMI environment with a size above 1) and this build has MPI.
bool launched_by_mpirun();

// Runs the study over the ranks and returns the exit status every rank should return (the same
// on all of them). Rank 0 hands out the runs, longest expected first (the engine's cost
// estimate), one at a time to whichever rank asks (dynamic), runs `local_jobs` of them itself
// between requests, records every run's exit (a failed run is counted and the others go on),
// and merges; the other ranks run what they are given. Each run is `gran run` in a child process
// of its rank, as in a local study, and records the rank in /provenance/mpi_rank.
int run_study_mpi(const Study& st, const StudyOptions& opt);

}  // namespace gran
