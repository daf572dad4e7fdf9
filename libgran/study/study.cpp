#include "libgran/study/study.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "libgran/core/h5.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/study/study_fit.hpp"
#include "libgran/study/study_tradeoff.hpp"

extern char** environ;

namespace gran {

namespace fs = std::filesystem;

namespace {

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

// Keys swept by a `grid` or `zip` section: key -> list of values.
std::vector<std::pair<std::string, std::vector<YAML::Node>>> read_lists(const Where& w,
                                                                        const YAML::Node& n) {
    require_map(w, n, "a map from scene key to a list of values");
    std::vector<std::pair<std::string, std::vector<YAML::Node>>> out;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string key = it->first.as<std::string>();
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
    require_map(w, n, "a trade-off: {reference, quantities, analytic, cost}");
    StudyTradeoff t;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string k = it->first.as<std::string>();
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
                const std::string q = a->first.as<std::string>();
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
        } else {
            fail(wk, it->first,
                 "unknown key; a trade-off has reference, quantities, analytic, cost");
        }
    }
    return t;
}

StudyFit read_fit(const Where& w, const YAML::Node& n) {
    require_map(w, n, "a fit: {name, x, y, group_by, tolerance}");
    StudyFit f;
    for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string k = it->first.as<std::string>();
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

std::vector<std::string> assignments(const StudyRun& run) {
    std::vector<std::string> a;
    for (const auto& [k, v] : run.overrides) a.push_back(k + "=" + v);
    return a;
}

std::string resolved_scene_text(const Study& st, const StudyRun& run) {
    const Scene sc = load_scene(st.scene, assignments(run));
    YAML::Emitter em;
    em << sc.resolved;
    return em.c_str();
}

}  // namespace

Study load_study(const std::string& path) {
    YAML::Node root;
    try {
        root = YAML::LoadFile(path);
    } catch (const YAML::BadFile&) {
        throw SceneError(fmt::format("{}: cannot open the study file", path));
    } catch (const YAML::ParserException& e) {
        throw SceneError(fmt::format("{}:{}:{}: not valid YAML: {}", path, e.mark.line + 1,
                                     e.mark.column + 1, e.msg));
    }
    const Where top{path, ""};
    require_map(top, root, "a study: a map with keys scene, points, grid, zip, replicas, fits");
    Study st;
    st.file = path;
    {
        std::ifstream in(path);
        std::stringstream ss;
        ss << in.rdbuf();
        st.text = ss.str();
    }
    st.output_dir = (fs::path("results") / fs::path(path).stem()).string();
    std::vector<YAML::Node> points;
    std::vector<std::pair<std::string, std::vector<YAML::Node>>> grid, zip;
    int replicas = 1;
    YAML::Node zip_node;
    std::vector<std::pair<std::string, std::string>> base_sets;  // `set`: every run
    for (auto it = root.begin(); it != root.end(); ++it) {
        const std::string k = it->first.as<std::string>();
        const Where w = top.child(k);
        const YAML::Node v = it->second;  // a copy: it->second is a temporary proxy
        if (k == "scene") {
            st.scene = (fs::path(path).parent_path() / require_string(w, v)).lexically_normal();
            if (!fs::exists(st.scene)) fail(w, v, "no scene file '" + st.scene + "'");
        } else if (k == "output") {
            st.output_dir = require_string(w, v);
        } else if (k == "jobs") {
            st.jobs = require_count(w, v, 1);
        } else if (k == "replicas") {
            replicas = require_count(w, v, 1);
        } else if (k == "points") {
            if (!v.IsSequence() || v.size() == 0) fail(w, v, "expected a non-empty list of points");
            for (std::size_t i = 0; i < v.size(); ++i) points.push_back(v[i]);
        } else if (k == "grid") {
            grid = read_lists(w, v);
        } else if (k == "zip") {
            zip = read_lists(w, v);
            zip_node = v;
        } else if (k == "fits") {
            if (!v.IsSequence()) fail(w, v, "expected a list of fits");
            for (std::size_t i = 0; i < v.size(); ++i) st.fits.push_back(read_fit(w.item(i), v[i]));
        } else if (k == "set") {
            require_map(w, v, "a map from scene key to value (applied to every run)");
            for (auto s = v.begin(); s != v.end(); ++s)
                base_sets.emplace_back(s->first.as<std::string>(), yaml_text(s->second));
        } else if (k == "tradeoff") {
            st.has_tradeoff = true;
            st.tradeoff = read_tradeoff(w, v);
        } else {
            fail(w, it->first,
                 "unknown key; a study has scene, output, jobs, replicas, set, points, grid, zip, "
                 "fits, tradeoff");
        }
    }
    if (st.scene.empty()) fail(top, root, "missing required key `scene` (the base scene file)");
    std::size_t zip_len = 0;
    for (const auto& [key, values] : zip) {
        if (zip_len != 0 && values.size() != zip_len) {
            fail(top.child("zip").child(key), zip_node[key],
                 fmt::format("zipped lists must have equal lengths ({} here, {} before)",
                             values.size(), zip_len));
        }
        zip_len = values.size();
    }
    if (points.empty()) {
        YAML::Node base;
        base["name"] = fs::path(st.scene).stem().string();
        points.push_back(base);
    }

    // Expand: points x grid combinations x zip index x replicas.
    std::size_t combos = 1;
    for (const auto& g : grid) combos *= g.second.size();
    std::set<std::string> names;
    auto note_key = [&](const std::string& key) {
        if (std::find(st.swept_keys.begin(), st.swept_keys.end(), key) == st.swept_keys.end())
            st.swept_keys.push_back(key);
    };
    for (std::size_t p = 0; p < points.size(); ++p) {
        const Where wp = top.child("points").item(p);
        const YAML::Node& pn = points[p];
        require_map(wp, pn, "a point: {name: ..., set: {scene.key: value, ...}}");
        std::string pname;
        std::vector<std::pair<std::string, std::string>> sets = base_sets;
        YAML::Node meta(YAML::NodeType::Map);
        for (auto it = pn.begin(); it != pn.end(); ++it) {
            const std::string k = it->first.as<std::string>();
            if (k == "name") {
                pname = require_string(wp.child(k), it->second);
            } else if (k == "set") {
                require_map(wp.child(k), it->second, "a map from scene key to value");
                for (auto s = it->second.begin(); s != it->second.end(); ++s) {
                    sets.emplace_back(s->first.as<std::string>(), yaml_text(s->second));
                }
            } else {
                meta[k] = it->second;  // e.g. the paper's values, kept with the result
            }
        }
        if (pname.empty()) fail(wp, pn, "a point needs a `name`");
        for (std::size_t c = 0; c < combos; ++c) {
            for (std::size_t z = 0; z < std::max<std::size_t>(zip_len, 1); ++z) {
                for (int r = 1; r <= replicas; ++r) {
                    StudyRun run;
                    run.point = pname;
                    run.metadata = meta;
                    run.overrides = sets;
                    std::string name = pname;
                    std::size_t rest = c;
                    for (const auto& [key, values] : grid) {
                        const YAML::Node& v = values[rest % values.size()];
                        rest /= values.size();
                        run.overrides.emplace_back(key, yaml_text(v));
                        name += "_" + last_key(key) + label_text(v);
                    }
                    for (const auto& [key, values] : zip) {
                        run.overrides.emplace_back(key, yaml_text(values[z]));
                        name += "_" + last_key(key) + label_text(values[z]);
                    }
                    if (replicas > 1) {
                        run.replica = r;
                        run.overrides.emplace_back("seed", std::to_string(r));
                        name += "_r" + std::to_string(r);
                    }
                    run.name = safe_name(name);
                    try {
                        run.resolved_scene = resolved_scene_text(st, run);
                    } catch (const SceneError& e) {
                        throw SceneError(
                            fmt::format("{}: run '{}': {}", locate(wp, pn), run.name, e.what()));
                    }
                    if (!names.insert(run.name).second)
                        fail(wp, pn, "two runs are both named '" + run.name + "'; rename a point");
                    for (std::size_t o = base_sets.size(); o < run.overrides.size(); ++o)
                        note_key(run.overrides[o].first);
                    st.runs.push_back(std::move(run));
                }
            }
        }
    }
    if (st.has_tradeoff && st.tradeoff.analytic.empty() &&
        std::none_of(st.runs.begin(), st.runs.end(),
                     [&](const StudyRun& r) { return r.point == st.tradeoff.reference; })) {
        const YAML::Node tn = static_cast<const YAML::Node&>(root)["tradeoff"];
        const YAML::Node rn = tn["reference"];
        fail(top.child("tradeoff").child("reference"), rn ? rn : tn,
             "no point is named '" + st.tradeoff.reference +
                 "'; the reference must be a point of the study (or give `analytic` values)");
    }
    return st;
}

namespace {

// A result that completed and came from exactly this resolved scene needs no new run.
bool reusable(const std::string& file, const std::string& resolved) {
    if (!fs::exists(file)) return false;
    try {
        h5::File f = h5::File::open_read(file);
        const h5::Group r = f.root();
        return r.read_int64s("performance/completed").at(0) == 1 &&
               r.read_string("parameters/scene") == resolved;
    } catch (const std::exception&) {
        return false;
    }
}

pid_t spawn_run(const std::string& binary, const std::string& scene, const std::string& out,
                const StudyRun& run, const std::string& log) {
    std::vector<std::string> args{binary, "--quiet", "run", scene, "-o", out};
    for (const auto& a : assignments(run)) {
        args.push_back("--set");
        args.push_back(a);
    }
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, binary.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        throw std::runtime_error(
            fmt::format("study: cannot start '{}': {}", binary, std::strerror(rc)));
    }
    return pid;
}

// Every number in a run summary: estimates {value, error, ...}, values with a unit
// {value, unit} (error NaN) and plain counters, keyed by their dotted path
// ("observables.profiles.middle/ratios/light_over_heavy/gamma", "performance.cpu_time").
void flatten(const YAML::Node& n, const std::string& prefix,
             std::map<std::string, std::pair<double, double>>& out) {
    if (n.IsMap()) {
        if (n["value"] && n["value"].IsScalar()) {
            try {
                out[prefix] = {n["value"].as<double>(),
                               n["error"] ? n["error"].as<double>() : std::nan("")};
            } catch (const YAML::Exception&) {
            }
            return;
        }
        for (auto it = n.begin(); it != n.end(); ++it) {
            const std::string k = it->first.as<std::string>();
            flatten(it->second, prefix.empty() ? k : prefix + "." + k, out);
        }
    } else if (n.IsScalar()) {
        try {
            out[prefix] = {n.as<double>(), std::nan("")};
        } catch (const YAML::Exception&) {
        }
    }
}

struct Table {
    std::vector<std::string> quantities;  // union over runs, sorted
    std::vector<std::map<std::string, std::pair<double, double>>> rows;
};

Table summary_table(const Study& st, const std::vector<std::string>& summaries,
                    const std::vector<bool>& have) {
    Table t;
    std::set<std::string> q;
    t.rows.resize(st.runs.size());
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        try {
            const YAML::Node s = YAML::LoadFile(summaries[i]);
            flatten(s["observables"], "observables", t.rows[i]);
            flatten(s["drivers"], "drivers", t.rows[i]);
            flatten(s["performance"], "performance", t.rows[i]);
        } catch (const YAML::Exception& e) {
            spdlog::warn("study: cannot read {}: {}", summaries[i], e.what());
        }
        for (const auto& [k, v] : t.rows[i]) q.insert(k);
    }
    t.quantities.assign(q.begin(), q.end());
    return t;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string o = "\"";
    for (char c : s) o += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return o + "\"";
}

std::string override_value(const StudyRun& run, const std::string& key) {
    for (const auto& [k, v] : run.overrides) {
        if (k == key) return v;
    }
    return "";
}

void write_csv(const std::string& path, const Study& st, const Table& t,
               const std::vector<bool>& have) {
    std::ofstream o(path);
    // `point` names the study point a run belongs to, so readers group runs without parsing names.
    o << "run,point";
    for (const auto& k : st.swept_keys) o << "," << csv_field(k);
    for (const auto& q : t.quantities) o << "," << csv_field(q) << "," << csv_field(q + ".error");
    o << "\n";
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        o << csv_field(st.runs[i].name) << "," << csv_field(st.runs[i].point);
        for (const auto& k : st.swept_keys) o << "," << csv_field(override_value(st.runs[i], k));
        for (const auto& q : t.quantities) {
            auto it = t.rows[i].find(q);
            if (it == t.rows[i].end()) {
                o << ",,";
            } else {
                o << "," << fmt::format("{:.10g}", it->second.first) << ",";
                if (!std::isnan(it->second.second)) o << fmt::format("{:.10g}", it->second.second);
            }
        }
        o << "\n";
    }
}

// The x value of a fit for one run: a swept scene key or a summary quantity.
double fit_x(const StudyFit& f, const StudyRun& run,
             const std::map<std::string, std::pair<double, double>>& row) {
    const std::string v = override_value(run, f.x);
    if (!v.empty()) {
        try {
            return std::stod(v);
        } catch (const std::exception&) {
            return std::nan("");
        }
    }
    auto it = row.find(f.x);
    return it == row.end() ? std::nan("") : it->second.first;
}

}  // namespace

StudyReport run_study(const Study& st, const StudyOptions& opt) {
    StudyReport rep;
    const std::string outdir = opt.output_dir.empty() ? st.output_dir : opt.output_dir;
    const int jobs = opt.jobs > 0  ? opt.jobs
                     : st.jobs > 0 ? st.jobs
                                   : int(std::max(1u, std::thread::hardware_concurrency()));
    fs::create_directories(fs::path(outdir) / "logs");
    const std::size_t n = st.runs.size();
    std::vector<std::string> out(n), summary(n), log(n);
    std::vector<bool> have(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = (fs::path(outdir) / (st.runs[i].name + ".h5")).string();
        summary[i] = (fs::path(outdir) / (st.runs[i].name + ".summary.yaml")).string();
        log[i] = (fs::path(outdir) / "logs" / (st.runs[i].name + ".log")).string();
    }
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < n; ++i) {
        if (reusable(out[i], st.runs[i].resolved_scene) && fs::exists(summary[i])) {
            have[i] = true;
            ++rep.reused;
        } else {
            todo.push_back(i);
        }
    }
    spdlog::info("study {}: {} runs, {} already complete, {} to run on {} cores; results in {}",
                 st.file, n, rep.reused, todo.size(), jobs, outdir);

    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
    std::size_t next = 0, finished = 0;
    bool stop = false;
    while (next < todo.size() || !running.empty()) {
        if (opt.interrupt && opt.interrupt->load() && !stop) {
            stop = true;
            rep.interrupted = true;
            spdlog::warn(
                "study interrupted: stopping {} running runs (they keep what they measured)",
                running.size());
            for (const auto& [pid, r] : running) kill(pid, SIGTERM);
        }
        while (!stop && next < todo.size() && int(running.size()) < jobs) {
            const std::size_t i = todo[next++];
            pid_t pid = -1;
            try {
                pid = spawn_run(opt.gran_binary, st.scene, out[i], st.runs[i], log[i]);
            } catch (const std::exception& e) {
                // E.g. the binary is being rebuilt: this run fails, the others go on.
                ++rep.failed;
                spdlog::error("{}: {}", st.runs[i].name, e.what());
                continue;
            }
            running[pid] = {i, Clock::now()};
            rep.max_concurrent = std::max(rep.max_concurrent, int(running.size()));
        }
        if (running.empty()) break;
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(
                fmt::format("study: waitpid failed: {}", std::strerror(errno)));
        }
        auto it = running.find(pid);
        if (it == running.end()) continue;
        const auto [i, started] = it->second;
        running.erase(it);
        ++finished;
        const double secs = std::chrono::duration<double>(Clock::now() - started).count();
        const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        if (code == 0) {
            have[i] = true;
            ++rep.ran;
            if (opt.progress) {
                const double el = std::chrono::duration<double>(Clock::now() - t0).count();
                const double eta = el / double(finished) * double(todo.size() - finished);
                spdlog::info("[{}/{}] {} done in {:.1f} s (study ETA {:.0f} s)", finished,
                             todo.size(), st.runs[i].name, secs, eta);
            }
        } else if (code == 3 && stop) {
            spdlog::warn("{}: interrupted; partial result {} (not reused next time)",
                         st.runs[i].name, out[i]);
        } else {
            ++rep.failed;
            spdlog::error("{} failed (exit {}); see {}", st.runs[i].name, code, log[i]);
        }
    }

    // Merge every complete run into one file, plus the summary table and fits.
    Table table = summary_table(st, summary, have);
    if (st.has_tradeoff) add_pdf_distances(st, out, table.rows, have, table.quantities);
    // Named after the study file: several studies may share one result folder (and its runs).
    const std::string stem = fs::path(st.file).stem().string();
    rep.table = (fs::path(outdir) / (stem + ".study.csv")).string();
    write_csv(rep.table, st, table, have);
    const std::vector<FitResult> fits = fit_all(
        st, table.quantities, table.rows, have,
        [&](const StudyFit& f, std::size_t i) { return fit_x(f, st.runs[i], table.rows[i]); });
    TradeoffResult tradeoff;
    if (st.has_tradeoff) tradeoff = analyse_tradeoff(st, table.quantities, table.rows, have);
    rep.merged = (fs::path(outdir) / (stem + ".study.h5")).string();
    const std::string part = rep.merged + ".part";
    {
        h5::File f = h5::File::create(part);
        h5::Group root = f.root();
        h5::Group sg = root.group("study");
        sg.write_string("study", st.text);
        sg.attr("file", st.file);
        sg.attr("scene", st.scene);
        sg.attr("swept_keys", st.swept_keys);
        std::vector<std::string> names, points;
        for (std::size_t i = 0; i < n; ++i) {
            if (!have[i]) continue;
            names.push_back(st.runs[i].name);
            points.push_back(st.runs[i].point);
            h5::File rf = h5::File::open_read(out[i]);
            h5::Group pg = root.group("points/" + st.runs[i].name);
            pg.copy_children_from(rf.root());
            pg.attr("point", st.runs[i].point);
            pg.attr("replica", st.runs[i].replica);
            pg.attr("overrides", assignments(st.runs[i]));
            if (st.runs[i].metadata.size() > 0) {
                YAML::Emitter em;
                em << st.runs[i].metadata;
                pg.attr("metadata", std::string(em.c_str()));
            }
        }
        h5::Group sum = root.group("summary");
        sum.write_strings("runs", names);
        sum.write_strings("points", points);
        for (const auto& key : st.swept_keys) {
            std::vector<std::string> vals;
            for (std::size_t i = 0; i < n; ++i) {
                if (have[i]) vals.push_back(override_value(st.runs[i], key));
            }
            sum.write_strings("parameters/" + key, vals);
        }
        for (const auto& q : table.quantities) {
            std::vector<double> v, e;
            for (std::size_t i = 0; i < n; ++i) {
                if (!have[i]) continue;
                auto it = table.rows[i].find(q);
                v.push_back(it == table.rows[i].end() ? std::nan("") : it->second.first);
                e.push_back(it == table.rows[i].end() ? std::nan("") : it->second.second);
            }
            h5::Group qg = sum.group("quantities/" + q);
            qg.write("value", v);
            qg.write("error", e);
        }
        write_fits(root, fits);
        if (st.has_tradeoff) write_tradeoff(root, tradeoff);
        h5::Group perf = root.group("performance");
        perf.write_scalar("ran", rep.ran);
        perf.write_scalar("reused", rep.reused);
        perf.write_scalar("failed", rep.failed);
        perf.write_scalar("max_concurrent_runs", rep.max_concurrent);
        perf.write_scalar("wall_time", std::chrono::duration<double>(Clock::now() - t0).count());
        perf.attr_on("wall_time", "unit", "s");
    }
    fs::rename(part, rep.merged);
    if (st.has_tradeoff) {
        write_tradeoff_csv((fs::path(outdir) / (stem + ".tradeoff.csv")).string(), tradeoff);
        rep.tradeoff = (fs::path(outdir) / (stem + ".tradeoff.md")).string();
        std::ofstream md(rep.tradeoff);
        md << "# Speed versus accuracy: " << st.file << "\n\n"
           << "Deviation of each quantity from its reference, relative, with one standard error; "
              "`*`: on the Pareto front of (CPU time, |deviation| + error) for that quantity; "
              "`worst`: the largest |deviation| + error over the quantities, and its front.\n\n"
           << tradeoff_table(tradeoff);
    }
    if (!fits.empty()) {
        const std::string fits_csv = (fs::path(outdir) / (stem + ".fits.csv")).string();
        write_fits_csv(fits_csv, fits);
        for (const auto& r : fits) {
            if (r.problem.empty())
                spdlog::info("fit {}", describe(r));
            else
                spdlog::error("fit {}", describe(r));
        }
    }
    return rep;
}

}  // namespace gran
