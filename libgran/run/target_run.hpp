#pragma once
// A run with a target (run.target_error, issue 17): what a look at the error bars finds, when the
// run may stop, and the forecast of what reaching the targets will cost. The run loop
// (libgran/run/run.cpp) takes the looks; this file holds the rules, free of the engine.
//
// Forecast: an error bar from n_eff effective samples falls as 1 / sqrt(length) once the
// measurement is longer than the autocorrelation time, so a quantity with error e after a
// measured length L reaches its target e_t after L (e / e_t)^2 (and its n_eff reaches the minimum
// after L n_min / n_eff). The CPU time follows from the cost per unit of measurement so far. Its
// uncertainty is that of e^2 estimated from n_eff samples, about sqrt(2 / n_eff) relative.
// The run stops at the first look past that length (looks at L0, 1.5 L0, 2.25 L0, ...) where the
// error bars, themselves noisy, are below their targets: the forecast is the CPU time at the
// length needed; the look it falls before is reported beside it. A short first look
// underestimates correlation times (blocking errors are biased low when the series is not much
// longer than its correlation time), so its forecast is low: docs/choosing-speed-or-accuracy.md.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/scene/accuracy_target.hpp"

namespace gran {

struct QuantityLook {
    std::string quantity;
    bool found = false;           // the summary has it, with an error bar
    double value = 0, error = 0;  // as the observable reports them now
    double n_eff = 0;
    double target = 0;  // the absolute error bar asked for (relative targets: of |value|)
    bool met = false;   // error <= target and n_eff >= the minimum
    // Measurement length (schedule units) at which the target is expected to be met.
    double length_needed = 0;
    double relative_uncertainty = 0;  // of length_needed: sqrt(2 / n_eff)
};

struct TargetLook {
    int index = 0;             // 0: the first look (after the minimum measurement)
    double length = 0;         // measured so far (schedule units)
    double cpu = 0;            // CPU seconds of the whole run so far
    double cpu_measuring = 0;  // of the measurement so far
    std::vector<QuantityLook> quantities;
    bool all_met() const;
    // A quantity whose error has stopped falling: its n_eff did not grow since the previous look
    // (its window is fixed, e.g. a cooling state that broke down); empty if none.
    std::string stalled;
};

struct Forecast {
    bool valid = false;
    double length = 0;  // measurement length at which every target is expected to be met
    double cpu = 0;     // CPU seconds of the whole run there
    double cpu_low = 0, cpu_high = 0;      // the same at 1 -/+ the uncertainty of that length
    double stop_length = 0;                // the first look at or past `length`
    double cpu_at_stop = 0;                // CPU seconds of the whole run at that look
    std::vector<double> cpu_per_quantity;  // each quantity's own target (no look grid)
    std::vector<double> uncertainty_per_quantity;  // relative, of each length needed
};

// The forecast rule of one quantity, shared by runs with a target and by `gran tradeoff`: the
// factor by which a measurement whose error bar is `error`, from `n_eff` effective samples (NaN:
// fixed blocks, whose error alone counts), must grow to reach the absolute error bar `target`
// with at least `n_min` effective samples.
double growth_needed(double error, double n_eff, double target, double n_min);
// The relative uncertainty of that factor: of an error^2 from n_eff samples, sqrt(2 / n_eff)
// (8 blocks when n_eff is unknown).
double growth_uncertainty(double n_eff);
// The CPU seconds of a run that spent `cpu`, `cpu_measuring` of them measuring, had its
// measurement been `growth` times as long.
inline double cpu_after_growth(double cpu, double cpu_measuring, double growth) {
    return cpu - cpu_measuring + cpu_measuring * growth;
}

// The look at `summary` (the observables section of a summary, libgran/run/measurements.hpp).
// A quantity the summary lacks, or that has no error bar, is not found: the run stops with an
// error naming it (the names the summary has are listed by `summary_names`).
TargetLook look_at(const AccuracyTarget& target, const YAML::Node& observables_summary,
                   double length, double cpu, double cpu_measuring, const TargetLook* previous);
std::vector<std::string> summary_names(const YAML::Node& observables_summary);

// The measurement length of look k (k = 0: the minimum measurement).
double look_length(const AccuracyTarget& target, double minimum, int k);

// The forecast from a look: CPU time = cpu_before_measuring + cpu_measuring / length x L.
Forecast forecast(const AccuracyTarget& target, const TargetLook& look, double minimum);

// One line per quantity for the log: value, error, target, n_eff, forecast CPU time.
std::vector<std::string> describe(const TargetLook& look, const Forecast& f);

// The `target` section of the summary and /performance/target: the targets, the errors
// reached, status, why, cost, forecast against the cost spent.
struct TargetOutcome {
    // "reached"; "target_not_reached" (stopped at max_cost); "not_reachable" (an error stopped
    // falling); "unknown_quantity" (a target names no quantity of the summary); "interrupted",
    // "stopped" (the run ended otherwise); empty while measuring.
    std::string status;
    std::string reason;  // why, for every status but "reached"
    TargetLook last;
    Forecast first_forecast;
    int looks = 0;
};

// The looks of one run: when they are due, what each finds, when the run stops measuring, and
// its outcome (written to the result). Archived with the run's checkpoints.
class TargetTracker {
  public:
    // `unit`: of the schedule's lengths ("time", "collisions per particle").
    TargetTracker(const AccuracyTarget& target, double minimum_measurement, std::string unit)
        : target_(target), minimum_(minimum_measurement), unit_(std::move(unit)) {}
    bool active() const { return target_.active(); }
    // Measurement length (schedule units) of the next look.
    double next_look_length() const { return look_length(target_, minimum_, next_look_); }
    // A look at the observables' summary: true when measuring should stop (targets reached, an
    // error that stopped falling, a quantity the summary lacks). Logs what it found.
    bool take_look(const YAML::Node& observables_summary, double length, double cpu,
                   double cpu_measuring);
    // The cost cap: true once `cpu` (CPU s of the run) or `work` (events, steps) reach it.
    bool over_cap(double cpu, std::uint64_t work) const;
    // The run stopped measuring at the cap, or otherwise (interrupted, stalled), after a last look.
    void stopped_at_cap(const YAML::Node& observables_summary, double length, double cpu,
                        double cpu_measuring);
    void stopped(const std::string& why);
    const TargetOutcome& outcome() const { return out_; }
    // The `target` group of the result and summary; `work`: the engine's work units in all
    // (events and kick updates, or steps: what max_cost counts), `work_unit` their name.
    void write(ResultGroup& g, double cpu_total, std::uint64_t work,
               const std::string& work_unit) const;
    void checkpoint(StateArchive& ar);

  private:
    const AccuracyTarget& target_;
    double minimum_;
    std::string unit_;
    int next_look_ = 0;
    TargetOutcome out_;
    bool have_last_ = false;
};

}  // namespace gran
