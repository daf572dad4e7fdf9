#include "libgran/study/knob.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace gran {

bool register_knob(std::string name, int order, std::string summary,
                   std::function<KnobOutcome(const KnobContext&)> make) {
    KnobPlugin p;
    p.name = std::move(name);
    p.summary = std::move(summary);
    p.order = order;
    p.make = std::move(make);
    return KnobRegistry::instance().add(std::move(p));
}

std::vector<const KnobPlugin*> knobs_in_order() {
    std::vector<const KnobPlugin*> v = KnobRegistry::instance().all();
    std::stable_sort(v.begin(), v.end(),
                     [](const KnobPlugin* a, const KnobPlugin* b) { return a->order < b->order; });
    return v;
}

std::string knob_names() {
    std::string s;
    for (const KnobPlugin* k : knobs_in_order()) s += (s.empty() ? "" : ", ") + k->name;
    return s;
}

namespace knobs {

std::string number(double x) {
    return fmt::format("{:.6g}", x);
}

double real_at(const YAML::Node& n, const char* key, double fallback) {
    if (!n || !n[key]) return fallback;
    try {
        return n[key].as<double>();
    } catch (const YAML::Exception&) {
        return fallback;
    }
}

bool has_set(const std::vector<std::string>& sets, const std::string& key) {
    return std::any_of(sets.begin(), sets.end(),
                       [&](const std::string& s) { return s.rfind(key + "=", 0) == 0; });
}

std::string fraction_label(double f) {
    if (f == 1) return "x1";
    if (f < 1) return fmt::format("x1/{}", int(std::lround(1 / f)));
    return fmt::format("x{}", number(f));
}

Knob scaled(const std::string& name, const std::string& doc, const std::string& key, double base,
            const std::vector<double>& factors, double max_value) {
    Knob k{name, doc, {}, -1};
    for (double f : factors) {
        const double v = base * f;
        if (v > max_value * (1 + 1e-12)) continue;
        if (f == 1) k.base = int(k.levels.size());
        k.levels.push_back({number(v), f == 1 ? std::vector<std::pair<std::string, std::string>>{}
                                              : std::vector<std::pair<std::string, std::string>>{
                                                    {key, number(v)}}});
    }
    return k;
}

std::string engine_type(const KnobContext& c) {
    const YAML::Node eng = c.resolved["engine"];
    return eng && eng["type"] ? eng["type"].Scalar() : "";
}

}  // namespace knobs

}  // namespace gran
