#include "libgran/run/target_run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "libgran/run/summary_numbers.hpp"

namespace gran {

bool TargetLook::all_met() const {
    return std::all_of(quantities.begin(), quantities.end(),
                       [](const QuantityLook& q) { return q.met; });
}

std::vector<std::string> summary_names(const YAML::Node& observables_summary) {
    std::vector<std::string> names;
    for (const auto& [name, x] : summary_numbers(observables_summary, "observables")) {
        if (std::isfinite(x.error)) names.push_back(name);
    }
    return names;
}

TargetLook look_at(const AccuracyTarget& target, const YAML::Node& observables_summary,
                   double length, double cpu, double cpu_measuring, const TargetLook* previous) {
    const auto numbers = summary_numbers(observables_summary, "observables");
    TargetLook look;
    look.index = previous ? previous->index + 1 : 0;
    look.length = length;
    look.cpu = cpu;
    look.cpu_measuring = cpu_measuring;
    for (std::size_t k = 0; k < target.targets.size(); ++k) {
        const TargetError& t = target.targets[k];
        QuantityLook q;
        q.quantity = t.quantity;
        const auto it = numbers.find(t.quantity);
        if (it != numbers.end() && std::isfinite(it->second.value) &&
            std::isfinite(it->second.error)) {
            const SummaryNumber& x = it->second;
            q.found = true;
            q.value = x.value;
            q.error = x.error;
            q.n_eff = x.n_eff;
            q.target = t.absolute(x.value);
            const double n_min = double(target.min_effective_samples);
            // An error from fixed blocks of samples (profiles, local_temperature) has no n_eff:
            // its jackknife rests on at least 8 blocks, and only the error bar counts.
            const bool known = std::isfinite(q.n_eff);
            q.met = q.error <= q.target && (!known || q.n_eff >= n_min);
            q.length_needed = length * growth_needed(q.error, q.n_eff, q.target, n_min);
            q.relative_uncertainty = growth_uncertainty(q.n_eff);
            // A quantity over a window that no longer grows (a cooling state that broke down)
            // reports the same value and error at every look.
            if (previous && !q.met && k < previous->quantities.size() &&
                previous->quantities[k].found && q.value == previous->quantities[k].value &&
                q.error == previous->quantities[k].error && length > 1.2 * previous->length &&
                look.stalled.empty()) {
                look.stalled = fmt::format(
                    "{}: its value and error bar stopped changing ({:.6g} +- {:.3g} at {:.4g} and "
                    "{:.4g} measured): it is measured over a window that no longer grows (such "
                    "as a cooling state that broke down), and measuring longer cannot reach the "
                    "target",
                    t.quantity, q.value, q.error, previous->length, length);
            }
        }
        look.quantities.push_back(q);
    }
    return look;
}

double growth_needed(double error, double n_eff, double target, double n_min) {
    // Error ~ 1/sqrt(length), n_eff ~ length.
    const double by_error = target > 0 ? std::pow(error / target, 2) : INFINITY;
    const double by_samples = !std::isfinite(n_eff) ? 0.0 : n_eff > 0 ? n_min / n_eff : INFINITY;
    return std::max({by_error, by_samples, 1e-300});
}

double growth_uncertainty(double n_eff) {
    return std::sqrt(2.0 / (std::isfinite(n_eff) ? std::max(n_eff, 1.0) : 8.0));
}

double look_length(const AccuracyTarget& target, double minimum, int k) {
    return minimum * std::pow(target.look_ratio, k);
}

Forecast forecast(const AccuracyTarget& target, const TargetLook& look, double minimum) {
    Forecast f;
    if (!(look.length > 0) || look.quantities.empty()) return f;
    double need = 0, rel = 0;
    for (const QuantityLook& q : look.quantities) {
        if (!q.found) return f;
        if (q.length_needed > need) {
            need = q.length_needed;
            rel = q.relative_uncertainty;
        }
    }
    const double per_length = look.cpu_measuring / look.length;
    auto cpu_at = [&](double length) {
        return cpu_after_growth(look.cpu, look.cpu_measuring, length / look.length);
    };
    auto stop_at = [&](double length) {  // the first look at or past `length`
        int k = 0;
        while (look_length(target, minimum, k) < length * (1 - 1e-12) && k < 200) ++k;
        return std::max(look_length(target, minimum, k), look.length);
    };
    f.valid = std::isfinite(need) && std::isfinite(per_length);
    f.length = need;
    // The run stops at a look, never before the one it is at: a target already met costs what
    // was spent.
    f.cpu = cpu_at(std::max(look.length, need));
    f.cpu_low = cpu_at(std::max(look.length, need / (1 + rel)));
    f.cpu_high = cpu_at(std::max(look.length, need * (1 + rel)));
    f.stop_length = stop_at(need);
    f.cpu_at_stop = cpu_at(f.stop_length);
    for (const QuantityLook& q : look.quantities) {
        f.cpu_per_quantity.push_back(cpu_at(q.length_needed));
        f.uncertainty_per_quantity.push_back(q.relative_uncertainty);
    }
    return f;
}

std::vector<std::string> describe(const TargetLook& look, const Forecast& f) {
    std::vector<std::string> lines;
    for (std::size_t k = 0; k < look.quantities.size(); ++k) {
        const QuantityLook& q = look.quantities[k];
        if (!q.found) {
            lines.push_back(fmt::format("{}: not in the summary yet", q.quantity));
            continue;
        }
        std::string s =
            fmt::format("{} = {:.6g} +- {:.3g} (target {:.3g}, n_eff {:.0f}): {}", q.quantity,
                        q.value, q.error, q.target, q.n_eff, q.met ? "reached" : "not yet");
        if (!q.met && f.valid && k < f.cpu_per_quantity.size())
            s += fmt::format("; about {:.3g} CPU s in all to reach it (+-{:.0f}%)",
                             f.cpu_per_quantity[k], 100 * q.relative_uncertainty);
        lines.push_back(s);
    }
    return lines;
}

// ---- TargetTracker ----------------------------------------------------------------------------

bool TargetTracker::take_look(const YAML::Node& observables_summary, double length, double cpu,
                              double cpu_measuring) {
    TargetLook look = look_at(target_, observables_summary, length, cpu, cpu_measuring,
                              have_last_ ? &out_.last : nullptr);
    ++next_look_;
    out_.looks = next_look_;
    for (const QuantityLook& q : look.quantities) {
        if (q.found) continue;
        const auto names = summary_names(observables_summary);
        const TargetError& t =
            *std::find_if(target_.targets.begin(), target_.targets.end(),
                          [&](const TargetError& e) { return e.quantity == q.quantity; });
        out_.status = "unknown_quantity";
        out_.reason = fmt::format(
            "{}: '{}' is not a quantity with an error bar in this run's summary; it has: {}",
            t.location, q.quantity, fmt::join(names, ", "));
        out_.last = look;
        have_last_ = true;
        spdlog::error("{}", out_.reason);
        return true;
    }
    const Forecast f = forecast(target_, look, minimum_);
    if (look.index == 0) out_.first_forecast = f;
    spdlog::info("look {} at {:.6g} measured ({:.3g} CPU s):", look.index + 1, length, cpu);
    for (const std::string& line : describe(look, f)) spdlog::info("  {}", line);
    if (!look.all_met() && f.valid)
        spdlog::info(
            "  forecast: the targets are reached after about {:.6g} measured, {:.3g} CPU s in "
            "all ({:.3g}-{:.3g}); the run stops at the first look past it ({:.6g})",
            f.length, f.cpu, f.cpu_low, f.cpu_high, f.stop_length);
    out_.last = look;
    have_last_ = true;
    if (look.all_met()) {
        out_.status = "reached";
        out_.reason.clear();
        return true;
    }
    if (!look.stalled.empty()) {
        out_.status = "not_reachable";
        out_.reason = look.stalled;
        spdlog::warn("target not reachable: {}", look.stalled);
        return true;
    }
    return false;
}

bool TargetTracker::over_cap(double cpu, std::uint64_t work) const {
    return cpu >= target_.max_cost.cpu_seconds || work >= target_.max_cost.work;
}

void TargetTracker::stopped_at_cap(const YAML::Node& observables_summary, double length, double cpu,
                                   double cpu_measuring) {
    out_.last = look_at(target_, observables_summary, length, cpu, cpu_measuring,
                        have_last_ ? &out_.last : nullptr);
    have_last_ = true;
    ++out_.looks;
    if (out_.last.all_met()) {
        out_.status = "reached";
        return;
    }
    out_.status = "target_not_reached";
    std::vector<std::string> missed;
    for (const QuantityLook& q : out_.last.quantities) {
        if (!q.met)
            missed.push_back(q.found ? fmt::format("{} +- {:.3g} (target {:.3g}, n_eff {:.0f})",
                                                   q.quantity, q.error, q.target, q.n_eff)
                                     : q.quantity + " (not in the summary)");
    }
    out_.reason = fmt::format("max_cost {} spent at {:.6g} measured: {}", target_.max_cost.text,
                              length, fmt::join(missed, "; "));
    spdlog::warn("target not reached: {}", out_.reason);
}

void TargetTracker::stopped(const std::string& why) {
    if (!out_.status.empty()) return;
    out_.status = why;
    out_.reason = "the run ended before its targets were looked at again";
}

void TargetTracker::write(ResultGroup& g, double cpu_total, std::uint64_t work,
                          const std::string& work_unit) const {
    g.text("status", out_.status.empty() ? std::string("measuring") : out_.status);
    if (!out_.reason.empty()) g.text("reason", out_.reason);
    g.value("looks", std::int64_t(out_.looks));
    g.value("measured", out_.last.length, unit_);
    g.value("cpu_seconds", cpu_total, "s");
    g.value("work", work, work_unit);
    if (!target_.max_cost.text.empty()) g.text("max_cost", target_.max_cost.text);
    g.value("min_effective_samples", std::int64_t(target_.min_effective_samples));
    const Forecast& f = out_.first_forecast;
    if (f.valid) {
        ResultGroup fg = g.group("forecast");
        fg.value("cpu_seconds", f.cpu, "s");
        fg.value("cpu_seconds_low", f.cpu_low, "s");
        fg.value("cpu_seconds_high", f.cpu_high, "s");
        fg.value("measured", f.length, unit_);
        fg.value("stop_at_look", f.stop_length, unit_);
        fg.value("cpu_seconds_at_stop_look", f.cpu_at_stop, "s");
        fg.value("spent_over_forecast", cpu_total / f.cpu);
    }
    for (std::size_t k = 0; k < target_.targets.size(); ++k) {
        const TargetError& t = target_.targets[k];
        ResultGroup q = g.group("quantities").group(t.quantity);
        q.text("target_error", t.text);
        if (k >= out_.last.quantities.size() || !out_.last.quantities[k].found) continue;
        const QuantityLook& l = out_.last.quantities[k];
        q.value("target", l.target);
        q.value("value", l.value);
        q.value("error", l.error);
        if (std::isfinite(l.n_eff)) q.value("n_eff", l.n_eff);
        q.flag("reached", l.met);
        if (f.valid && k < f.cpu_per_quantity.size() && k < f.uncertainty_per_quantity.size()) {
            q.value("forecast_cpu_seconds", f.cpu_per_quantity[k], "s");
            q.value("forecast_uncertainty", f.uncertainty_per_quantity[k]);
        }
    }
}

void TargetTracker::checkpoint(StateArchive& ar) {
    ar.section("target");
    ar.io(next_look_);
    ar.io(out_.looks);
    ar.io(out_.status);
    ar.io(out_.reason);
    ar.io(have_last_);
    ar.io(out_.last.index);
    ar.io(out_.last.length);
    std::vector<double> value, error, n_eff, found;
    for (const QuantityLook& q : out_.last.quantities) {
        value.push_back(q.value);
        error.push_back(q.error);
        n_eff.push_back(q.n_eff);
        found.push_back(q.found ? 1 : 0);
    }
    ar.io(value);
    ar.io(error);
    ar.io(n_eff);
    ar.io(found);
    if (ar.loading()) {
        out_.last.quantities.assign(n_eff.size(), QuantityLook{});
        for (std::size_t k = 0; k < n_eff.size(); ++k) {
            QuantityLook& q = out_.last.quantities[k];
            q.value = value[k];
            q.error = error[k];
            q.n_eff = n_eff[k];
            q.found = found[k] != 0;
            q.quantity = target_.targets[k].quantity;
        }
    }
    Forecast& f = out_.first_forecast;
    ar.io(f.valid);
    ar.io(f.length);
    ar.io(f.cpu);
    ar.io(f.cpu_low);
    ar.io(f.cpu_high);
    ar.io(f.stop_length);
    ar.io(f.cpu_at_stop);
    ar.io(f.cpu_per_quantity);
    ar.io(f.uncertainty_per_quantity);
}

}  // namespace gran
