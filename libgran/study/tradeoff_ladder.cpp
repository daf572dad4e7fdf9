#include "libgran/study/tradeoff_ladder.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include "libgran/core/scene_error.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/study/knob.hpp"

namespace gran {

namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

void require_registered_knobs(const std::vector<std::string>& wanted) {
    for (const auto& w : wanted) {
        if (!KnobRegistry::instance().find(w)) {
            throw SceneError(fmt::format(
                "gran tradeoff: unknown knob '{}'; the knobs are {} (or --knob KEY=v1,v2,... for "
                "any scene key)",
                w, knob_names()));
        }
    }
}

// Drop levels the scene cannot take (e.g. a box too narrow for its cells at small N): the
// reason is noted, the rest of the ladder runs.
void drop_refused_levels(const TradeoffRequest& rq, Knob& k, std::vector<std::string>& skipped) {
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

// The user's own ladders (--knob KEY=v1,v2,...): cheapest first, most accurate last. A level
// equal to the base scene's own value is the base (not run twice).
std::vector<Knob> custom_knobs(const TradeoffRequest& rq) {
    std::vector<Knob> out;
    if (rq.custom.empty()) return out;
    const Scene base_scene = load_scene(rq.scene, rq.sets);
    for (const auto& [key, values] : rq.custom) {
        const std::string own = resolved_value(base_scene.resolved, key);
        Knob k{key, "given with --knob (cheapest first, most accurate last)", {}, -1};
        for (const auto& v : values) {
            if (same_value(v, own)) {
                k.base = int(k.levels.size());
                k.levels.push_back({v, {}});
            } else {
                k.levels.push_back({v, {{key, v}}});
            }
        }
        out.push_back(k);
    }
    return out;
}

// The reference point: every knob at its most accurate level, and its label
// ("dt_over_tc=0.01 N=x1").
struct Reference {
    Sets set;
    std::vector<std::string> labels;
};

Reference reference_of(const std::vector<Knob>& knobs) {
    Reference ref;
    for (const auto& k : knobs) {
        const auto& best = k.levels.back();
        if (int(k.levels.size()) - 1 != k.base) {
            ref.set.insert(ref.set.end(), best.set.begin(), best.set.end());
            ref.labels.push_back(k.name + "=" + best.label);
        }
    }
    // On the event-driven engine the DEM knobs mean nothing: the reference is the hard limit.
    const bool hard_limit = std::any_of(ref.set.begin(), ref.set.end(), [](const auto& kv) {
        return kv.first == "engine" && kv.second.find("event_driven") != std::string::npos;
    });
    if (hard_limit) {
        std::erase_if(ref.set, [](const auto& kv) {
            return kv.first.rfind("engine.", 0) == 0 || kv.first == "interactions.stiffness" ||
                   kv.first == "interactions.contact_time";
        });
        std::erase_if(ref.labels, [](const std::string& l) {
            return l.rfind("dt_over_tc=", 0) == 0 || l.rfind("stiffness=", 0) == 0;
        });
    }
    return ref;
}

// The study's scene, output folder and base overrides (`set`).
void emit_base(YAML::Emitter& em, const TradeoffRequest& rq, const std::string& output) {
    em << YAML::Key << "scene" << YAML::Value
       << std::filesystem::absolute(rq.scene).lexically_normal().string();
    em << YAML::Key << "output" << YAML::Value << output;
    if (rq.sets.empty()) return;
    em << YAML::Key << "set" << YAML::Value << YAML::BeginMap;
    for (const auto& s : rq.sets) {
        const auto eq = s.find('=');
        if (eq == std::string::npos)
            throw SceneError("gran tradeoff: --set expects key=value, got '" + s + "'");
        em << YAML::Key << s.substr(0, eq) << YAML::Value << s.substr(eq + 1);
    }
    em << YAML::EndMap;
}

void emit_tradeoff_section(YAML::Emitter& em, const TradeoffRequest& rq, const Reference& ref) {
    em << YAML::Key << "tradeoff" << YAML::Value << YAML::BeginMap;
    em << YAML::Key << "reference" << YAML::Value << (ref.set.empty() ? "base" : "reference");
    if (!rq.quantities.empty()) {
        em << YAML::Key << "quantities" << YAML::Value << YAML::Flow << rq.quantities;
    }
    if (!rq.analytic.empty()) {
        em << YAML::Key << "analytic" << YAML::Value << YAML::BeginMap;
        for (const auto& [q, v] : rq.analytic) em << YAML::Key << q << YAML::Value << v;
        em << YAML::EndMap;
    }
    if (!rq.target_error.empty()) {
        em << YAML::Key << "target_error" << YAML::Value << YAML::BeginMap;
        for (const auto& a : rq.target_error) {
            const auto eq = a.rfind('=');
            if (eq == std::string::npos || eq == 0 || eq + 1 >= a.size())
                throw SceneError(
                    "gran tradeoff: --target-error expects QUANTITY=0.002 or "
                    "QUANTITY=1%, got '" +
                    a + "'");
            em << YAML::Key << a.substr(0, eq) << YAML::Value << a.substr(eq + 1);
        }
        em << YAML::EndMap;
    }
    em << YAML::EndMap;
}

void emit_point(YAML::Emitter& em, const std::string& name, const std::string& knob,
                const std::string& level, const Sets& set) {
    em << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << name << YAML::Key
       << "knob" << YAML::Value << knob << YAML::Key << "level" << YAML::Value << level;
    if (!set.empty()) {
        em << YAML::Key << "set" << YAML::Value << YAML::BeginMap;
        for (const auto& [key, v] : set) em << YAML::Key << key << YAML::Value << v;
        em << YAML::EndMap;
    }
    em << YAML::EndMap;
}

Sets sorted(Sets v) {
    std::sort(v.begin(), v.end());
    return v;
}

// The points: the base, every other level of one knob at a time, and the reference.
void emit_points(YAML::Emitter& em, const std::vector<Knob>& knobs, const Reference& ref) {
    em << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
    emit_point(em, "base", "base", "scene", {});
    std::set<std::string> names{"base", "reference"};
    const Sets reference_sorted = sorted(ref.set);
    std::string reference_knob = "reference";
    for (const auto& k : knobs) {
        for (int l = 0; l < int(k.levels.size()); ++l) {
            if (l == k.base) continue;
            const KnobLevel& level = k.levels[std::size_t(l)];
            // A level that is the reference itself (a single raised knob, or the event-driven
            // limit) runs once, as the reference.
            if (!ref.set.empty() && sorted(level.set) == reference_sorted) {
                reference_knob = k.name;
                continue;
            }
            std::string name = k.name + "_" + level.label;
            std::replace(name.begin(), name.end(), '/', '_');
            if (!names.insert(name).second) continue;
            emit_point(em, name, k.name, level.label, level.set);
        }
    }
    if (!ref.set.empty()) {
        std::string label;
        for (const auto& l : ref.labels) label += (label.empty() ? "" : " ") + l;
        emit_point(em, "reference", reference_knob, label, ref.set);
    }
    em << YAML::EndSeq;
}

// Comments after the study: what each knob trades, and why the others are no knobs here.
std::string notes(const std::vector<Knob>& knobs, const std::vector<std::string>& skipped) {
    std::string s = "\n";
    for (const auto& k : knobs) s += fmt::format("# knob {}: {}\n", k.name, k.doc);
    for (const auto& x : skipped) s += "# not a knob here: " + x + "\n";
    return s;
}

}  // namespace

std::vector<Knob> automatic_knobs(const TradeoffRequest& rq, std::vector<std::string>& skipped) {
    require_registered_knobs(rq.knobs);
    auto wanted = [&](const std::string& n) {
        return rq.knobs.empty() || std::find(rq.knobs.begin(), rq.knobs.end(), n) != rq.knobs.end();
    };
    const Scene sc = load_scene(rq.scene, rq.sets);
    YAML::Node raw;
    try {
        raw = YAML::LoadFile(rq.scene);
    } catch (const YAML::Exception&) {
    }
    const KnobContext context{rq, sc, sc.resolved, raw};
    std::vector<Knob> out;
    for (const KnobPlugin* p : knobs_in_order()) {
        if (!wanted(p->name)) continue;
        KnobOutcome o = p->make(context);
        if (auto* reason = std::get_if<std::string>(&o)) {
            skipped.push_back(p->name + ": " + *reason);
        } else {
            out.push_back(std::move(std::get<Knob>(o)));
        }
    }
    for (auto& k : out) drop_refused_levels(rq, k, skipped);
    return out;
}

std::string tradeoff_study_text(const TradeoffRequest& rq, const std::string& output) {
    std::vector<std::string> skipped;
    std::vector<Knob> knobs;
    if (rq.custom.empty() || !rq.knobs.empty()) knobs = automatic_knobs(rq, skipped);
    for (Knob& k : custom_knobs(rq)) knobs.push_back(std::move(k));
    const Reference ref = reference_of(knobs);

    YAML::Emitter em;
    em << YAML::Comment(fmt::format(
              "generated by `gran tradeoff {}`: one knob at a time from the base scene, and the "
              "reference with every knob at its most accurate level",
              rq.scene))
       << YAML::Newline;
    em << YAML::BeginMap;
    emit_base(em, rq, output);
    emit_tradeoff_section(em, rq, ref);
    emit_points(em, knobs, ref);
    em << YAML::EndMap;
    return std::string(em.c_str()) + notes(knobs, skipped);
}

}  // namespace gran
