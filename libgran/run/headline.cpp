#include "libgran/run/headline.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gran {

namespace {

struct Ratio {
    std::string from;  // "observables.<name>.<key>"
    YAML::Node estimate;
};

YAML::Node entry(const Ratio& r) {
    YAML::Node e(YAML::NodeType::Map);
    // Clones: a node shared with the observables section would be emitted as a YAML alias.
    e["value"] = YAML::Clone(r.estimate["value"]);
    e["error"] = YAML::Clone(r.estimate["error"]);
    e["from"] = r.from;
    return e;
}

const std::string kMiddle = "middle/ratios/";
const std::string kGamma = "/gamma";

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The first profiles observable's middle-of-the-cell gammas and the first temperatures
// observable's whole-system gammas, by species pair (in the summary's order).
void collect(const YAML::Node& observables, std::map<std::string, Ratio>& middle,
             std::map<std::string, Ratio>& whole, std::vector<std::string>& pairs) {
    for (auto it = observables.begin(); it != observables.end(); ++it) {
        const std::string name = it->first.as<std::string>();
        if (!it->second.IsMap()) continue;
        for (auto m = it->second.begin(); m != it->second.end(); ++m) {
            const std::string key = m->first.as<std::string>();
            if (key.rfind(kMiddle, 0) != 0 || !ends_with(key, kGamma)) continue;
            const std::string pair =
                key.substr(kMiddle.size(), key.size() - kMiddle.size() - kGamma.size());
            if (middle.count(pair) || pair.find('/') != std::string::npos) continue;
            middle[pair] = {"observables." + name + "." + key, m->second};
            if (!whole.count(pair)) pairs.push_back(pair);
        }
        const YAML::Node ratios = it->second["ratios"];
        if (!ratios || !ratios.IsMap()) continue;
        for (auto r = ratios.begin(); r != ratios.end(); ++r) {
            const std::string pair = r->first.as<std::string>();
            if (whole.count(pair) || !r->second["gamma"]) continue;
            whole[pair] = {"observables." + name + ".ratios." + pair + ".gamma",
                           r->second["gamma"]};
            if (!middle.count(pair)) pairs.push_back(pair);
        }
    }
}

}  // namespace

YAML::Node headline(const YAML::Node& summary) {
    YAML::Node out(YAML::NodeType::Map);
    const YAML::Node observables = summary["observables"];
    if (!observables || !observables.IsMap()) return out;
    std::map<std::string, Ratio> middle, whole;
    std::vector<std::string> pairs;
    collect(observables, middle, whole, pairs);
    const bool one = pairs.size() == 1;
    for (const std::string& pair : pairs) {
        const std::string suffix = one ? "" : "/" + pair;
        const auto m = middle.find(pair);
        const auto w = whole.find(pair);
        if (m != middle.end()) {
            out["gamma" + suffix] = entry(m->second);
            if (w != whole.end()) out["gamma_whole_system" + suffix] = entry(w->second);
        } else {
            out["gamma" + suffix] = entry(w->second);
        }
    }
    return out;
}

}  // namespace gran
