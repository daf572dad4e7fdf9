#pragma once
// Merging the completed runs of a study (docs/studies.md): the summary table (CSV), the power-law
// fits, the trade-off and one HDF5 file with a group per run. Used by run_study (study_run.cpp).
#include <chrono>
#include <string>
#include <vector>

#include "libgran/core/file_lock.hpp"
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

// An exclusive lock on the merge of one study in OUTDIR: flock(2) on OUTDIR/.<stem>.merge.lock
// (the study file's stem; the file is kept there), held while a process decides which runs are
// complete and writes the merged files. Two merges of one study at once are normal on a cluster
// (the array's merge job and a resubmitted task's both start when their jobs end), and HDF5
// truncates a file it creates before it finds the file in use: without the lock the second merge
// emptied part of the first one's merged file (`make test-cluster` caught it). Waits for the
// other merge to finish; where the file system has no locks, warns and merges without.
class StudyMergeLock {
  public:
    StudyMergeLock(const Study& st, const std::string& outdir);

  private:
    ExclusiveFileLock lock_;
};

}  // namespace gran
