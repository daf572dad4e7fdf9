#include "libgran/scene/accuracy_target.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

namespace gran {

double TargetError::absolute(double value) const {
    return relative ? error * std::abs(value) : error;
}

namespace {

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return "";
    const auto b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

}  // namespace

TargetError read_target_error(const std::string& quantity, const YAML::Node& v, const Where& w) {
    if (!v.IsScalar()) fail(w, v, "expected an error bar: a number (0.002) or a percentage (1%)");
    TargetError t;
    t.quantity = quantity;
    t.text = v.Scalar();
    t.location = locate(w, v);
    std::string number = trim(t.text);
    if (!number.empty() && number.back() == '%') {
        t.relative = true;
        number = trim(number.substr(0, number.size() - 1));
    }
    try {
        std::size_t used = 0;
        t.error = std::stod(number, &used);
        if (used != number.size() && number.find_first_not_of(" \t", used) != std::string::npos)
            throw std::invalid_argument(number);
    } catch (const std::exception&) {
        fail(w, v,
             "expected an error bar: a number (0.002) or a percentage (1%), got '" + t.text + "'");
    }
    if (t.relative) t.error /= 100;
    if (!(t.error > 0) || !std::isfinite(t.error))
        fail(w, v, "the error bar must be positive and finite, got '" + t.text + "'");
    if (t.relative && t.error >= 1)
        fail(w, v, "a relative error bar of 100% or more asks for nothing: give less than 100%");
    return t;
}

namespace {

CostCap read_cap(const YAML::Node& v, const Where& w, const std::string& work_unit) {
    CostCap cap;
    if (!v.IsDefined() || v.IsNull()) return cap;
    if (!v.IsScalar())
        fail(w, v,
             "expected a cost: CPU seconds (600 or '600 s') or engine work ('1e9 " + work_unit +
                 "')");
    cap.text = v.Scalar();
    // "<number> [unit]": the number up to the first letter other than an exponent's e.
    const std::string text = trim(cap.text);
    std::size_t cut = 0;
    while (cut < text.size() &&
           (std::isdigit(static_cast<unsigned char>(text[cut])) || text[cut] == '.' ||
            text[cut] == '+' ||
            ((text[cut] == 'e' || text[cut] == 'E') && cut > 0 && cut + 1 < text.size() &&
             (std::isdigit(static_cast<unsigned char>(text[cut + 1])) || text[cut + 1] == '+' ||
              text[cut + 1] == '-'))))
        ++cut;
    double x = 0;
    try {
        std::size_t used = 0;
        x = cut > 0 ? std::stod(text.substr(0, cut), &used) : 0.0;
        if (used != cut) x = 0;
    } catch (const std::exception&) {
        x = 0;
    }
    const std::string unit = trim(text.substr(cut));
    if (!(x > 0) || !std::isfinite(x) ||
        !(unit.empty() || unit == "s" || unit == "events" || unit == "steps")) {
        fail(w, v,
             "expected a cost: CPU seconds (600 or '600 s') or engine work ('1e9 " + work_unit +
                 "'), got '" + cap.text + "'");
    }
    if (unit == "events" || unit == "steps") {
        if (unit != work_unit)
            fail(w, v, "this engine counts its work in " + work_unit + ", not " + unit);
        if (x >= 1.8e19) fail(w, v, "more work than a 64-bit counter holds");
        cap.work = static_cast<std::uint64_t>(std::ceil(x));
        cap.unit = unit;
    } else {
        cap.cpu_seconds = x;
        cap.unit = "s";
    }
    return cap;
}

}  // namespace

AccuracyTarget read_accuracy_target(const YAML::Node& run, const Where& where,
                                    const std::string& engine_work_unit) {
    AccuracyTarget out;
    const YAML::Node map = run.IsMap() ? run["target_error"] : YAML::Node();
    const Where wt = where.child("target_error");
    if (map.IsDefined() && !map.IsNull()) {
        if (!map.IsMap() || map.size() == 0)
            fail(wt, map,
                 "expected a map from summary quantities to error bars, e.g. "
                 "{observables.temperatures.ratios.light_over_heavy.gamma: 0.002}");
        for (auto it = map.begin(); it != map.end(); ++it) {
            const std::string q = it->first.as<std::string>();
            const Where wq = wt.child(q);
            if (q.rfind("observables.", 0) != 0 || q.size() <= 12)
                fail(wq, it->first,
                     "a target names a summary quantity of an observable, "
                     "observables.<name>.<quantity> as in a study table (gran run writes them "
                     "to OUT.summary.yaml)");
            out.targets.push_back(read_target_error(q, it->second, wq));
        }
    }
    const YAML::Node cap = run.IsMap() ? run["max_cost"] : YAML::Node();
    out.max_cost = read_cap(cap, where.child("max_cost"), engine_work_unit);
    const YAML::Node n = run.IsMap() ? run["min_effective_samples"] : YAML::Node();
    if (n.IsDefined() && !n.IsNull()) {
        try {
            out.min_effective_samples = n.as<std::int64_t>();
        } catch (const YAML::Exception&) {
            out.min_effective_samples = 0;
        }
        if (out.min_effective_samples < 2)
            fail(where.child("min_effective_samples"), n, "expected an integer >= 2");
    }
    if (!out.active() && out.max_cost.unit.size())
        fail(where.child("max_cost"), cap,
             "max_cost caps a run with run.target_error; a run of fixed length ends at "
             "run.measurement");
    return out;
}

YAML::Node resolved_target(const AccuracyTarget& target) {
    YAML::Node r;
    for (const TargetError& t : target.targets) r["target_error"][t.quantity] = t.text;
    if (!target.max_cost.text.empty()) r["max_cost"] = target.max_cost.text;
    r["min_effective_samples"] = target.min_effective_samples;
    return r;
}

}  // namespace gran
