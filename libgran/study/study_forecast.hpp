#pragma once
// What a study's runs with a target (run.target_error) are forecast to cost, before they run
// (issue 17: `gran study` uses the forecast of `gran check`). One pilot per point, the first run
// of that point, measures to its first look; its forecast (libgran/run/target_run.hpp) is the
// cost of each of the point's runs, replicas included (they differ only in their seed).
#include <string>
#include <vector>

#include "libgran/study/study.hpp"

namespace gran {

// The runs to pilot: the first run of every point whose resolved scene has run.target_error.
std::vector<std::size_t> runs_to_pilot(const Study& st);

// The Markdown report: per point its runs, the pilot's status and forecast CPU seconds per run
// (with the range), the point's total; the points without a target; the study's total and the
// wall time it needs at least on `jobs` cores. `pilot_summaries[i]`: the summary of run i's
// pilot, empty when run i had none or its pilot failed.
std::string study_forecast_report(const Study& st, const std::vector<std::string>& pilot_summaries,
                                  int jobs);

}  // namespace gran
