#include "libgran/study/study_merge.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "libgran/core/h5.hpp"
#include "libgran/run/summary_numbers.hpp"
#include "libgran/study/study_fit.hpp"
#include "libgran/study/study_pool.hpp"
#include "libgran/study/study_tradeoff.hpp"

namespace gran {

namespace fs = std::filesystem;

RunFiles run_files(const Study& st, const std::string& outdir) {
    RunFiles f;
    for (const StudyRun& run : st.runs) {
        f.result.push_back((fs::path(outdir) / (run.name + ".h5")).string());
        f.summary.push_back((fs::path(outdir) / (run.name + ".summary.yaml")).string());
        f.log.push_back((fs::path(outdir) / "logs" / (run.name + ".log")).string());
    }
    return f;
}

namespace {

// Every number in a run summary (value and error, NaN: none) by its dotted path
// (libgran/run/summary_numbers.hpp), and the effective samples of the error bars that have them.
void flatten(const YAML::Node& n, const std::string& prefix,
             std::map<std::string, std::pair<double, double>>& out,
             std::map<std::string, double>& n_eff) {
    for (const auto& [name, x] : summary_numbers(n, prefix)) {
        out[name] = {x.value, x.error};
        if (std::isfinite(x.n_eff)) n_eff[name] = x.n_eff;
    }
}

struct Table {
    std::vector<std::string> quantities;  // union over runs, sorted
    std::vector<SummaryRow> rows;
    std::vector<std::map<std::string, double>> n_eff;  // per run (the trade-off's forecasts)
};

Table summary_table(const Study& st, const std::vector<std::string>& summaries,
                    const std::vector<bool>& have) {
    Table t;
    std::set<std::string> q;
    t.rows.resize(st.runs.size());
    t.n_eff.resize(st.runs.size());
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        try {
            const YAML::Node s = YAML::LoadFile(summaries[i]);
            for (const char* section : {"observables", "drivers", "performance"})
                flatten(s[section], section, t.rows[i], t.n_eff[i]);
            // Runs with a target: the error reached, the cost, the forecast against it.
            if (s["target"]) flatten(s["target"], "target", t.rows[i], t.n_eff[i]);
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

// The study file and what it swept.
void write_study_group(h5::Group& root, const Study& st) {
    h5::Group sg = root.group("study");
    sg.write_string("study", st.text);
    sg.attr("file", st.file);
    sg.attr("scene", st.scene);
    sg.attr("swept_keys", st.swept_keys);
}

// Every complete run's result file, copied under points/<run> with its point, replica, overrides
// and metadata.
void copy_runs(h5::Group& root, const Study& st, const RunFiles& files,
               const std::vector<bool>& have) {
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        const StudyRun& run = st.runs[i];
        h5::File rf = h5::File::open_read(files.result[i]);
        h5::Group pg = root.group("points/" + run.name);
        pg.copy_children_from(rf.root());
        pg.attr("point", run.point);
        pg.attr("replica", run.replica);
        pg.attr("overrides", assignments(run));
        if (run.metadata.size() > 0) {
            YAML::Emitter em;
            em << run.metadata;
            pg.attr("metadata", std::string(em.c_str()));
        }
    }
}

// The summary table as columns over the complete runs: names, points, swept keys, quantities.
void write_summary_group(h5::Group& root, const Study& st, const Table& table,
                         const std::vector<bool>& have) {
    const std::size_t n = st.runs.size();
    std::vector<std::string> names, points;
    for (std::size_t i = 0; i < n; ++i) {
        if (!have[i]) continue;
        names.push_back(st.runs[i].name);
        points.push_back(st.runs[i].point);
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
}

// Where each complete run ran (its /provenance `host` and `mpi_rank`; a result from before they
// were recorded: "" and -1), so a merged study shows how the work was spread.
void write_placement(h5::Group& root, const Study& st, const RunFiles& files,
                     const std::vector<bool>& have) {
    std::vector<std::string> hosts;
    std::vector<std::int64_t> ranks;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        std::string host;
        std::int64_t rank = -1;
        try {
            const h5::File rf = h5::File::open_read(files.result[i]);
            const h5::Group prov = rf.root().group("provenance");
            host = prov.read_attr_string("host");
            rank = static_cast<std::int64_t>(prov.read_attr_double("mpi_rank"));
        } catch (const std::exception&) {
            // recorded before placement was
        }
        hosts.push_back(host);
        ranks.push_back(rank);
    }
    h5::Group pl = root.group("summary/placement");
    pl.write_strings("host", hosts);
    pl.write("mpi_rank", ranks);
}

void write_performance(h5::Group& root, const StudyReport& rep,
                       std::chrono::steady_clock::time_point started) {
    h5::Group perf = root.group("performance");
    perf.write_scalar("ran", rep.ran);
    perf.write_scalar("reused", rep.reused);
    perf.write_scalar("failed", rep.failed);
    perf.write_scalar("max_concurrent_runs", rep.max_concurrent);
    perf.write_scalar(
        "wall_time",
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    perf.attr_on("wall_time", "unit", "s");
}

// What the runs add up to, besides the runs themselves.
struct Analysis {
    Table table;
    std::vector<FitResult> fits;
    TradeoffResult tradeoff;
};

// Written as <file>.part and renamed, so a merged file is never half written.
void write_merged_file(const std::string& file, const Study& st, const RunFiles& files,
                       const std::vector<bool>& have, const Analysis& a, const StudyReport& rep,
                       std::chrono::steady_clock::time_point started) {
    const std::string part = file + ".part";
    {
        h5::File f = h5::File::create(part);
        h5::Group root = f.root();
        write_study_group(root, st);
        copy_runs(root, st, files, have);
        write_summary_group(root, st, a.table, have);
        write_placement(root, st, files, have);
        write_fits(root, a.fits);
        if (st.has_tradeoff) write_tradeoff(root, a.tradeoff);
        write_performance(root, rep, started);
    }
    fs::rename(part, file);
}

void write_tradeoff_report(const Study& st, const std::string& outdir, const std::string& stem,
                           const TradeoffResult& tradeoff, StudyReport& rep) {
    write_tradeoff_csv((fs::path(outdir) / (stem + ".tradeoff.csv")).string(), tradeoff);
    rep.tradeoff = (fs::path(outdir) / (stem + ".tradeoff.md")).string();
    std::ofstream md(rep.tradeoff);
    md << "# Speed versus accuracy: " << st.file << "\n\n"
       << "Deviation of each quantity from its reference, relative, with one standard error; "
          "`*`: on the Pareto front of (CPU time, |deviation| + error) for that quantity; "
          "`worst`: the largest |deviation| + error over the quantities, and its front.\n\n"
       << tradeoff_table(tradeoff);
    if (const std::string f = tradeoff_forecast_table(tradeoff); !f.empty()) md << "\n" << f;
}

void write_fit_report(const std::string& outdir, const std::string& stem,
                      const std::vector<FitResult>& fits) {
    write_fits_csv((fs::path(outdir) / (stem + ".fits.csv")).string(), fits);
    for (const auto& r : fits) {
        if (r.problem.empty())
            spdlog::info("fit {}", describe(r));
        else
            spdlog::error("fit {}", describe(r));
    }
}

}  // namespace

void merge_study(const Study& st, const std::string& outdir, const RunFiles& files,
                 const std::vector<bool>& have, std::chrono::steady_clock::time_point started,
                 StudyReport& rep) {
    Analysis a;
    a.table = summary_table(st, files.summary, have);
    const Table& table = a.table;
    if (st.has_tradeoff)
        add_pdf_distances(st, files.result, a.table.rows, have, a.table.quantities);
    // Named after the study file: several studies may share one result folder (and its runs).
    const std::string stem = fs::path(st.file).stem().string();
    rep.table = (fs::path(outdir) / (stem + ".study.csv")).string();
    write_csv(rep.table, st, table, have);
    const std::string pooled = (fs::path(outdir) / (stem + ".pooled.csv")).string();
    if (write_pooled_csv(pooled, st, table.quantities, table.rows, have)) rep.pooled = pooled;
    a.fits = fit_all(st, table.quantities, table.rows, have, [&](const StudyFit& f, std::size_t i) {
        return fit_x(f, st.runs[i], table.rows[i]);
    });
    if (st.has_tradeoff)
        a.tradeoff = analyse_tradeoff(st, table.quantities, table.rows, have, table.n_eff);
    rep.merged = (fs::path(outdir) / (stem + ".study.h5")).string();
    write_merged_file(rep.merged, st, files, have, a, rep, started);
    if (st.has_tradeoff) write_tradeoff_report(st, outdir, stem, a.tradeoff, rep);
    if (!a.fits.empty()) write_fit_report(outdir, stem, a.fits);
}

namespace {

std::string merge_lock_path(const Study& st, const std::string& outdir) {
    fs::create_directories(outdir);
    const std::string stem = fs::path(st.file).stem().string();
    return (fs::path(outdir) / ("." + stem + ".merge.lock")).string();
}

}  // namespace

StudyMergeLock::StudyMergeLock(const Study& st, const std::string& outdir)
    : lock_(merge_lock_path(st, outdir), [&] {
          spdlog::info("study: another merge of {} is writing in {}; waiting for it", st.file,
                       outdir);
      }) {
    if (!lock_.held()) {
        spdlog::warn("study: cannot lock the merge of {} in {} ({}); merging without the lock",
                     st.file, outdir, lock_.error());
    }
}

}  // namespace gran
