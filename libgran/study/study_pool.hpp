#pragma once
// Replicas pooled (docs/studies.md, "<study>.pooled.csv"): one row per run of a study with its
// replicas combined, so that each quantity's value has the error of all of them.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "libgran/study/study.hpp"

namespace gran {

// Every number of each run's summary by its dotted name: value and error (NaN: none).
using SummaryRow = std::map<std::string, std::pair<double, double>>;

// Writes `path` when the study has replicas: runs that differ only in their replica form a group.
// A quantity with an error in every replica: the inverse-variance weighted mean, its error
// 1 / sqrt(sum 1 / e_i^2), and `.scatter` = sqrt(chi^2 / (n - 1)) of the replicas about it (about
// 1 when the errors are right; the Birge ratio). Otherwise the plain mean and the standard error
// of the replicas' spread. Returns false (nothing written) without replicas.
bool write_pooled_csv(const std::string& path, const Study& st,
                      const std::vector<std::string>& quantities,
                      const std::vector<SummaryRow>& rows, const std::vector<bool>& have);

}  // namespace gran
