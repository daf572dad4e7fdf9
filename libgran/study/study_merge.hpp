#pragma once
// Merging the completed runs of a study (docs/studies.md): the summary table (CSV), the power-law
// fits, the trade-off and one HDF5 file with a group per run. Used by run_study (study_run.cpp).
#include <chrono>
#include <string>
#include <vector>

#include "libgran/study/study.hpp"

namespace gran {

// Where each run of a study writes (index as Study::runs): its result file, its summary and its
// log.
struct RunFiles {
    std::vector<std::string> result, summary, log;
};
RunFiles run_files(const Study& st, const std::string& outdir);

// Merges every run i with have[i] into OUTDIR/<study stem>.study.h5 and .study.csv, plus the
// trade-off and fit files when the study has them; sets rep.table, rep.merged and rep.tradeoff.
// The merged file's performance group records rep's counts and the wall time since `started`.
void merge_study(const Study& st, const std::string& outdir, const RunFiles& files,
                 const std::vector<bool>& have, std::chrono::steady_clock::time_point started,
                 StudyReport& rep);

}  // namespace gran
