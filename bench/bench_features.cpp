// What each feature costs (issue 6): the bare monodisperse smooth elastic gas in a periodic box run
// through the real scene/run path (YAML -> parse_scene -> run_scene, as `gran run`), against
//  1. a minimal specialised event-driven kernel for exactly that case (bench/minimal_event_driven),
//     which gran's bare gas must match within 10% (collisions per CPU second, same N, packing
//     fraction, initial state and number of collisions); the kernel's physics is checked (energy,
//     momentum, no overlaps, and a collision frequency equal to gran's within 1%);
//  2. the same scene with one feature added (bench/feature_scenes): the ratio of CPU time per
//     collision (event-driven; per particle-step for DEM) to its baseline scene.
// Every ratio is a median over interleaved pairs (baseline and feature run back to back, the order
// alternating between rounds) measured in one process with the process CPU clock: the machine is
// shared, so single absolute times mean little.
//
//   gran_bench_features [--quick] [--repeats R] [--only KEY,...] [--geometries 2d_phi0.1,...]
//                       [--no-minimal] [--csv PATH]
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_clock.hpp"
#include "bench/feature_scenes.hpp"
#include "bench/minimal_event_driven.hpp"
#include "libgran/core/h5.hpp"
#include "libgran/core/huge_pages.hpp"
#include "libgran/run/run.hpp"
#include "libgran/scene/placement.hpp"
#include "libgran/scene/scene.hpp"

namespace {

using namespace gran;
using namespace gran::bench;

struct Options {
    bool quick = false;
    int repeats = 3;
    int minimal_repeats = 5;
    bool minimal = true;
    std::vector<std::string> only;        // feature keys (baselines are run as needed)
    std::vector<std::string> geometries;  // substrings of "2d_phi0.1_N10000"
    std::string csv;
};

std::string geometry_name(const Geometry& g) {
    return fmt::format("{}d_phi{}_N{}", g.dim, g.phi, g.n);
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t end = s.find(',', start);
        const std::string tok = s.substr(start, end == std::string::npos ? end : end - start);
        if (!tok.empty()) out.push_back(tok);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

// One run of a scene through run_scene: CPU seconds of the whole call (setup, run, output),
// the engine's work counters and the simulated time.
struct Measured {
    double cpu = 0;
    double collisions = 0;
    double events = 0;  // event-driven: events; DEM: particle-steps
    double sim_time = 0;
};

Measured run_gran(const YAML::Node& scene_yaml, const std::string& tag,
                  const std::filesystem::path& dir) {
    const Scene scene = parse_scene(YAML::Clone(scene_yaml), tag + ".yaml");
    RunOptions opt;
    opt.output = (dir / (tag + ".h5")).string();
    opt.progress = false;
    const double c0 = cpu_seconds();
    const RunReport rep = run_scene(scene, opt);
    Measured m;
    m.cpu = cpu_seconds() - c0;
    const YAML::Node perf = rep.summary["performance"];
    if (perf["engine"].as<std::string>() == "dem") {
        const double n = rep.summary["particles"].as<double>();
        m.events = perf["steps"].as<double>() * n;
        m.collisions = m.events;
    } else {
        m.events = perf["events"].as<double>();
        m.collisions = perf["collisions"].as<double>();
    }
    {
        h5::File f = h5::File::open_read(opt.output);
        m.sim_time = f.root().read_doubles("performance/final_time").at(0);
    }
    std::filesystem::remove(opt.output);
    std::filesystem::remove(rep.summary_file);
    if (!rep.completed) throw std::runtime_error(tag + ": run did not complete");
    return m;
}

double median(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    const std::size_t k = x.size() / 2;
    return x.size() % 2 ? x[k] : 0.5 * (x[k - 1] + x[k]);
}

struct Row {
    std::string engine, geometry, key, what, baseline, unit;
    Geometry g;
    double rate = 0;  // collisions (particle-steps) per CPU second of the feature run, median
    std::vector<double> ratios, event_ratios;
    double events_per_collision = 0;
};

// ---- 1. gran's bare gas against the minimal kernel ------------------------------------------

struct MinimalRun {
    double cpu = 0, collisions = 0, events = 0, sim_time = 0;
    double energy_err = 0, momentum_err = 0;
    std::uint64_t overlaps = 0;
};

template <int D>
MinimalRun run_minimal(const Scene& sc, std::uint64_t collisions) {
    // The scene's own initial state (same generator, seed and streams as run_scene).
    Box<D> box;
    for (int a = 0; a < D; ++a) {
        box.length[a] = sc.box_length[std::size_t(a)];
        box.periodic[std::size_t(a)] = true;
    }
    Rng rng = make_rng(sc.seed, Stream::Placement);
    Particles<D> p = place_lattice<D>(box, sc.species, rng);
    Rng vrng = make_rng(sc.seed, Stream::Velocities);
    maxwellian_velocities<D>(p, sc.species, sc.temperature, vrng);
    std::vector<double> r, v;
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (int a = 0; a < D; ++a) {
            r.push_back(p.r[i][a]);
            v.push_back(p.v[i][a]);
        }
    }
    auto energy = [](const std::vector<double>& u) {
        double e = 0;
        for (double x : u) e += 0.5 * x * x;
        return e;
    };
    auto momentum = [](const std::vector<double>& u) {
        std::vector<double> m(D, 0.0);
        for (std::size_t k = 0; k < u.size(); ++k) m[k % D] += u[k];
        return m;
    };
    const double e0 = energy(v);
    const auto m0 = momentum(v);
    MinimalRun out;
    const double c0 = cpu_seconds();
    MinimalEventDriven<D> md(box.length[0], r, v);
    md.run_until(collisions);
    out.cpu = cpu_seconds() - c0;
    md.state(r, v);
    out.collisions = double(md.collisions());
    out.events = double(md.events());
    out.sim_time = md.now();
    out.overlaps = md.overlaps();
    out.energy_err = std::abs(energy(v) - e0) / e0;
    const auto m1 = momentum(v);
    double dm = 0;
    for (int a = 0; a < D; ++a)
        dm += (m1[std::size_t(a)] - m0[std::size_t(a)]) * (m1[std::size_t(a)] - m0[std::size_t(a)]);
    out.momentum_err = std::sqrt(dm) / std::sqrt(2 * e0);
    return out;
}

struct MinimalComparison {
    Geometry g;
    std::vector<double> ratios;  // gran CPU per collision / kernel CPU per collision
    double gran_rate = 0, kernel_rate = 0;
    double omega_gran = 0, omega_kernel = 0;
    bool physics_ok = true;
    std::string problem;
};

MinimalComparison compare_minimal(const Geometry& g, const RunLength& run, int repeats,
                                  const std::filesystem::path& dir) {
    MinimalComparison mc;
    mc.g = g;
    const YAML::Node bare = bare_scene("event_driven", g, run);
    const Scene sc = parse_scene(YAML::Clone(bare), "bare.yaml");
    // The run's collisions: equilibration plus measurement, as run_with counts them.
    const auto coll_of = [&](double cpp) {
        return static_cast<std::uint64_t>(std::llround(cpp * double(g.n) / 2.0));
    };
    const std::uint64_t total = coll_of(run.ed_equilibration) + coll_of(run.ed_measurement);
    std::vector<double> gran_rates, kernel_rates;
    for (int k = 0; k < repeats; ++k) {
        Measured gm;
        MinimalRun km;
        auto kernel = [&] {
            km = g.dim == 2 ? run_minimal<2>(sc, total) : run_minimal<3>(sc, total);
        };
        auto gran_run = [&] { gm = run_gran(bare, "bare_vs_minimal", dir); };
        if (k % 2 == 0) {
            gran_run();
            kernel();
        } else {
            kernel();
            gran_run();
        }
        mc.ratios.push_back((gm.cpu / gm.collisions) / (km.cpu / km.collisions));
        gran_rates.push_back(gm.collisions / gm.cpu);
        kernel_rates.push_back(km.collisions / km.cpu);
        // Same physics: collision frequency per particle 2 N_coll / (N t) over the whole run from
        // the identical initial state. Its relative statistical error is about 1/sqrt(N_coll)
        // (1.3e-3 for 6e5 collisions), so 1% is a ~7 sigma bound that a wrong contact distance
        // (+1% in sigma gives +1% to +3% in omega through sigma^(d-1) chi) or missed collisions
        // would break.
        mc.omega_gran = 2 * gm.collisions / (double(g.n) * gm.sim_time);
        mc.omega_kernel = 2 * km.collisions / (double(g.n) * km.sim_time);
        std::vector<std::string> bad;
        if (!(km.energy_err <= 1e-9)) bad.push_back(fmt::format("dE/E = {:.2e}", km.energy_err));
        if (!(km.momentum_err <= 1e-9)) bad.push_back(fmt::format("dP = {:.2e}", km.momentum_err));
        if (km.overlaps > 0) bad.push_back(fmt::format("{} overlaps", km.overlaps));
        if (km.collisions != double(total) || gm.collisions != double(total))
            bad.push_back("collision counts differ");
        if (!(std::abs(mc.omega_kernel / mc.omega_gran - 1) <= 0.01))
            bad.push_back(
                fmt::format("omega kernel/gran = {:.4f}", mc.omega_kernel / mc.omega_gran));
        if (!bad.empty()) {
            mc.physics_ok = false;
            for (const auto& b : bad) mc.problem += (mc.problem.empty() ? "" : ", ") + b;
        }
    }
    mc.gran_rate = median(gran_rates);
    mc.kernel_rate = median(kernel_rates);
    return mc;
}

// ---- 2. the cost of each feature -------------------------------------------------------------

Row measure_feature(const std::vector<Feature>& all, const Feature& f, const Geometry& g,
                    const RunLength& run, int repeats, const std::filesystem::path& dir) {
    Row row;
    row.engine = f.engine;
    row.g = g;
    row.geometry = geometry_name(g);
    row.key = f.key;
    row.what = f.what;
    row.baseline = f.baseline;
    row.unit = f.engine == "dem" ? "particle-steps/s" : "collisions/s";
    const YAML::Node base = feature_scene(all, f.baseline, g, run);
    const YAML::Node with = feature_scene(all, f.key, g, run);
    std::vector<double> rates, epc;
    for (int k = 0; k < repeats; ++k) {
        Measured b, w;
        if (k % 2 == 0) {
            b = run_gran(base, "baseline", dir);
            w = run_gran(with, "feature", dir);
        } else {
            w = run_gran(with, "feature", dir);
            b = run_gran(base, "baseline", dir);
        }
        row.ratios.push_back((w.cpu / w.collisions) / (b.cpu / b.collisions));
        row.event_ratios.push_back((w.cpu / w.events) / (b.cpu / b.events));
        rates.push_back(w.collisions / w.cpu);
        epc.push_back((w.events / w.collisions) / (b.events / b.collisions));
    }
    row.rate = median(rates);
    row.events_per_collision = median(epc);
    return row;
}

void usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: gran_bench_features [--quick] [--repeats R] [--only KEY,...]\n"
                 "                           [--geometries 2d_phi0.1,...] [--no-minimal] "
                 "[--csv PATH]\n"
                 "  The cost of each scene feature relative to the bare monodisperse elastic\n"
                 "  smooth gas, and the bare gas against a minimal specialised kernel.\n"
                 "  --quick       N = 2000, 1 round, shorter runs (smoke test)\n"
                 "  --repeats     interleaved (baseline, feature) pairs per feature (default 3;\n"
                 "                the bare gas and the kernel: 5 pairs)\n"
                 "  --only        feature keys (e.g. gravity,obs_profiles); 'none': minimal only\n"
                 "  --geometries  keep geometries whose name contains any of these\n"
                 "  --no-minimal  skip the comparison with the minimal kernel\n"
                 "  --csv         write the rows to PATH\n"
                 "  Exits 1 if the kernel's physics checks fail or the bare gas is more than\n"
                 "  10%% slower than the kernel.\n");
}

std::optional<Options> parse(int argc, char** argv) {
    Options o;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        auto value = [&]() -> std::optional<std::string> {
            if (k + 1 >= argc) return std::nullopt;
            return std::string(argv[++k]);
        };
        if (a == "--quick") {
            o.quick = true;
        } else if (a == "--no-minimal") {
            o.minimal = false;
        } else if (a == "--repeats" || a == "--only" || a == "--geometries" || a == "--csv") {
            const auto v = value();
            if (!v) return std::nullopt;
            if (a == "--repeats") o.repeats = std::max(1, std::atoi(v->c_str()));
            if (a == "--only") o.only = split(*v);
            if (a == "--geometries") o.geometries = split(*v);
            if (a == "--csv") o.csv = *v;
        } else if (a == "-h" || a == "--help") {
            usage(stdout);
            std::exit(0);
        } else {
            std::fprintf(stderr, "gran_bench_features: unknown argument '%s'\n", a.c_str());
            return std::nullopt;
        }
    }
    return o;
}

std::string spread(const std::vector<double>& r) {
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    return fmt::format("{:.3f} [{:.3f}-{:.3f}]", median(r), *lo, *hi);
}

// N, and under --quick shorter runs and a single round.
std::size_t apply_quick(Options& opt, RunLength& run) {
    if (!opt.quick) return 10000;
    opt.repeats = 1;
    opt.minimal_repeats = 1;
    run.ed_equilibration = 10;
    run.ed_measurement = 40;
    run.dem_measurement = 0.4;
    run.samples = 40;
    return 2000;
}

std::vector<Geometry> select_geometries(const Options& opt, std::size_t n) {
    std::vector<Geometry> geometries;
    for (const auto& [dim, phi] :
         std::vector<std::pair<int, double>>{{2, 0.1}, {2, 0.5}, {3, 0.1}, {3, 0.3}}) {
        const Geometry g{dim, phi, n};
        bool keep = opt.geometries.empty();
        for (const auto& s : opt.geometries)
            keep = keep || geometry_name(g).find(s) != std::string::npos;
        if (keep) geometries.push_back(g);
    }
    return geometries;
}

// Part 1 (the table's rows as measured); ok becomes false when a check fails.
std::vector<MinimalComparison> bench_minimal(const std::vector<Geometry>& geometries,
                                             const RunLength& run, const Options& opt,
                                             const std::filesystem::path& dir, bool& ok) {
    std::vector<MinimalComparison> minimal;
    std::printf(
        "1. bare gas through gran run vs the minimal kernel (bench/minimal_event_driven)\n");
    std::printf("%-18s %12s %12s %22s %10s %10s  %s\n", "geometry", "gran coll/s", "kernel coll/s",
                "gran/kernel CPU/coll", "omega gran", "kernel", "check");
    for (const auto& g : geometries) {
        auto mc = compare_minimal(g, run, opt.minimal_repeats, dir);
        const bool within = median(mc.ratios) <= 1.10;
        ok = ok && mc.physics_ok && within;
        std::printf("%-18s %12.4g %12.4g %22s %10.5f %10.5f  %s%s\n", geometry_name(g).c_str(),
                    mc.gran_rate, mc.kernel_rate, spread(mc.ratios).c_str(), mc.omega_gran,
                    mc.omega_kernel,
                    mc.physics_ok ? "physics ok" : ("PHYSICS FAILED: " + mc.problem).c_str(),
                    within ? ", within 10%" : ", MORE THAN 10% SLOWER");
        std::fflush(stdout);
        minimal.push_back(mc);
    }
    std::printf("\n");
    return minimal;
}

// Part 2: the rows of the features selected by --only ('none': no feature).
std::vector<Row> bench_features(const std::vector<Geometry>& geometries, const RunLength& run,
                                const Options& opt, const std::filesystem::path& dir) {
    std::vector<Row> rows;
    if (opt.only.size() == 1 && opt.only[0] == "none") return rows;
    std::printf(
        "2. cost of each feature: CPU time per collision (DEM: per particle-step) "
        "relative to its baseline\n");
    std::printf("%-14s %-26s %-16s %12s %9s %22s %22s\n", "geometry", "feature", "baseline", "rate",
                "ev/coll", "CPU/coll ratio", "CPU/event ratio");
    for (const auto& g : geometries) {
        // The thermostat's strength balances cooling at T = 1: the bare gas's collision frequency.
        Calibration cal;
        {
            const Measured m = run_gran(bare_scene("event_driven", g, run), "calibration", dir);
            cal.omega = 2 * m.collisions / (double(g.n) * m.sim_time);
        }
        const auto all = features(cal);
        for (const auto& f : all) {
            if (f.baseline.empty()) continue;
            if (f.engine == "dem" && g.dim != 3) continue;  // the DEM rows: spheres only
            if (!opt.only.empty() &&
                std::find(opt.only.begin(), opt.only.end(), f.key) == opt.only.end())
                continue;
            Row r = measure_feature(all, f, g, run, opt.repeats, dir);
            std::printf("%-14s %-26s %-16s %12.4g %9.3f %22s %22s\n", r.geometry.c_str(),
                        r.key.c_str(), r.baseline.c_str(), r.rate, r.events_per_collision,
                        spread(r.ratios).c_str(), spread(r.event_ratios).c_str());
            std::fflush(stdout);
            rows.push_back(r);
        }
    }
    return rows;
}

// --csv: false when the file cannot be written.
bool write_csv(const std::string& csv, const std::vector<MinimalComparison>& minimal,
               const std::vector<Row>& rows) {
    const std::filesystem::path path(csv);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    if (!out) {
        std::fprintf(stderr, "gran_bench_features: cannot write %s\n", csv.c_str());
        return false;
    }
    out << "engine,dimension,N,packing_fraction,feature,baseline,rate,unit,cost_ratio,"
           "cost_ratio_min,cost_ratio_max,event_cost_ratio,pairs\n";
    for (const auto& mc : minimal) {
        const auto [lo, hi] = std::minmax_element(mc.ratios.begin(), mc.ratios.end());
        out << fmt::format(
            "event_driven,{},{},{},bare_vs_minimal_kernel,minimal_kernel,{:.0f},"
            "collisions/s,{:.4f},{:.4f},{:.4f},,{}\n",
            mc.g.dim, mc.g.n, mc.g.phi, mc.gran_rate, median(mc.ratios), *lo, *hi,
            mc.ratios.size());
    }
    for (const auto& r : rows) {
        const auto [lo, hi] = std::minmax_element(r.ratios.begin(), r.ratios.end());
        out << fmt::format("{},{},{},{},{},{},{:.0f},{},{:.4f},{:.4f},{:.4f},{:.4f},{}\n", r.engine,
                           r.g.dim, r.g.n, r.g.phi, r.key, r.baseline, r.rate, r.unit,
                           median(r.ratios), *lo, *hi, median(r.event_ratios), r.ratios.size());
    }
    std::printf("wrote %s\n", csv.c_str());
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    gran::use_huge_pages(argv);  // may re-execute this program once (huge_pages.hpp)
    auto parsed = parse(argc, argv);
    if (!parsed) {
        usage(stderr);
        return 2;
    }
    Options opt = *parsed;
    RunLength run;
    const std::size_t n = apply_quick(opt, run);
    const std::vector<Geometry> geometries = select_geometries(opt, n);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("gran_bench_features_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    bool ok = true;

    std::printf(
        "gran_bench_features%s: CPU time ratios, medians of %d interleaved pairs [min-max]\n",
        opt.quick ? " (--quick)" : "", opt.repeats);
    std::printf(
        "event-driven runs: %g + %g collisions per particle, %d samples; DEM: t = %g, "
        "%d samples\n\n",
        run.ed_equilibration, run.ed_measurement, run.samples, run.dem_measurement, run.samples);
    std::vector<MinimalComparison> minimal;
    if (opt.minimal) minimal = bench_minimal(geometries, run, opt, dir, ok);
    const std::vector<Row> rows = bench_features(geometries, run, opt, dir);
    std::filesystem::remove_all(dir);

    if (!opt.csv.empty() && !write_csv(opt.csv, minimal, rows)) return 1;
    if (!ok) {
        std::fprintf(stderr, "gran_bench_features: FAILED (see the minimal-kernel rows)\n");
        return 1;
    }
    return 0;
}
