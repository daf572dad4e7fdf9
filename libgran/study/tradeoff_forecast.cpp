#include "libgran/study/tradeoff_forecast.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "libgran/run/target_run.hpp"

namespace gran {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The scale of quantity q's deviations: |reference|, or 1 for a distance (compared absolutely).
double deviation_scale(const TradeoffResult& t, std::size_t q) {
    if (t.reference_kind[q].find("(distance)") != std::string::npos) return 1.0;
    return t.rows.empty() ? kNaN : std::abs(t.rows[0].cells[q].reference);
}

const TargetError* given_target(const StudyTradeoff& spec, const std::string& q) {
    for (const TargetError& e : spec.target_error)
        if (e.quantity == q) return &e;
    return nullptr;
}

// The mean error bar (on the deviation scale) of quantity q over the rows of `point`.
double mean_error_of_point(const TradeoffResult& t, std::size_t q, const std::string& point) {
    double sum = 0;
    int n = 0;
    for (const TradeoffRow& r : t.rows) {
        const TradeoffCell& c = r.cells[q];
        if (r.point != point || !std::isfinite(c.error)) continue;
        sum += c.error;
        ++n;
    }
    return n > 0 ? sum / n / deviation_scale(t, q) : kNaN;
}

// Quantity q's target on the deviation scale: given, else the base runs' error bar, else the
// reference runs'.
void choose_target(const StudyTradeoff& spec, TradeoffResult& t, std::size_t q) {
    const double scale = deviation_scale(t, q);
    if (const TargetError* e = given_target(spec, t.quantities[q])) {
        t.target.push_back(e->relative && scale != 1.0 ? e->error : e->error / scale);
        t.target_kind.push_back("given");
        return;
    }
    if (const double b = mean_error_of_point(t, q, "base"); std::isfinite(b) && b > 0) {
        t.target.push_back(b);
        t.target_kind.push_back("base runs' error");
        return;
    }
    const double r = mean_error_of_point(t, q, spec.reference);
    t.target.push_back(std::isfinite(r) && r > 0 ? r : kNaN);
    t.target_kind.push_back(std::isfinite(r) && r > 0 ? "reference runs' error" : "none");
}

double row_number(const Row& row, const std::string& key) {
    const auto it = row.find(key);
    return it == row.end() ? kNaN : it->second.first;
}

double n_eff_of(const std::vector<std::map<std::string, double>>& n_eff, std::size_t i,
                const std::string& q) {
    if (i >= n_eff.size()) return kNaN;
    const auto it = n_eff[i].find(q);
    return it == n_eff[i].end() ? kNaN : it->second;
}

}  // namespace

void add_cost_forecasts(const Study& st, const std::vector<Row>& rows,
                        const std::vector<std::size_t>& runs,
                        const std::vector<std::map<std::string, double>>& n_eff,
                        TradeoffResult& t) {
    for (std::size_t q = 0; q < t.quantities.size(); ++q) choose_target(st.tradeoff, t, q);
    // The minimum statistics a run with a target asks of an error bar (run.min_effective_samples).
    const double n_min = double(AccuracyTarget{}.min_effective_samples);
    bool unknown_split = false;
    for (std::size_t k = 0; k < t.rows.size(); ++k) {
        TradeoffRow& r = t.rows[k];
        const Row& row = rows[runs[k]];
        const double cpu = row_number(row, "performance.cpu_time");
        const double measuring = row_number(row, "performance.cpu_time_measuring");
        if (!std::isfinite(measuring)) unknown_split = true;
        r.cpu_to_targets = 0;
        for (std::size_t q = 0; q < t.quantities.size(); ++q) {
            TradeoffCell& c = r.cells[q];
            c.cpu_to_target = c.cpu_to_target_uncertainty = kNaN;
            if (!std::isfinite(t.target[q])) continue;
            const double scale = deviation_scale(t, q);
            const double ne = n_eff_of(n_eff, runs[k], t.quantities[q]);
            const double growth = growth_needed(c.error / scale, ne, t.target[q], n_min);
            c.cpu_to_target = cpu_after_growth(cpu, measuring, growth);
            const double high =
                cpu_after_growth(cpu, measuring, growth * (1 + growth_uncertainty(ne)));
            c.cpu_to_target_uncertainty = high / c.cpu_to_target - 1;
            c.biased = std::abs(c.deviation) - 2 * c.deviation_error > t.target[q];
            r.biased = r.biased || c.biased;
            r.cpu_to_targets = std::isnan(c.cpu_to_target) || std::isnan(r.cpu_to_targets)
                                   ? kNaN
                                   : std::max(r.cpu_to_targets, c.cpu_to_target);
        }
    }
    if (unknown_split)
        t.problems.push_back(
            "cost forecasts: some runs do not report performance.cpu_time_measuring (written "
            "by an older gran); rerun them for a forecast");
}

std::string tradeoff_forecast_table(const TradeoffResult& t) {
    if (std::none_of(t.target.begin(), t.target.end(), [](double x) { return std::isfinite(x); }))
        return "";
    std::string s =
        "Cost to the same error bar: the CPU seconds at which each setting's error bar would "
        "reach the target (error ~ 1/sqrt(measurement), the forecast of runs with a target), "
        "+- the forecast's uncertainty; `biased`: the deviation exceeds the target by more than "
        "2 sigma, and no measurement length removes it.\n\n";
    for (std::size_t q = 0; q < t.quantities.size(); ++q) {
        if (!std::isfinite(t.target[q])) continue;
        s += fmt::format("q{} target: +- {:.3g}{} ({})\n", q + 1,
                         t.reference_kind[q].find("(distance)") == std::string::npos
                             ? 100 * t.target[q]
                             : t.target[q],
                         t.reference_kind[q].find("(distance)") == std::string::npos ? "%" : "",
                         t.target_kind[q]);
    }
    s += "\n| run | knob | level | CPU s spent |";
    for (std::size_t q = 0; q < t.quantities.size(); ++q) s += fmt::format(" q{} CPU s |", q + 1);
    s += " all |\n|---|---|---|---:|";
    for (std::size_t q = 0; q < t.quantities.size(); ++q) s += "---:|";
    s += "---:|\n";
    std::vector<std::size_t> order(t.rows.size());
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](std::size_t k) {  // runs without a forecast last
        const double c = t.rows[k].cpu_to_targets;
        return std::isnan(c) ? INFINITY : c;
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    const TradeoffRow* best = nullptr;
    for (std::size_t k : order) {
        const TradeoffRow& r = t.rows[k];
        s += fmt::format("| {}{} | {} | {} | {:.3g} |", r.run, r.reference ? " (ref)" : "",
                         r.knob.empty() ? "-" : r.knob, r.level.empty() ? "-" : r.level, r.cost);
        for (const TradeoffCell& c : r.cells) {
            if (std::isnan(c.cpu_to_target))
                s += " - |";
            else
                s += fmt::format(" {:.3g} +- {:.0f}%{} |", c.cpu_to_target,
                                 100 * c.cpu_to_target_uncertainty, c.biased ? " biased" : "");
        }
        s += std::isnan(r.cpu_to_targets)
                 ? " - |\n"
                 : fmt::format(" {:.3g}{} |\n", r.cpu_to_targets, r.biased ? " biased" : "");
        if (!best && !r.biased && std::isfinite(r.cpu_to_targets)) best = &r;
    }
    if (best)
        s += fmt::format(
            "\ncheapest setting to every target without a bias beyond it: {} (about {:.3g} CPU "
            "s)\n",
            best->run, best->cpu_to_targets);
    else
        s += "\nno setting reaches every target without a bias beyond it\n";
    return s;
}

}  // namespace gran
