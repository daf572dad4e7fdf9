#include "libgran/study/tradeoff_ladder.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "libgran/scene/scene.hpp"
#include "libgran/core/scene_error.hpp"

namespace gran {

namespace {

const std::vector<std::string> kKnobNames{"dt_over_tc",    "stiffness", "engine",
                                          "kick_interval", "N",         "measurement"};

std::string num(double x) {
    return fmt::format("{:.6g}", x);
}

double real_at(const YAML::Node& n, const char* key, double fallback = 0) {
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

// Levels base * factor (factors from cheapest to most accurate); base level where factor == 1.
Knob scaled_knob(const std::string& name, const std::string& doc, const std::string& key,
                 double base, const std::vector<double>& factors, double max_value = INFINITY) {
    Knob k{name, doc, {}, -1};
    for (double f : factors) {
        const double v = base * f;
        if (v > max_value * (1 + 1e-12)) continue;
        if (f == 1) k.base = int(k.levels.size());
        k.levels.push_back(
            {num(v), f == 1 ? std::vector<std::pair<std::string, std::string>>{}
                            : std::vector<std::pair<std::string, std::string>>{{key, num(v)}}});
    }
    return k;
}

std::string fraction_label(double f) {
    if (f == 1) return "x1";
    if (f < 1) return fmt::format("x1/{}", int(std::lround(1 / f)));
    return fmt::format("x{}", num(f));
}

// The text of a dotted scene key ("run.sample_interval", "drivers.0.interval") in the resolved
// scene, "" when absent.
std::string resolved_value(const YAML::Node& root, const std::string& key) {
    YAML::Node n;
    n.reset(root);  // reset rebinds; `=` would assign into the node it refers to
    std::stringstream ss(key);
    for (std::string part; std::getline(ss, part, '.');) {
        if (n.IsSequence()) {
            std::size_t i = 0;
            try {
                i = std::stoul(part);
            } catch (const std::exception&) {
                return "";
            }
            if (i >= n.size()) return "";
            n.reset(n[i]);
        } else if (n.IsMap() && n[part]) {
            n.reset(n[part]);
        } else {
            return "";
        }
    }
    return n.IsScalar() ? n.Scalar() : "";
}

bool same_value(const std::string& a, const std::string& b) {
    if (a == b) return true;
    try {
        std::size_t ia = 0, ib = 0;
        const double x = std::stod(a, &ia), y = std::stod(b, &ib);
        return ia == a.size() && ib == b.size() && x == y;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

std::vector<Knob> automatic_knobs(const TradeoffRequest& rq, std::vector<std::string>& skipped) {
    for (const auto& w : rq.knobs) {
        if (std::find(kKnobNames.begin(), kKnobNames.end(), w) == kKnobNames.end()) {
            throw SceneError(fmt::format(
                "gran tradeoff: unknown knob '{}'; the knobs are dt_over_tc, stiffness, engine, "
                "kick_interval, N, measurement (or --knob KEY=v1,v2,... for any scene key)",
                w));
        }
    }
    auto wanted = [&](const std::string& n) {
        return rq.knobs.empty() || std::find(rq.knobs.begin(), rq.knobs.end(), n) != rq.knobs.end();
    };
    const Scene sc = load_scene(rq.scene, rq.sets);
    const YAML::Node r = sc.resolved;
    YAML::Node raw;
    try {
        raw = YAML::LoadFile(rq.scene);
    } catch (const YAML::Exception&) {
    }
    std::vector<Knob> out;
    const YAML::Node eng = r["engine"];
    const bool dem = eng && eng["type"] && eng["type"].Scalar() == "dem";

    if (wanted("dt_over_tc")) {
        if (!dem) {
            skipped.push_back("dt_over_tc: the event-driven engine has no time step");
        } else if (real_at(eng, "dt") > 0) {
            skipped.push_back("dt_over_tc: engine.dt is set explicitly; use engine.dt_fraction");
        } else {
            out.push_back(scaled_knob(
                "dt_over_tc", "DEM time step as a fraction of the contact time t_c",
                "engine.dt_fraction", real_at(eng, "dt_fraction", 0.02), {4, 2, 1, 0.5}, 0.2));
        }
    }
    const YAML::Node contacts = r["interactions"];
    if (wanted("stiffness")) {
        if (!dem) {
            skipped.push_back("stiffness: hard spheres are infinitely stiff");
        } else if (real_at(contacts, "stiffness") > 0) {
            out.push_back(scaled_knob("stiffness",
                                      "normal spring stiffness k_n: stiffer is harder spheres, "
                                      "shorter contacts, smaller steps",
                                      "interactions.stiffness", real_at(contacts, "stiffness"),
                                      {0.01, 0.1, 1, 10}));
        } else {
            out.push_back(scaled_knob("stiffness", "contact time t_c (shorter is stiffer)",
                                      "interactions.contact_time",
                                      real_at(contacts, "contact_time"),
                                      {10, std::sqrt(10.0), 1, 1 / std::sqrt(10.0)}));
        }
    }
    if (wanted("engine")) {
        if (!dem) {
            skipped.push_back("engine: the scene is event-driven already (the hard limit)");
        } else if (sc.contacts.rotating) {
            skipped.push_back(
                "engine: friction makes the soft-sphere model differ from the event-driven "
                "one (rough hard spheres have a tangential restitution instead)");
        } else {
            Knob k{"engine",
                   "event-driven hard spheres: the k_n -> infinity, dt -> 0 limit",
                   {{"dem", {}}, {"event_driven", {{"engine", "{type: event_driven}"}}}},
                   0};
            out.push_back(k);
        }
    }
    if (wanted("kick_interval")) {
        const YAML::Node drivers = r["drivers"];
        bool found = false;
        for (std::size_t i = 0; drivers && i < drivers.size(); ++i) {
            if (drivers[i]["type"] && drivers[i]["type"].Scalar() == "stochastic_thermostat") {
                out.push_back(scaled_knob("kick_interval", "time between thermostat kicks",
                                          fmt::format("drivers.{}.interval", i),
                                          real_at(drivers[i], "interval"), {4, 2, 1, 0.5}));
                found = true;
                break;
            }
        }
        if (!found) skipped.push_back("kick_interval: no stochastic_thermostat driver");
    }
    if (wanted("N")) {
        Knob k{"N", "number of particles at the same density (finite-size effects)", {}, -1};
        const bool by_fraction = (raw["box"] && raw["box"]["packing_fraction"]) ||
                                 has_set(rq.sets, "box.packing_fraction");
        const bool by_total = (raw["particles"] && true) || has_set(rq.sets, "particles");
        const YAML::Node species = r["species"];
        const YAML::Node lengths = r["box"]["lengths"];
        const YAML::Node periodic = r["box"]["periodic"];
        int n_periodic = 0;
        for (std::size_t a = 0; periodic && a < periodic.size(); ++a)
            n_periodic += periodic[a].as<bool>() ? 1 : 0;
        for (double f : {0.125, 0.25, 0.5, 1.0}) {
            KnobLevel lv{fraction_label(f), {}};
            bool too_small = false;
            if (f != 1) {
                if (by_total) {
                    const long n = std::lround(f * r["particles"].as<double>());
                    too_small = n < 8;
                    lv.set.emplace_back("particles", std::to_string(n));
                } else {
                    for (std::size_t s = 0; s < species.size(); ++s) {
                        const long n = std::lround(f * species[s]["count"].as<double>());
                        too_small = too_small || n < 4;
                        lv.set.emplace_back(fmt::format("species.{}.count", s), std::to_string(n));
                    }
                }
                if (!by_fraction) {
                    // The same density: scale the periodic (lateral) lengths, or every length
                    // of a closed box.
                    const int dims = int(lengths.size());
                    const int scaled = n_periodic > 0 ? n_periodic : dims;
                    const double g = std::pow(f, 1.0 / scaled);
                    for (int a = 0; a < dims; ++a) {
                        if (n_periodic > 0 && !periodic[std::size_t(a)].as<bool>()) continue;
                        lv.set.emplace_back(fmt::format("box.lengths.{}", a),
                                            num(lengths[std::size_t(a)].as<double>() * g));
                    }
                }
            }
            if (too_small) continue;
            if (f == 1) k.base = int(k.levels.size());
            k.levels.push_back(lv);
        }
        if (k.levels.size() > 1) {
            out.push_back(k);
        } else {
            skipped.push_back("N: too few particles to scale down");
        }
    }
    if (wanted("measurement")) {
        const double m = real_at(r["run"], "measurement");
        Knob k{"measurement", "length of the measurement (statistical error)", {}, -1};
        for (double f : {0.125, 0.25, 0.5, 1.0}) {
            if (f == 1) k.base = int(k.levels.size());
            k.levels.push_back(
                {fraction_label(f), f == 1 ? std::vector<std::pair<std::string, std::string>>{}
                                           : std::vector<std::pair<std::string, std::string>>{
                                                 {"run.measurement", num(m * f)}}});
        }
        out.push_back(k);
    }
    // Drop levels the scene cannot take (e.g. a box too narrow for its cells at small N): the
    // reason is noted, the rest of the ladder runs.
    for (auto& k : out) {
        std::vector<KnobLevel> kept;
        int base = -1;
        for (int l = 0; l < int(k.levels.size()); ++l) {
            std::vector<std::string> sets = rq.sets;
            for (const auto& [key, v] : k.levels[std::size_t(l)].set) sets.push_back(key + "=" + v);
            try {
                if (l != k.base) (void)load_scene(rq.scene, sets);
            } catch (const SceneError& e) {
                skipped.push_back(
                    fmt::format("{} = {}: {}", k.name, k.levels[std::size_t(l)].label, e.what()));
                continue;
            }
            if (l == k.base) base = int(kept.size());
            kept.push_back(k.levels[std::size_t(l)]);
        }
        k.levels = std::move(kept);
        k.base = base;
    }
    return out;
}

std::string tradeoff_study_text(const TradeoffRequest& rq, const std::string& output) {
    std::vector<std::string> skipped;
    std::vector<Knob> knobs;
    if (rq.custom.empty() || !rq.knobs.empty()) knobs = automatic_knobs(rq, skipped);
    std::optional<Scene> base_scene;
    for (const auto& [key, values] : rq.custom) {
        // The user's own ladder: cheapest first, most accurate last. A level equal to the base
        // scene's own value is the base (not run twice).
        if (!base_scene) base_scene = load_scene(rq.scene, rq.sets);
        const std::string own = resolved_value(base_scene->resolved, key);
        Knob k{key, "given with --knob (cheapest first, most accurate last)", {}, -1};
        for (const auto& v : values) {
            if (same_value(v, own)) {
                k.base = int(k.levels.size());
                k.levels.push_back({v, {}});
            } else {
                k.levels.push_back({v, {{key, v}}});
            }
        }
        knobs.push_back(k);
    }

    YAML::Emitter em;
    em << YAML::Comment(fmt::format(
              "generated by `gran tradeoff {}`: one knob at a time from the base scene, and the "
              "reference with every knob at its most accurate level",
              rq.scene))
       << YAML::Newline;
    em << YAML::BeginMap;
    em << YAML::Key << "scene" << YAML::Value
       << std::filesystem::absolute(rq.scene).lexically_normal().string();
    em << YAML::Key << "output" << YAML::Value << output;
    if (!rq.sets.empty()) {
        em << YAML::Key << "set" << YAML::Value << YAML::BeginMap;
        for (const auto& s : rq.sets) {
            const auto eq = s.find('=');
            if (eq == std::string::npos)
                throw SceneError("gran tradeoff: --set expects key=value, got '" + s + "'");
            em << YAML::Key << s.substr(0, eq) << YAML::Value << s.substr(eq + 1);
        }
        em << YAML::EndMap;
    }
    std::vector<std::pair<std::string, std::string>> reference;
    std::vector<std::string> reference_label;
    for (const auto& k : knobs) {
        const auto& best = k.levels.back();
        if (int(k.levels.size()) - 1 != k.base) {
            reference.insert(reference.end(), best.set.begin(), best.set.end());
            reference_label.push_back(k.name + "=" + best.label);
        }
    }
    // On the event-driven engine the DEM knobs mean nothing: the reference is the hard limit.
    const bool hard_limit = std::any_of(reference.begin(), reference.end(), [](const auto& kv) {
        return kv.first == "engine" && kv.second.find("event_driven") != std::string::npos;
    });
    if (hard_limit) {
        std::erase_if(reference, [](const auto& kv) {
            return kv.first.rfind("engine.", 0) == 0 || kv.first == "interactions.stiffness" ||
                   kv.first == "interactions.contact_time";
        });
        std::erase_if(reference_label, [](const std::string& l) {
            return l.rfind("dt_over_tc=", 0) == 0 || l.rfind("stiffness=", 0) == 0;
        });
    }
    em << YAML::Key << "tradeoff" << YAML::Value << YAML::BeginMap;
    em << YAML::Key << "reference" << YAML::Value << (reference.empty() ? "base" : "reference");
    if (!rq.quantities.empty()) {
        em << YAML::Key << "quantities" << YAML::Value << YAML::Flow << rq.quantities;
    }
    if (!rq.analytic.empty()) {
        em << YAML::Key << "analytic" << YAML::Value << YAML::BeginMap;
        for (const auto& [q, v] : rq.analytic) em << YAML::Key << q << YAML::Value << v;
        em << YAML::EndMap;
    }
    em << YAML::EndMap;
    em << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
    auto point = [&](const std::string& name, const std::string& knob, const std::string& level,
                     const std::vector<std::pair<std::string, std::string>>& set) {
        em << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << name
           << YAML::Key << "knob" << YAML::Value << knob << YAML::Key << "level" << YAML::Value
           << level;
        if (!set.empty()) {
            em << YAML::Key << "set" << YAML::Value << YAML::BeginMap;
            for (const auto& [key, v] : set) em << YAML::Key << key << YAML::Value << v;
            em << YAML::EndMap;
        }
        em << YAML::EndMap;
    };
    point("base", "base", "scene", {});
    std::set<std::string> names{"base", "reference"};
    auto sorted = [](std::vector<std::pair<std::string, std::string>> v) {
        std::sort(v.begin(), v.end());
        return v;
    };
    const auto reference_sorted = sorted(reference);
    std::string reference_knob = "reference";
    for (const auto& k : knobs) {
        for (int l = 0; l < int(k.levels.size()); ++l) {
            if (l == k.base) continue;
            // A level that is the reference itself (a single raised knob, or the event-driven
            // limit) runs once, as the reference.
            if (!reference.empty() && sorted(k.levels[std::size_t(l)].set) == reference_sorted) {
                reference_knob = k.name;
                continue;
            }
            std::string name = k.name + "_" + k.levels[std::size_t(l)].label;
            for (char& c : name) {
                if (c == '/') c = '_';
            }
            if (!names.insert(name).second) continue;
            point(name, k.name, k.levels[std::size_t(l)].label, k.levels[std::size_t(l)].set);
        }
    }
    if (!reference.empty()) {
        std::string label;
        for (const auto& l : reference_label) label += (label.empty() ? "" : " ") + l;
        point("reference", reference_knob, label, reference);
    }
    em << YAML::EndSeq << YAML::EndMap;
    std::string text = em.c_str();
    std::string notes = "\n";
    for (const auto& k : knobs) notes += fmt::format("# knob {}: {}\n", k.name, k.doc);
    for (const auto& s : skipped) notes += "# not a knob here: " + s + "\n";
    return text + notes;
}

}  // namespace gran
