#include "libgran/study/study_pool.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

namespace gran {

namespace {

struct Pooled {
    double value = std::nan(""), error = std::nan(""), scatter = std::nan("");
};

Pooled pool(const std::vector<std::pair<double, double>>& x) {
    Pooled p;
    const double n = double(x.size());
    if (x.empty()) return p;
    bool weighted = true;
    for (const auto& [v, e] : x) weighted = weighted && std::isfinite(e) && e > 0;
    if (weighted) {
        double sw = 0, swx = 0;
        for (const auto& [v, e] : x) {
            sw += 1 / (e * e);
            swx += v / (e * e);
        }
        p.value = swx / sw;
        p.error = 1 / std::sqrt(sw);
        if (x.size() > 1) {
            double chi2 = 0;
            for (const auto& [v, e] : x) chi2 += (v - p.value) * (v - p.value) / (e * e);
            p.scatter = std::sqrt(chi2 / (n - 1));
        }
        return p;
    }
    double mean = 0;
    for (const auto& [v, e] : x) mean += v / n;
    p.value = mean;
    if (x.size() > 1) {
        double var = 0;
        for (const auto& [v, e] : x) var += (v - mean) * (v - mean) / (n - 1);
        p.error = std::sqrt(var / n);
    }
    return p;
}

std::string number(double x) {
    return std::isfinite(x) ? fmt::format("{:.10g}", x) : std::string();
}

std::string field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string o = "\"";
    for (char c : s) o += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return o + "\"";
}

// The run's name without its replica suffix "_r<k>".
std::string group_of(const StudyRun& run) {
    if (run.replica <= 0) return run.name;
    const std::string suffix = "_r" + std::to_string(run.replica);
    const std::string& n = run.name;
    return n.size() > suffix.size() &&
                   n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0
               ? n.substr(0, n.size() - suffix.size())
               : n;
}

}  // namespace

bool write_pooled_csv(const std::string& path, const Study& st,
                      const std::vector<std::string>& quantities,
                      const std::vector<SummaryRow>& rows, const std::vector<bool>& have) {
    bool replicas = false;
    for (const StudyRun& run : st.runs) replicas = replicas || run.replica > 0;
    if (!replicas) return false;
    std::vector<std::string> order;
    std::map<std::string, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < st.runs.size(); ++i) {
        if (!have[i]) continue;
        const std::string g = group_of(st.runs[i]);
        if (!groups.count(g)) order.push_back(g);
        groups[g].push_back(i);
    }
    std::vector<std::string> keys;
    for (const auto& k : st.swept_keys) {
        if (k != "seed") keys.push_back(k);
    }
    std::ofstream o(path);
    o << "run,point,replicas";
    for (const auto& k : keys) o << "," << field(k);
    for (const auto& q : quantities)
        o << "," << field(q) << "," << field(q + ".error") << "," << field(q + ".scatter");
    o << "\n";
    for (const std::string& g : order) {
        const std::vector<std::size_t>& members = groups[g];
        const StudyRun& first = st.runs[members.front()];
        o << field(g) << "," << field(first.point) << "," << members.size();
        for (const auto& k : keys) o << "," << field(override_value(first, k));
        for (const auto& q : quantities) {
            std::vector<std::pair<double, double>> x;
            for (std::size_t i : members) {
                auto it = rows[i].find(q);
                if (it != rows[i].end() && std::isfinite(it->second.first)) x.push_back(it->second);
            }
            const Pooled p = pool(x);
            o << "," << number(p.value) << "," << number(p.error) << "," << number(p.scatter);
        }
        o << "\n";
    }
    return true;
}

}  // namespace gran
