#pragma once
// The cost of equal error bars over a trade-off's settings (issue 17, "gran tradeoff uses the
// same forecast"). A setting's run has an error bar e on a quantity, from n_eff effective
// samples, after cpu_measuring of its cpu seconds were spent measuring. The forecast rule of runs
// with a target (libgran/run/target_run.hpp: error ~ 1/sqrt(length)) gives the CPU time at which
// that setting's error bar would reach a target: the settings are compared at equal noise, which
// a fixed-length ladder does not do (a cheap setting with a large error bar may be the cheapest
// way to a given error bar, or not). A setting whose deviation from the reference exceeds the
// target significantly is `biased`: measuring longer shrinks its noise, not its bias.
#include <map>
#include <string>
#include <vector>

#include "libgran/study/study.hpp"
#include "libgran/study/study_fit.hpp"
#include "libgran/study/study_tradeoff.hpp"

namespace gran {

// Fills t.target, t.target_kind and every cell's cpu_to_target, cpu_to_target_uncertainty and
// biased, and each row's cpu_to_targets and biased. `runs[k]` is the study run index of
// t.rows[k]; `n_eff[i]` the effective samples of run i's quantities (may be empty).
void add_cost_forecasts(const Study& st, const std::vector<Row>& rows,
                        const std::vector<std::size_t>& runs,
                        const std::vector<std::map<std::string, double>>& n_eff, TradeoffResult& t);

}  // namespace gran
