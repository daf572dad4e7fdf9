#include "libgran/study/study_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace gran {

PowerLawFit fit_power_law(std::span<const double> x, std::span<const double> y, double tolerance) {
    std::vector<double> lx, ly;
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
        if (x[i] > 0 && y[i] > 0 && std::isfinite(x[i]) && std::isfinite(y[i])) {
            lx.push_back(std::log(x[i]));
            ly.push_back(std::log(y[i]));
        }
    }
    PowerLawFit f;
    f.points = lx.size();
    if (f.points < 2) {
        f.theta = f.theta_error = f.log_prefactor = f.max_deviation = std::nan("");
        return f;
    }
    const double m = double(f.points);
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < lx.size(); ++i) {
        mx += lx[i] / m;
        my += ly[i] / m;
    }
    double sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < lx.size(); ++i) {
        sxx += (lx[i] - mx) * (lx[i] - mx);
        sxy += (lx[i] - mx) * (ly[i] - my);
    }
    if (!(sxx > 0)) {
        f.theta = f.theta_error = f.log_prefactor = f.max_deviation = std::nan("");
        return f;
    }
    f.theta = sxy / sxx;
    f.log_prefactor = my - f.theta * mx;
    double ssr = 0;
    f.max_deviation = 0;
    for (std::size_t i = 0; i < lx.size(); ++i) {
        const double r = ly[i] - (f.log_prefactor + f.theta * lx[i]);
        ssr += r * r;
        f.max_deviation = std::max(f.max_deviation, std::abs(r));
    }
    // Standard error of an OLS slope: sqrt(SSR / (m - 2) / Sxx).
    f.theta_error = f.points > 2 ? std::sqrt(ssr / (m - 2) / sxx) : std::nan("");
    f.valid = f.max_deviation < tolerance;
    return f;
}

namespace {

// "<point>" for the key `point`, else the value the run gives the scene key ("" if none); the
// group of a run is the "_"-joined list, its label "<last key part><value>" joined.
std::string group_value(const StudyRun& run, const std::string& key) {
    return key == "point" ? run.point : override_value(run, key);
}

std::string group_of(const StudyRun& run, const std::vector<std::string>& keys) {
    std::string g;
    for (const auto& k : keys) g += (g.empty() ? "" : "|") + group_value(run, k);
    return g;
}

std::string group_label(const StudyRun& run, const std::vector<std::string>& keys) {
    std::string label;
    for (const auto& k : keys) {
        const auto dot = k.rfind('.');
        label += "_" + (k == "point" ? "" : k.substr(dot == std::string::npos ? 0 : dot + 1)) +
                 group_value(run, k);
    }
    return label;
}

}  // namespace

std::vector<FitResult> fit_all(const Study& st, const std::vector<std::string>& quantities,
                               const std::vector<Row>& rows, const std::vector<bool>& have,
                               const std::function<double(const StudyFit&, std::size_t)>& x_of) {
    std::vector<FitResult> out;
    for (const auto& spec : st.fits) {
        if (std::find(quantities.begin(), quantities.end(), spec.y) == quantities.end()) {
            FitResult r;
            r.spec = spec;
            r.name = spec.name;
            r.fit = fit_power_law({}, {}, spec.tolerance);
            r.problem = fmt::format(
                "{}: no run reports the quantity '{}' (the study's .study.csv lists them)", st.file,
                spec.y);
            out.push_back(std::move(r));
            continue;
        }
        std::vector<std::string> groups;
        for (std::size_t i = 0; i < st.runs.size(); ++i) {
            if (!have[i]) continue;
            const std::string g = group_of(st.runs[i], spec.group_by);
            if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
        }
        for (const auto& g : groups) {
            FitResult r;
            r.spec = spec;
            r.group = g;
            r.name = spec.name;
            for (std::size_t i = 0; i < st.runs.size(); ++i) {
                if (!have[i]) continue;
                if (group_of(st.runs[i], spec.group_by) != g) continue;
                if (r.x.empty()) r.name = spec.name + group_label(st.runs[i], spec.group_by);
                auto it = rows[i].find(spec.y);
                if (it == rows[i].end()) continue;
                r.x.push_back(x_of(spec, i));
                r.y.push_back(it->second.first);
                r.y_error.push_back(it->second.second);
            }
            r.fit = fit_power_law(r.x, r.y, spec.tolerance);
            out.push_back(std::move(r));
        }
    }
    return out;
}

void write_fits(h5::Group& root, const std::vector<FitResult>& fits) {
    for (const auto& r : fits) {
        h5::Group g = root.group("fits/" + r.name);
        g.attr("x", r.spec.x);
        g.attr("y", r.spec.y);
        g.attr("group_by", r.spec.group_by);
        g.attr("group", r.group);
        g.attr("tolerance", r.spec.tolerance);
        g.attr("model", "log y = theta log x + log_prefactor (least squares)");
        g.write("x", r.x);
        g.write("y", r.y);
        g.write("y_error", r.y_error);
        g.write_scalar("theta", r.fit.theta);
        g.attr_on("theta", "error", r.fit.theta_error);
        g.write_scalar("log_prefactor", r.fit.log_prefactor);
        g.write_scalar("max_deviation", r.fit.max_deviation);
        g.write_scalar("valid", static_cast<std::int64_t>(r.fit.valid ? 1 : 0));
    }
}

void write_fits_csv(const std::string& path, const std::vector<FitResult>& fits) {
    std::ofstream o(path);
    o << "fit,x,y,group,points,theta,theta_error,log_prefactor,max_deviation,valid\n";
    for (const auto& r : fits) {
        o << fmt::format("{},{},{},{},{},{:.6g},{:.3g},{:.6g},{:.3g},{}\n", r.name, r.spec.x,
                         r.spec.y, r.group, r.fit.points, r.fit.theta, r.fit.theta_error,
                         r.fit.log_prefactor, r.fit.max_deviation, r.fit.valid ? 1 : 0);
    }
}

std::string describe(const FitResult& r) {
    if (!r.problem.empty()) return r.name + ": " + r.problem;
    if (!r.fit.valid) {
        return fmt::format("{}: no exponent ({} points; max |log deviation| {:.3g} >= {:.3g})",
                           r.name, r.fit.points, r.fit.max_deviation, r.spec.tolerance);
    }
    const std::string err = std::isnan(r.fit.theta_error)
                                ? std::string(" (two points: no error estimate)")
                                : fmt::format(" +- {:.4f}", r.fit.theta_error);
    return fmt::format("{}: theta = {:.4f}{} over {} points (max |log deviation| {:.3f})", r.name,
                       r.fit.theta, err, r.fit.points, r.fit.max_deviation);
}

}  // namespace gran
