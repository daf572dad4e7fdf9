#include "libgran/study/study_tradeoff.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <set>

#include "libgran/study/tradeoff_forecast.hpp"

namespace gran {

std::vector<bool> pareto_front(std::span<const double> cost, std::span<const double> error) {
    const std::size_t n = cost.size();
    std::vector<bool> front(n, false);
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < n; ++i) {
        if (std::isfinite(cost[i]) && std::isfinite(error[i])) idx.push_back(i);
    }
    // Cheapest first (ties: smallest error first); a point is on the front when its error is below
    // that of every cheaper point. Equal points are all on the front (none dominates the other).
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
        return cost[a] != cost[b] ? cost[a] < cost[b] : error[a] < error[b];
    });
    double best = std::numeric_limits<double>::infinity();
    double best_cost = -1;
    for (std::size_t k : idx) {
        if (error[k] < best || (error[k] == best && cost[k] == best_cost)) {
            front[k] = true;
            best = error[k];
            best_cost = cost[k];
        }
    }
    return front;
}

namespace {

std::string last_component(const std::string& q) {
    const auto cut = q.find_last_of("./");
    return cut == std::string::npos ? q : q.substr(cut + 1);
}

std::string metadata_text(const StudyRun& run, const char* key) {
    const YAML::Node n = run.metadata[key];
    if (!n || !n.IsScalar()) return "";
    return n.Scalar();
}

}  // namespace

std::vector<std::string> default_tradeoff_quantities(const std::vector<std::string>& available) {
    // Headline quantities of the observables (docs/scene-reference.md): the temperature ratio,
    // the (mixture) temperature, the Sonine coefficient, pressures, and the vibrated bed's scaled
    // temperatures. Per-component and per-species variants are left to an explicit list.
    static const std::set<std::string> headline{"gamma",
                                                "T_mixture",
                                                "a2_mixture",
                                                "pressure",
                                                "T_volume_scaled",
                                                "T_plain_scaled",
                                                "T_z_volume_scaled",
                                                "T_z_plain_scaled",
                                                "T_y_volume_scaled",
                                                "T_y_plain_scaled",
                                                "h_cm",
                                                "pdf_distance"};
    std::vector<std::string> out;
    for (const auto& q : available) {
        if (q.rfind("observables.", 0) != 0) continue;
        const std::string last = last_component(q);
        // A headline quantity whose reference is 0 (the open top of a vibrated bed) is dropped
        // with a note by analyse_tradeoff: it has no relative deviation.
        if (headline.count(last)) out.push_back(q);
    }
    return out;
}

namespace {

constexpr const char* kPdfDistance = "observables.velocity_pdf.pdf_distance";

bool is_distance(const std::string& q) {
    return last_component(q) == "pdf_distance";
}

struct Pdf {
    std::vector<double> density, error, edges;
};

// Every rescaled component PDF of a run, keyed "<species>/<component>"; empty without the
// observable.
std::map<std::string, Pdf> read_pdfs(const std::string& file, const std::string& scene_text) {
    std::map<std::string, Pdf> out;
    try {
        const YAML::Node scene = YAML::Load(scene_text);
        const int dim = scene["dimension"].as<int>();
        h5::File f = h5::File::open_read(file);
        const h5::Group root = f.root();
        if (!root.exists("observables/velocity_pdf")) return out;
        for (const auto& sp : scene["species"]) {
            for (int a = 0; a < dim; ++a) {
                const std::string key =
                    sp["name"].as<std::string>() + "/" + std::string(1, "xyz"[a]);
                const std::string base = "observables/velocity_pdf/" + key + "/scaled_";
                if (!root.exists(base + "density")) continue;
                out[key] = {root.read_doubles(base + "density"), root.read_doubles(base + "error"),
                            root.read_doubles(base + "edges")};
            }
        }
    } catch (const std::exception&) {
        out.clear();
    }
    return out;
}

}  // namespace

void add_pdf_distances(const Study& st, const std::vector<std::string>& outputs,
                       std::vector<Row>& rows, const std::vector<bool>& have,
                       std::vector<std::string>& quantities) {
    std::size_t ref = st.runs.size();
    for (std::size_t i = 0; i < st.runs.size() && ref == st.runs.size(); ++i) {
        if (have[i] && st.runs[i].point == st.tradeoff.reference) ref = i;
    }
    if (ref == st.runs.size()) return;
    const auto ref_pdfs = read_pdfs(outputs[ref], st.runs[ref].resolved_scene);
    if (ref_pdfs.empty()) return;
    bool any = false;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        const auto pdfs = i == ref ? ref_pdfs : read_pdfs(outputs[i], st.runs[i].resolved_scene);
        double d_sum = 0, e_sum = 0;
        int n = 0;
        for (const auto& [key, p] : pdfs) {
            auto it = ref_pdfs.find(key);
            if (it == ref_pdfs.end()) continue;
            const Pdf& r = it->second;
            // Only histograms on the same bins compare bin by bin.
            if (r.edges != p.edges || p.density.size() + 1 != p.edges.size()) continue;
            double d = 0, e = 0;
            for (std::size_t b = 0; b < p.density.size(); ++b) {
                const double dc = p.edges[b + 1] - p.edges[b];
                d += 0.5 * std::abs(p.density[b] - r.density[b]) * dc;
                const double var =
                    p.error[b] * p.error[b] + (i == ref ? 0.0 : r.error[b] * r.error[b]);
                e += 0.5 * dc * std::sqrt(2 / M_PI) * std::sqrt(var);
            }
            d_sum += d;
            e_sum += e;
            ++n;
        }
        if (n == 0) continue;
        rows[i][kPdfDistance] = {d_sum / n, e_sum / n};
        any = true;
    }
    if (any && std::find(quantities.begin(), quantities.end(), kPdfDistance) == quantities.end())
        quantities.push_back(kPdfDistance);
}

namespace {

// The runs to compare (complete ones) and those of the reference point among them.
struct RunSets {
    std::vector<std::size_t> runs, refs;
};

RunSets run_sets(const Study& st, const std::vector<bool>& have) {
    RunSets s;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        s.runs.push_back(i);
        if (st.runs[i].point == st.tradeoff.reference) s.refs.push_back(i);
    }
    return s;
}

const double* analytic_of(const StudyTradeoff& spec, const std::string& q) {
    for (const auto& [k, v] : spec.analytic) {
        if (k == q) return &v;
    }
    return nullptr;
}

// The study's quantities, else the headline estimates of the reference runs (of every run
// without them) and the quantities given analytic values.
std::vector<std::string> wanted_quantities(const StudyTradeoff& spec, const RunSets& s,
                                           const std::vector<Row>& rows) {
    if (!spec.quantities.empty()) return spec.quantities;
    std::set<std::string> avail;
    for (std::size_t i : s.refs.empty() ? s.runs : s.refs) {
        for (const auto& [k, v] : rows[i])
            if (!std::isnan(v.second)) avail.insert(k);
    }
    std::vector<std::string> wanted = default_tradeoff_quantities({avail.begin(), avail.end()});
    for (const auto& [k, v] : spec.analytic) {
        if (std::find(wanted.begin(), wanted.end(), k) == wanted.end()) wanted.push_back(k);
    }
    return wanted;
}

// The reference value of every quantity compared, with its error.
struct References {
    std::vector<double> value, error;
};

// Quantity q's reference from the runs of the reference point: their mean, with the error of
// the mean; false (and a problem noted) when there is none or it is 0.
bool mean_of_reference_runs(const std::string& q, const std::vector<std::size_t>& refs,
                            const std::vector<Row>& rows, TradeoffResult& t, References& r) {
    double sum = 0, var = 0;
    std::size_t k = 0;
    for (std::size_t i : refs) {
        auto it = rows[i].find(q);
        if (it == rows[i].end() || !std::isfinite(it->second.first)) continue;
        sum += it->second.first;
        var += std::isfinite(it->second.second) ? it->second.second * it->second.second : 0;
        ++k;
    }
    if (k == 0) {
        t.problems.push_back(fmt::format("{}: the reference runs do not report it", q));
        return false;
    }
    const double mean = sum / double(k);
    if (mean == 0) {
        t.problems.push_back(
            fmt::format("{}: the reference value is 0, so there is no relative deviation", q));
        return false;
    }
    r.value.push_back(mean);
    r.error.push_back(std::sqrt(var) / double(k));
    return true;
}

// Sets t.quantities and t.reference_kind to the quantities that have a reference (the others
// are noted in t.problems), and returns their references.
References find_references(const StudyTradeoff& spec, const std::vector<std::string>& wanted,
                           const std::vector<std::size_t>& refs, const std::vector<Row>& rows,
                           TradeoffResult& t) {
    References r;
    for (const auto& q : wanted) {
        if (const double* a = analytic_of(spec, q)) {
            t.quantities.push_back(q);
            t.reference_kind.push_back("analytic");
            r.value.push_back(*a);
            r.error.push_back(0);
            continue;
        }
        if (refs.empty()) {
            t.problems.push_back(fmt::format(
                "{}: no analytic value and no completed run of the reference point '{}'", q,
                spec.reference));
            continue;
        }
        if (is_distance(q)) {
            // A distance from the reference: 0 by definition, deviations are absolute.
            t.quantities.push_back(q);
            t.reference_kind.push_back(spec.reference + " (distance)");
            r.value.push_back(0);
            r.error.push_back(0);
            continue;
        }
        if (!mean_of_reference_runs(q, refs, rows, t, r)) continue;
        t.quantities.push_back(q);
        t.reference_kind.push_back(spec.reference);
    }
    return r;
}

// Quantity q of a run (row) against its reference.
TradeoffCell compare(const TradeoffResult& t, std::size_t q, const References& refs, const Row& row,
                     bool reference_run) {
    TradeoffCell cell;
    cell.reference = refs.value[q];
    cell.reference_error = refs.error[q];
    auto it = row.find(t.quantities[q]);
    if (it == row.end()) {
        cell.value = cell.error = cell.deviation = cell.deviation_error = cell.accuracy =
            std::nan("");
        return cell;
    }
    cell.value = it->second.first;
    cell.error = it->second.second;
    const bool distance = is_distance(t.quantities[q]);
    const double scale = distance ? 1.0 : std::abs(cell.reference);
    cell.deviation = (cell.value - cell.reference) / scale;
    // A reference run against the mean of the reference runs: its own error only (the two are
    // not independent). Any other run: both errors, independent runs.
    const bool analytic = t.reference_kind[q] == "analytic" || distance;
    const double e2 =
        cell.error * cell.error +
        (reference_run || analytic ? 0.0 : cell.reference_error * cell.reference_error);
    cell.deviation_error = std::sqrt(e2) / scale;
    cell.accuracy = std::abs(cell.deviation) + cell.deviation_error;
    return cell;
}

// Run i: its cost and every quantity against its reference.
TradeoffRow compare_run(const Study& st, std::size_t i, const Row& row, const TradeoffResult& t,
                        const References& refs) {
    const StudyTradeoff& spec = st.tradeoff;
    TradeoffRow r;
    r.run = st.runs[i].name;
    r.point = st.runs[i].point;
    r.knob = metadata_text(st.runs[i], "knob");
    r.level = metadata_text(st.runs[i], "level");
    r.reference = st.runs[i].point == spec.reference;
    auto c = row.find(spec.cost);
    r.cost = c == row.end() ? std::nan("") : c->second.first;
    auto w = row.find("performance.wall_time");
    r.wall = w == row.end() ? std::nan("") : w->second.first;
    r.worst = 0;
    for (std::size_t q = 0; q < t.quantities.size(); ++q) {
        const TradeoffCell cell = compare(t, q, refs, row, r.reference);
        r.worst = std::isnan(cell.accuracy) ? std::nan("") : std::max(r.worst, cell.accuracy);
        r.cells.push_back(cell);
    }
    if (t.quantities.empty()) r.worst = std::nan("");
    return r;
}

// Pareto fronts: per quantity and for the worst quantity.
void mark_pareto_fronts(TradeoffResult& t) {
    std::vector<double> cost;
    for (const auto& r : t.rows) cost.push_back(r.cost);
    for (std::size_t q = 0; q < t.quantities.size(); ++q) {
        std::vector<double> acc;
        for (const auto& r : t.rows) acc.push_back(r.cells[q].accuracy);
        const auto f = pareto_front(cost, acc);
        for (std::size_t k = 0; k < t.rows.size(); ++k) t.rows[k].cells[q].pareto = f[k];
    }
    std::vector<double> worst;
    for (const auto& r : t.rows) worst.push_back(r.worst);
    const auto f = pareto_front(cost, worst);
    for (std::size_t k = 0; k < t.rows.size(); ++k) t.rows[k].pareto = f[k];
}

}  // namespace

TradeoffResult analyse_tradeoff(const Study& st, const std::vector<std::string>& quantities,
                                const std::vector<Row>& rows, const std::vector<bool>& have,
                                const std::vector<std::map<std::string, double>>& n_eff) {
    TradeoffResult t;
    const StudyTradeoff& spec = st.tradeoff;
    const RunSets s = run_sets(st, have);
    const std::vector<std::string> wanted = wanted_quantities(spec, s, rows);
    if (std::find(quantities.begin(), quantities.end(), spec.cost) == quantities.end())
        t.problems.push_back(fmt::format("cost quantity '{}' is in no run summary", spec.cost));
    const References refs = find_references(spec, wanted, s.refs, rows, t);
    for (std::size_t i : s.runs) t.rows.push_back(compare_run(st, i, rows[i], t, refs));
    mark_pareto_fronts(t);
    add_cost_forecasts(st, rows, s.runs, n_eff, t);
    return t;
}

void write_tradeoff(h5::Group& root, const TradeoffResult& t) {
    h5::Group g = root.group("tradeoff");
    std::vector<std::string> runs, points, knobs, levels;
    std::vector<double> cost, wall, worst;
    std::vector<std::int64_t> pareto, reference;
    for (const auto& r : t.rows) {
        runs.push_back(r.run);
        points.push_back(r.point);
        knobs.push_back(r.knob);
        levels.push_back(r.level);
        cost.push_back(r.cost);
        wall.push_back(r.wall);
        worst.push_back(r.worst);
        pareto.push_back(r.pareto);
        reference.push_back(r.reference);
    }
    g.write_strings("runs", runs);
    g.write_strings("points", points);
    g.write_strings("knobs", knobs);
    g.write_strings("levels", levels);
    g.write("cost", cost);
    g.attr_on("cost", "unit", "s");
    g.write("wall_time", wall);
    g.attr_on("wall_time", "unit", "s");
    g.write("worst_accuracy", worst);
    g.write("pareto", pareto);
    g.write("reference", reference);
    g.write_strings("quantity_names", t.quantities);
    g.write_strings("reference_kind", t.reference_kind);
    g.write_strings("problems", t.problems);
    for (std::size_t q = 0; q < t.quantities.size(); ++q) {
        h5::Group qg = g.group("quantities/" + t.quantities[q]);
        std::vector<double> v, e, d, de, acc, cpu_to;
        std::vector<std::int64_t> p, biased;
        for (const auto& r : t.rows) {
            v.push_back(r.cells[q].value);
            e.push_back(r.cells[q].error);
            d.push_back(r.cells[q].deviation);
            de.push_back(r.cells[q].deviation_error);
            acc.push_back(r.cells[q].accuracy);
            p.push_back(r.cells[q].pareto);
            cpu_to.push_back(r.cells[q].cpu_to_target);
            biased.push_back(r.cells[q].biased);
        }
        qg.write("value", v);
        qg.write("error", e);
        qg.write("deviation", d);
        qg.write("deviation_error", de);
        qg.write("accuracy", acc);
        qg.write("pareto", p);
        qg.write("cpu_to_target", cpu_to);
        qg.attr_on("cpu_to_target", "unit", "s");
        qg.attr_on("cpu_to_target", "target", t.target[q]);
        qg.attr_on("cpu_to_target", "target_kind", t.target_kind[q]);
        qg.write("biased", biased);
        const double ref = t.rows.empty() ? std::nan("") : t.rows[0].cells[q].reference;
        const double ref_e = t.rows.empty() ? std::nan("") : t.rows[0].cells[q].reference_error;
        qg.write_scalar("reference", ref);
        qg.attr_on("reference", "error", ref_e);
        qg.attr("reference_kind", t.reference_kind[q]);
    }
}

void write_tradeoff_csv(const std::string& path, const TradeoffResult& t) {
    std::ofstream o(path);
    // cost and wall_time in s, named as in /tradeoff and the run summaries.
    o << "run,point,knob,level,cost,wall_time,reference_run,worst_accuracy,pareto";
    for (const auto& q : t.quantities) {
        for (const char* c : {"value", "error", "deviation", "deviation_error", "pareto",
                              "cpu_to_target", "biased"})
            o << "," << q << "." << c;
    }
    o << "\n";
    auto num = [](double x) { return std::isnan(x) ? std::string() : fmt::format("{:.8g}", x); };
    for (const auto& r : t.rows) {
        o << r.run << "," << r.point << "," << r.knob << "," << r.level << "," << num(r.cost) << ","
          << num(r.wall) << "," << int(r.reference) << "," << num(r.worst) << "," << int(r.pareto);
        for (const auto& c : r.cells) {
            o << "," << num(c.value) << "," << num(c.error) << "," << num(c.deviation) << ","
              << num(c.deviation_error) << "," << int(c.pareto) << "," << num(c.cpu_to_target)
              << "," << int(c.biased);
        }
        o << "\n";
    }
}

std::string tradeoff_table(const TradeoffResult& t) {
    std::string s;
    for (std::size_t q = 0; q < t.quantities.size(); ++q) {
        s += fmt::format("q{} = {}: reference {} = {:.6g} +- {:.2g}\n", q + 1, t.quantities[q],
                         t.reference_kind[q],
                         t.rows.empty() ? std::nan("") : t.rows[0].cells[q].reference,
                         t.rows.empty() ? std::nan("") : t.rows[0].cells[q].reference_error);
    }
    s += "\n| run | knob | level | CPU s | wall s |";
    for (std::size_t q = 0; q < t.quantities.size(); ++q)
        s += fmt::format(" q{} deviation |", q + 1);
    s += " worst | front |\n|---|---|---|---:|---:|";
    for (std::size_t q = 0; q < t.quantities.size(); ++q) s += "---:|";
    s += "---:|:-:|\n";
    // Cheapest first: the table reads as a ladder of cost.
    std::vector<std::size_t> order(t.rows.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return t.rows[a].cost < t.rows[b].cost; });
    for (std::size_t k : order) {
        const auto& r = t.rows[k];
        s += fmt::format("| {}{} | {} | {} | {:.3g} | {:.3g} |", r.run, r.reference ? " (ref)" : "",
                         r.knob.empty() ? "-" : r.knob, r.level.empty() ? "-" : r.level, r.cost,
                         r.wall);
        for (const auto& c : r.cells) {
            if (std::isnan(c.deviation))
                s += " - |";
            else
                s += fmt::format(" {:+.2f}% +- {:.2f}%{} |", 100 * c.deviation,
                                 100 * c.deviation_error, c.pareto ? " *" : "");
        }
        s += fmt::format(" {:.2f}% | {} |\n", 100 * r.worst, r.pareto ? "yes" : "");
    }
    for (const auto& p : t.problems) s += "note: " + p + "\n";
    return s;
}

}  // namespace gran
