#include "libgran/study/study_forecast.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <set>

namespace gran {

namespace {

bool has_target(const StudyRun& run) {
    try {
        const YAML::Node scene = YAML::Load(run.resolved_scene);
        return scene["run"] && scene["run"]["target_error"] &&
               scene["run"]["target_error"].IsMap() && scene["run"]["target_error"].size() > 0;
    } catch (const YAML::Exception&) {
        return false;
    }
}

double number(const YAML::Node& n) {
    if (!n) return std::nan("");
    const YAML::Node v = n.IsMap() ? n["value"] : n;
    try {
        return v ? v.as<double>() : std::nan("");
    } catch (const YAML::Exception&) {
        return std::nan("");
    }
}

// A pilot's forecast: CPU seconds per run and its range; status as the pilot left it.
struct PilotForecast {
    bool ok = false;
    std::string status;
    double cpu = 0, low = 0, high = 0;
    double at_stop = 0;  // at the look where the run stops if the forecast is right
};

PilotForecast read_pilot(const std::string& summary) {
    PilotForecast p;
    if (summary.empty()) return p;
    try {
        const YAML::Node t = YAML::LoadFile(summary)["target"];
        if (!t) return p;
        p.status = t["status"] ? t["status"].as<std::string>() : "";
        const YAML::Node f = t["forecast"];
        p.cpu = number(f["cpu_seconds"]);
        p.low = number(f["cpu_seconds_low"]);
        p.high = number(f["cpu_seconds_high"]);
        p.at_stop = number(f["cpu_seconds_at_stop_look"]);
        p.ok = std::isfinite(p.cpu) && std::isfinite(p.low) && std::isfinite(p.high) &&
               std::isfinite(p.at_stop);
    } catch (const YAML::Exception&) {
        p.ok = false;
    }
    return p;
}

std::string describe_status(const std::string& status) {
    if (status == "reached") return "reached at the first look";
    if (status == "measuring") return "first look";
    return status.empty() ? "first look" : status;
}

}  // namespace

std::vector<std::size_t> runs_to_pilot(const Study& st) {
    std::vector<std::size_t> out;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (seen.count(st.runs[i].point)) continue;
        seen.insert(st.runs[i].point);
        if (has_target(st.runs[i])) out.push_back(i);
    }
    return out;
}

std::string study_forecast_report(const Study& st, const std::vector<std::string>& pilot_summaries,
                                  int jobs) {
    std::map<std::string, int> runs_of;  // point -> runs
    for (const StudyRun& r : st.runs) ++runs_of[r.point];
    std::string s = fmt::format(
        "# Forecast: {}\n\nThe CPU time each point's runs are forecast to need to reach their "
        "targets (run.target_error), from one pilot per point: equilibration and the first look "
        "of the measurement, as `gran check` runs it. The forecast is that of runs with a target "
        "(docs/choosing-speed-or-accuracy.md): per run, the CPU time to the length the targets "
        "need, with its range, and at the look where the run then stops (looks are 1.5x apart, "
        "so a run spends up to 1.5x the measurement it needs); a short first look forecasts "
        "low. Replicas are forecast to cost what their point's pilot forecasts.\n\n"
        "| point | runs | pilot | CPU s per run to the targets (range) | at the stopping look | "
        "all its runs, at their stopping looks |\n"
        "|---|---:|---|---:|---:|---:|\n",
        st.file);
    double total = 0, low = 0, high = 0, at_stop = 0;
    int forecast_runs = 0;
    std::vector<std::string> failed, fixed;
    const std::vector<std::size_t> piloted = runs_to_pilot(st);
    std::set<std::string> piloted_points;
    for (std::size_t i : piloted) {
        const std::string& point = st.runs[i].point;
        piloted_points.insert(point);
        const PilotForecast p =
            read_pilot(i < pilot_summaries.size() ? pilot_summaries[i] : std::string());
        const int n = runs_of[point];
        if (!p.ok) {
            failed.push_back(point);
            s += fmt::format("| {} | {} | failed or no forecast | - | - | - |\n", point, n);
            continue;
        }
        s += fmt::format("| {} | {} | {} | {:.3g} ({:.3g}-{:.3g}) | {:.3g} | {:.3g} |\n", point, n,
                         describe_status(p.status), p.cpu, p.low, p.high, p.at_stop, n * p.at_stop);
        total += n * p.cpu;
        at_stop += n * p.at_stop;
        low += n * p.low;
        high += n * p.high;
        forecast_runs += n;
    }
    for (const auto& [point, n] : runs_of)
        if (!piloted_points.count(point)) fixed.push_back(fmt::format("{} ({} runs)", point, n));
    s += fmt::format(
        "\ntotal for the {} runs with a forecast: {:.3g} CPU s at their stopping looks ({:.3g} "
        "to the targets, {:.3g}-{:.3g}); on {} core{} at least {:.3g} s of wall time\n",
        forecast_runs, at_stop, total, low, high, jobs, jobs == 1 ? "" : "s",
        at_stop / std::max(jobs, 1));
    if (!fixed.empty())
        s += fmt::format("points without a target (fixed length, not forecast): {}\n",
                         fmt::join(fixed, ", "));
    if (!failed.empty())
        s += fmt::format("points whose pilot gave no forecast (see pilots/logs): {}\n",
                         fmt::join(failed, ", "));
    return s;
}

}  // namespace gran
