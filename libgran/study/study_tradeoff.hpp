#pragma once
// Speed versus accuracy over the runs of a study (docs/studies.md, "Trade-off"). Every run is one
// fidelity setting (a softer spring, a larger time step, fewer particles, a shorter average, ...);
// for each chosen quantity its relative deviation from a reference is set against the run's cost
// (CPU seconds), and the settings that no other setting beats on both are marked (Pareto front).
//
// The reference of a quantity is its analytic value when the study gives one, else the mean of
// the runs of the reference point (the most accurate setting). A setting's error for a quantity is
// |deviation| + its one-sigma uncertainty: a deviation that is only noise still counts as the
// error a user of that setting must expect, and a lucky run is not rewarded.
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/study/study.hpp"
#include "libgran/study/study_fit.hpp"

namespace gran {

// Indices of the points of the Pareto front of (cost, error), both to be minimised: no other
// point has cost <= and error <= with one of them strictly smaller. Points with a NaN coordinate
// are never on the front. Plain kernel, O(n log n).
std::vector<bool> pareto_front(std::span<const double> cost, std::span<const double> error);

// One quantity of one run compared with its reference.
struct TradeoffCell {
    double value = 0, error = 0;                // the run's estimate
    double reference = 0, reference_error = 0;  // analytic (error 0) or the reference runs
    double deviation = 0, deviation_error = 0;  // (value - reference) / |reference|
    double accuracy = 0;  // |deviation| + deviation_error: the error to expect at this setting
    bool pareto = false;  // on the front of (cost, accuracy) for this quantity
    // The forecast of runs with a target (libgran/run/target_run.hpp) applied to this run: the
    // CPU seconds at which its error bar would reach the quantity's target, with the relative
    // uncertainty of that forecast; `biased`: |deviation| exceeds the target by more than two
    // deviation errors, so no measurement length reaches that accuracy at this setting.
    double cpu_to_target = 0, cpu_to_target_uncertainty = 0;
    bool biased = false;
};

struct TradeoffRow {
    std::string run, point, knob, level;
    double cost = 0;                  // the study's cost quantity (CPU seconds by default)
    double wall = 0;                  // the run's wall-clock seconds
    std::vector<TradeoffCell> cells;  // one per quantity
    double worst = 0;                 // largest accuracy over the quantities
    bool pareto = false;              // on the front of (cost, worst)
    bool reference = false;           // a run of the reference point
    double cpu_to_targets = 0;        // largest cpu_to_target over the quantities
    bool biased = false;              // some quantity is biased beyond its target
};

struct TradeoffResult {
    std::vector<std::string> quantities;
    std::vector<std::string> reference_kind;  // per quantity: "analytic" or the reference point
    // Per quantity: the error bar the cost forecasts aim at, on the deviation's scale (relative
    // to |reference|; absolute for distances), NaN when there is none, and where it came from.
    std::vector<double> target;
    std::vector<std::string> target_kind;  // "given", "base runs' error", "reference runs' error"
    std::vector<TradeoffRow> rows;
    std::vector<std::string> problems;  // quantities asked for but missing, no reference, ...
};

// The default quantities when the study lists none: every estimate in the reference runs whose
// last name component is one of the headline quantities of the observables (temperature ratios
// gamma, temperatures T / T_mixture / T_z..., Sonine a2, pressures, scaled bed temperatures).
std::vector<std::string> default_tradeoff_quantities(const std::vector<std::string>& available);

// The distance between velocity distributions, for runs with a `velocity_pdf` observable: for
// every species and component the total-variation distance between the rescaled PDFs of the run and
// of the first reference run, D = (1/2) sum_i |P_i - P_ref,i| dc_i (0: identical, 1: disjoint),
// then the mean over species and components. Its error is the noise floor two independent
// histograms give, (1/2) sum_i dc_i sqrt(2/pi) sqrt(sigma_i^2 + sigma_ref,i^2) (the mean absolute
// value of a Gaussian difference), averaged the same way. Added to `rows` as
// `observables.velocity_pdf.pdf_distance` (reference 0: compared absolutely, not relatively).
// `outputs` are the runs' result files.
void add_pdf_distances(const Study& st, const std::vector<std::string>& outputs,
                       std::vector<Row>& rows, const std::vector<bool>& have,
                       std::vector<std::string>& quantities);

// `n_eff`: per run, the effective samples of each quantity's error bar (as in the run summary;
// missing: unknown, the error bar alone counts). The cost forecasts read each run's
// performance.cpu_time and performance.cpu_time_measuring.
TradeoffResult analyse_tradeoff(const Study& st, const std::vector<std::string>& quantities,
                                const std::vector<Row>& rows, const std::vector<bool>& have,
                                const std::vector<std::map<std::string, double>>& n_eff = {});

void write_tradeoff(h5::Group& root, const TradeoffResult& t);
void write_tradeoff_csv(const std::string& path, const TradeoffResult& t);
// A Markdown table: one line per run, cost and the deviation of every quantity.
std::string tradeoff_table(const TradeoffResult& t);
// A Markdown table of the cost forecasts: per run, the CPU seconds to each quantity's target,
// and the cheapest setting that reaches every target without a bias beyond it ("" without
// targets).
std::string tradeoff_forecast_table(const TradeoffResult& t);

}  // namespace gran
