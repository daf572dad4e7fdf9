// Reading a study file (docs/studies.md): its sections, validated at their keys, and the runs they
// expand to (points x grid combinations x zip index x replicas), each run's scene resolved so a bad
// override is refused before anything runs.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "libgran/core/scene_error.hpp"
#include "libgran/core/yaml_file.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/study/study.hpp"

namespace gran {

namespace fs = std::filesystem;

std::vector<std::string> assignments(const StudyRun& run) {
    std::vector<std::string> a;
    for (const auto& [k, v] : run.overrides) a.push_back(k + "=" + v);
    return a;
}

std::string override_value(const StudyRun& run, const std::string& key) {
    for (const auto& [k, v] : run.overrides) {
        if (k == key) return v;
    }
    return "";
}

namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;
using Lists = std::vector<std::pair<std::string, std::vector<YAML::Node>>>;

std::string yaml_text(const YAML::Node& n) {
    if (n.IsScalar()) return n.Scalar();
    YAML::Emitter em;
    em << YAML::Flow << n;
    return em.c_str();
}

// A value as it appears in a run name: lists joined by "x" ([0.2, 0.044] -> 0.2x0.044).
std::string label_text(const YAML::Node& n) {
    if (!n.IsSequence()) return yaml_text(n);
    std::string s;
    for (std::size_t i = 0; i < n.size(); ++i) s += (i ? "x" : "") + label_text(n[i]);
    return s;
}

// File-name safe: letters, digits and . _ + - only.
std::string safe_name(std::string s) {
    for (char& c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '+' &&
            c != '-')
            c = '_';
    }
    return s;
}

std::string last_key(const std::string& key) {
    const auto dot = key.rfind('.');
    return dot == std::string::npos ? key : key.substr(dot + 1);
}

void require_map(const Where& w, const YAML::Node& n, const std::string& what) {
    if (!n.IsMap()) fail(w, n, "expected " + what);
}

std::string require_string(const Where& w, const YAML::Node& n) {
    if (!n.IsScalar() || n.Scalar().empty()) fail(w, n, "expected a non-empty string");
    return n.Scalar();
}

int require_count(const Where& w, const YAML::Node& n, int lo) {
    try {
        if (n.IsScalar()) {
            const long v = n.as<long>();
            if (v >= lo && v < 1000000) return int(v);
        }
    } catch (const YAML::Exception&) {
    }
    fail(w, n, fmt::format("expected an integer >= {}", lo));
}

// A map key as a name: a YAML complex key (`? [a, b]`) is refused here, not left to escape as
// yaml-cpp's "bad conversion" (found by fuzzing the scene loader).
std::string key_name(const Where& w, const YAML::Node& key) {
    if (!key.IsScalar()) fail(w, key, "expected a key name, got a list or a map");
    return key.Scalar();
}

// Keys swept by a `grid` or `zip` section: key -> list of values.
std::vector<std::pair<std::string, std::vector<YAML::Node>>> read_lists(const Where& w,
                                                                        const YAML::Node& n) {
    require_map(w, n, "a map from scene key to a list of values");
    std::vector<std::pair<std::string, std::vector<YAML::Node>>> out;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string key = key_name(w, it->first);
        const Where wk = w.child(key);
        if (!it->second.IsSequence() || it->second.size() == 0)
            fail(wk, it->second, "expected a non-empty list of values for this scene key");
        std::vector<YAML::Node> values;
        for (std::size_t i = 0; i < it->second.size(); ++i) values.push_back(it->second[i]);
        out.emplace_back(key, std::move(values));
    }
    return out;
}

StudyTradeoff read_tradeoff(const Where& w, const YAML::Node& n) {
    require_map(w, n, "a trade-off: {reference, quantities, analytic, cost, target_error}");
    StudyTradeoff t;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string k = key_name(w, it->first);
        const Where wk = w.child(k);
        const YAML::Node v = it->second;
        if (k == "reference") {
            t.reference = require_string(wk, v);
        } else if (k == "cost") {
            t.cost = require_string(wk, v);
        } else if (k == "quantities") {
            if (!v.IsSequence() || v.size() == 0)
                fail(wk, v, "expected a non-empty list of summary quantities");
            for (std::size_t i = 0; i < v.size(); ++i)
                t.quantities.push_back(require_string(wk.item(i), v[i]));
        } else if (k == "analytic") {
            require_map(wk, v, "a map from summary quantity to its exact value");
            for (auto a = v.begin(); a != v.end(); ++a) {
                const std::string q = key_name(wk, a->first);
                double x = 0;
                try {
                    x = a->second.as<double>();
                } catch (const YAML::Exception&) {
                    fail(wk.child(q), a->second, "expected a number (the exact value)");
                }
                if (!std::isfinite(x) || x == 0)
                    fail(wk.child(q), a->second,
                         "expected a finite non-zero number (deviations are relative to it)");
                t.analytic.emplace_back(q, x);
            }
        } else if (k == "target_error") {
            require_map(wk, v, "a map from summary quantity to an error bar (0.002 or 1%)");
            for (auto a = v.begin(); a != v.end(); ++a) {
                const std::string q = key_name(wk, a->first);
                t.target_error.push_back(read_target_error(q, a->second, wk.child(q)));
            }
        } else {
            fail(wk, it->first,
                 "unknown key; a trade-off has reference, quantities, analytic, cost, "
                 "target_error");
        }
    }
    return t;
}

StudyFit read_fit(const Where& w, const YAML::Node& n) {
    require_map(w, n, "a fit: {name, x, y, group_by, tolerance}");
    StudyFit f;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string k = key_name(w, it->first);
        const Where wk = w.child(k);
        if (k == "name") {
            f.name = safe_name(require_string(wk, it->second));
        } else if (k == "x") {
            f.x = require_string(wk, it->second);
        } else if (k == "y") {
            f.y = require_string(wk, it->second);
        } else if (k == "group_by") {
            if (it->second.IsSequence()) {
                for (std::size_t i = 0; i < it->second.size(); ++i)
                    f.group_by.push_back(require_string(wk.item(i), it->second[i]));
            } else {
                f.group_by.push_back(require_string(wk, it->second));
            }
        } else if (k == "tolerance") {
            try {
                f.tolerance = it->second.as<double>();
            } catch (const YAML::Exception&) {
                fail(wk, it->second, "expected a number > 0 (natural-log deviation)");
            }
            if (!(f.tolerance > 0)) fail(wk, it->second, "expected a number > 0");
        } else {
            fail(wk, it->first, "unknown key; a fit has name, x, y, group_by, tolerance");
        }
    }
    if (f.x.empty() || f.y.empty()) fail(w, n, "a fit needs both `x` and `y`");
    if (f.name.empty()) f.name = safe_name(last_key(f.y) + "_vs_" + last_key(f.x));
    return f;
}

// The run's resolved scene text (what its result records) and the engine's cost estimate.
void resolve_scene(const Study& st, StudyRun& run) {
    const Scene sc = load_scene(st.scene, assignments(run));
    YAML::Emitter em;
    em << sc.resolved;
    run.resolved_scene = em.c_str();
    run.expected_work = sc.cost.work;
}

YAML::Node read_study_yaml(const std::string& path) {
    return load_yaml_file(path, "study file");
}

std::string file_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The sections of a study file that expand to runs.
struct Sections {
    std::vector<YAML::Node> points;
    Lists grid, zip;
    int replicas = 1;
    YAML::Node zip_node;
    Sets base_sets;  // `set`: every run
};

// One top-level key of the study file, into the study or the sections.
void read_section(const Where& top, const YAML::Node& key, const YAML::Node& v,
                  const std::string& path, Study& st, Sections& sec) {
    const std::string k = key_name(top, key);
    const Where w = top.child(k);
    if (k == "scene") {
        st.scene = (fs::path(path).parent_path() / require_string(w, v)).lexically_normal();
        if (!fs::exists(st.scene)) fail(w, v, "no scene file '" + st.scene + "'");
    } else if (k == "output") {
        st.output_dir = require_string(w, v);
    } else if (k == "jobs") {
        st.jobs = require_count(w, v, 1);
    } else if (k == "replicas") {
        sec.replicas = require_count(w, v, 1);
    } else if (k == "points") {
        if (!v.IsSequence() || v.size() == 0) fail(w, v, "expected a non-empty list of points");
        for (std::size_t i = 0; i < v.size(); ++i) sec.points.push_back(v[i]);
    } else if (k == "grid") {
        sec.grid = read_lists(w, v);
    } else if (k == "zip") {
        sec.zip = read_lists(w, v);
        sec.zip_node.reset(v);
    } else if (k == "fits") {
        if (!v.IsSequence()) fail(w, v, "expected a list of fits");
        for (std::size_t i = 0; i < v.size(); ++i) st.fits.push_back(read_fit(w.item(i), v[i]));
    } else if (k == "set") {
        require_map(w, v, "a map from scene key to value (applied to every run)");
        for (auto s = v.begin(); s != v.end(); ++s)
            sec.base_sets.emplace_back(key_name(w, s->first), yaml_text(s->second));
    } else if (k == "tradeoff") {
        st.has_tradeoff = true;
        st.tradeoff = read_tradeoff(w, v);
    } else {
        fail(w, key,
             "unknown key; a study has scene, output, jobs, replicas, set, points, grid, zip, "
             "fits, tradeoff");
    }
}

Sections read_sections(const Where& top, const YAML::Node& root, const std::string& path,
                       Study& st) {
    Sections sec;
    for (auto it = root.begin(); it != root.end(); ++it) {
        const YAML::Node v = it->second;  // a copy: it->second is a temporary proxy
        read_section(top, it->first, v, path, st, sec);
    }
    if (st.scene.empty()) fail(top, root, "missing required key `scene` (the base scene file)");
    if (sec.points.empty()) {
        YAML::Node base;
        base["name"] = fs::path(st.scene).stem().string();
        sec.points.push_back(base);
    }
    return sec;
}

// The common length of the zipped lists (0 without `zip`).
std::size_t zip_length(const Where& top, const Sections& sec) {
    std::size_t zip_len = 0;
    for (const auto& [key, values] : sec.zip) {
        if (zip_len != 0 && values.size() != zip_len) {
            fail(top.child("zip").child(key), sec.zip_node[key],
                 fmt::format("zipped lists must have equal lengths ({} here, {} before)",
                             values.size(), zip_len));
        }
        zip_len = values.size();
    }
    return zip_len;
}

// A point as written: its name, its overrides (after the study's `set`) and its other keys.
struct Point {
    Where where;
    YAML::Node node;
    std::string name;
    Sets sets;
    YAML::Node meta{YAML::NodeType::Map};  // e.g. the paper's values, kept with the result
};

Point read_point(const Where& wp, const YAML::Node& pn, const Sets& base_sets) {
    require_map(wp, pn, "a point: {name: ..., set: {scene.key: value, ...}}");
    Point p{wp, pn, "", base_sets};
    for (auto it = pn.begin(); it != pn.end(); ++it) {
        const std::string k = key_name(wp, it->first);
        if (k == "name") {
            p.name = require_string(wp.child(k), it->second);
        } else if (k == "set") {
            require_map(wp.child(k), it->second, "a map from scene key to value");
            for (auto s = it->second.begin(); s != it->second.end(); ++s) {
                p.sets.emplace_back(key_name(wp.child(k), s->first), yaml_text(s->second));
            }
        } else {
            p.meta[k] = it->second;
        }
    }
    if (p.name.empty()) fail(wp, pn, "a point needs a `name`");
    return p;
}

// The run of point p at grid combination `combo`, zip index z and replica r (1..replicas), its
// scene resolved.
StudyRun make_run(const Study& st, const Sections& sec, const Point& p, std::size_t combo,
                  std::size_t z, int r) {
    StudyRun run;
    run.point = p.name;
    run.metadata = p.meta;
    run.overrides = p.sets;
    std::string name = p.name;
    std::size_t rest = combo;
    for (const auto& [key, values] : sec.grid) {
        const YAML::Node& v = values[rest % values.size()];
        rest /= values.size();
        run.overrides.emplace_back(key, yaml_text(v));
        name += "_" + last_key(key) + label_text(v);
    }
    for (const auto& [key, values] : sec.zip) {
        run.overrides.emplace_back(key, yaml_text(values[z]));
        name += "_" + last_key(key) + label_text(values[z]);
    }
    if (sec.replicas > 1) {
        run.replica = r;
        run.overrides.emplace_back("seed", std::to_string(r));
        name += "_r" + std::to_string(r);
    }
    run.name = safe_name(name);
    try {
        resolve_scene(st, run);
    } catch (const SceneError& e) {
        throw SceneError(
            fmt::format("{}: run '{}': {}", locate(p.where, p.node), run.name, e.what()));
    }
    return run;
}

// Expand: points x grid combinations x zip index x replicas.
void expand_runs(const Where& top, const Sections& sec, std::size_t zip_len, Study& st) {
    std::size_t combos = 1;
    for (const auto& g : sec.grid) combos *= g.second.size();
    std::set<std::string> names;
    auto note_key = [&](const std::string& key) {
        if (std::find(st.swept_keys.begin(), st.swept_keys.end(), key) == st.swept_keys.end())
            st.swept_keys.push_back(key);
    };
    for (std::size_t i = 0; i < sec.points.size(); ++i) {
        const Point p = read_point(top.child("points").item(i), sec.points[i], sec.base_sets);
        for (std::size_t c = 0; c < combos; ++c) {
            for (std::size_t z = 0; z < std::max<std::size_t>(zip_len, 1); ++z) {
                for (int r = 1; r <= sec.replicas; ++r) {
                    StudyRun run = make_run(st, sec, p, c, z, r);
                    if (!names.insert(run.name).second)
                        fail(p.where, p.node,
                             "two runs are both named '" + run.name + "'; rename a point");
                    for (std::size_t o = sec.base_sets.size(); o < run.overrides.size(); ++o)
                        note_key(run.overrides[o].first);
                    st.runs.push_back(std::move(run));
                }
            }
        }
    }
}

// A trade-off compares with its reference point unless every quantity has an analytic value.
void require_reference_point(const Where& top, const YAML::Node& root, const Study& st) {
    if (!st.has_tradeoff || !st.tradeoff.analytic.empty() ||
        std::any_of(st.runs.begin(), st.runs.end(),
                    [&](const StudyRun& r) { return r.point == st.tradeoff.reference; }))
        return;
    const YAML::Node tn = root["tradeoff"];
    const YAML::Node rn = tn["reference"];
    fail(top.child("tradeoff").child("reference"), rn ? rn : tn,
         "no point is named '" + st.tradeoff.reference +
             "'; the reference must be a point of the study (or give `analytic` values)");
}

}  // namespace

Study load_study(const std::string& path) {
    const YAML::Node root = read_study_yaml(path);
    const Where top{path, ""};
    require_map(top, root, "a study: a map with keys scene, points, grid, zip, replicas, fits");
    Study st;
    st.file = path;
    st.text = file_text(path);
    st.output_dir = (fs::path("results") / fs::path(path).stem()).string();
    const Sections sec = read_sections(top, root, path, st);
    expand_runs(top, sec, zip_length(top, sec), st);
    require_reference_point(top, root, st);
    return st;
}

}  // namespace gran
