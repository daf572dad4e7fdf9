// Throughput benchmark of the event-driven engine: collisions per CPU second for monodisperse
// elastic hard disks and spheres in a periodic square/cubic box, one core, plain timers.
//
// Per case: one species (m = 1, sigma = 1, alpha = 1, beta = -1), box from the packing fraction,
// simple lattice (random insertion cannot reach phi = 0.5 in 2D), Maxwellian velocities at T = 1,
// equilibration until the lattice has melted (a fixed number of collisions per particle), then a
// timed run of a fixed number of collisions. Elastic dynamics conserve kinetic energy exactly up to
// round-off, so every case doubles as a sanity check: relative drift above 1e-9 (or a lattice that
// did not melt) fails the run with a non-zero exit status.
//
//   gran_bench [--quick] [--cases 2d,3d,phi0.5,...] [--n 10000,100000] [--equil C] [--csv PATH]
//   gran_bench --dimension 3 --packing-fraction 0.1,0.2,0.3,0.4,0.5 --n 1e4,1e5,1e6
// The start is the simple lattice where its sites are a diameter apart, else the close-packed
// (hexagonal/fcc) one, which reaches every packing fraction accepted (3D up to 0.55, 2D 0.8).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_clock.hpp"
#include "bench/bench_memory.hpp"
#include "libgran/core/huge_pages.hpp"
#include "libgran/core/kinetic_theory.hpp"
#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/scene/interactions.hpp"
#include "libgran/scene/placement.hpp"

namespace {

using gran::bench::cpu_seconds;
using gran::bench::wall_seconds;

using namespace gran;

struct Case {
    int dim;
    double phi;
    std::size_t n;
    std::string name() const { return fmt::format("{}d_phi{}_N{}", dim, phi, n); }
};

struct Options {
    bool quick = false;
    std::vector<std::string> case_filters;  // substrings of the case name; any match selects
    std::vector<std::size_t> sizes;         // empty = all
    std::vector<int> dimensions;            // --dimension: with --packing-fraction, the geometries
    std::vector<double> packing_fractions;  // (every pair); empty: the default five
    std::string csv;
    std::uint64_t seed = 12345;
    double equil_per_particle = 20;  // collisions per particle (each collision counts for both)
    std::uint64_t timed_min = 2'000'000;
    double timed_per_particle = 20;  // timed collisions >= this many times N
    bool shuffle = false;            // random particle order (as random placement gives)
    CellLayout cell_layout =
        CellLayout::automatic;  // --cell-layout: the engine's choice, or forced
    double skin = -1;           // --skin: neighbour shells' skin (negative: the engine's choice)
    QueueLayout queue = QueueLayout::automatic;  // --queue: the engine's choice, or forced
};

struct Result {
    Case c;
    std::uint64_t collisions = 0;
    double cpu_s = 0, wall_s = 0, setup_s = 0, equil_s = 0;
    EngineCounters delta;  // counters of the timed part only
    double energy_rel_err = 0;
    double momentum_err = 0;
    double melted_fraction = 0;     // particles whose velocity changed during equilibration
    double omega_over_enskog = 0;   // measured collision frequency / enskog_collision_frequency
    double skin = 0;                // neighbour shells' skin the engine used (0: cells)
    double bytes_per_particle = 0;  // peak resident memory of the case / N (bench_memory.hpp)
    bool ok = true;
    double rate_cpu() const { return double(collisions) / cpu_s; }
    double rate_wall() const { return double(collisions) / wall_s; }
    double events_per_s() const { return double(delta.events) / cpu_s; }
    double per_collision(std::uint64_t x) const { return double(x) / double(collisions); }
};

SpeciesTable monodisperse(std::size_t n) {
    SpeciesTable t;
    Species s;
    s.name = "grain";
    s.mass = 1;
    s.diameter = 1;
    s.count = n;
    t.species.push_back(s);
    return t;
}

// Elastic smooth contacts (constant_restitution, alpha = 1, beta = -1).
ContactTable elastic(const SpeciesTable& t, int dimension) {
    YAML::Node resolved;
    return read_interactions(YAML::Load("{}"), t, {"box"}, {dimension, 1.0, t.min_mass()},
                             {"bench", ""}, resolved);
}

template <int D>
double kinetic_energy(const Particles<D>& p) {
    double e = 0;
    for (const auto& v : p.v) e += 0.5 * v.squaredNorm();  // m = 1
    return e;
}

template <int D>
Vec<D> total_momentum(const Particles<D>& p) {
    Vec<D> m = Vec<D>::Zero();
    for (const auto& v : p.v) m += v;
    return m;
}

EngineCounters counters_minus(const EngineCounters& a, const EngineCounters& b) {
    EngineCounters d;
    d.events = a.events - b.events;
    d.collisions = a.collisions - b.collisions;
    d.cell_crossings = a.cell_crossings - b.cell_crossings;
    d.wall_hits = a.wall_hits - b.wall_hits;
    d.stale_events = a.stale_events - b.stale_events;
    d.tc_collisions = a.tc_collisions - b.tc_collisions;
    d.overlap_collisions = a.overlap_collisions - b.overlap_collisions;
    d.full_reschedules = a.full_reschedules - b.full_reschedules;
    d.shell_exits = a.shell_exits - b.shell_exits;
    d.wraps = a.wraps - b.wraps;
    return d;
}

template <int D>
Box<D> periodic_box(const Case& c) {
    Box<D> box;
    const double vd = D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
    box.length = Vec<D>::Constant(std::pow(double(c.n) * vd / c.phi, 1.0 / D));
    box.periodic.fill(true);
    return box;
}

// Simple lattice, Maxwellian velocities at T = 1 and, with --shuffle, random labels.
template <int D>
Particles<D> initial_particles(const Box<D>& box, const SpeciesTable& table, const Options& opt) {
    Rng rng_place = make_rng(opt.seed, Stream::Placement);
    Rng rng_vel = make_rng(opt.seed, Stream::Velocities);
    // The simple lattice has a diameter between sites only up to phi = pi/6 (3D) and pi/4 (2D),
    // less when N is not a power of D; past that the close-packed start.
    Particles<D> p;
    try {
        p = place_lattice<D>(box, table, rng_place);
    } catch (const PlacementError&) {
        p = place_close_packed<D>(box, table, rng_place);
    }
    maxwellian_velocities<D>(p, table, 1.0, rng_vel);
    if (opt.shuffle) {
        // Lattice sites are numbered in space-filling order, so neighbours are close in memory;
        // random placement gives no such locality. Relabel the particles to measure its cost.
        for (std::size_t k = p.size(); k > 1; --k) {
            const auto j = static_cast<std::size_t>(uniform01(rng_place) * double(k)) % k;
            std::swap(p.r[k - 1], p.r[j]);
            std::swap(p.v[k - 1], p.v[j]);
        }
    }
    return p;
}

// The fraction of particles whose velocity is no longer the initial one (x components kept as
// floats, 4 bytes per particle of the bench's own). The engine stores particles in cell order:
// the particle at storage index k has placement index ids[k].
template <int D>
double changed_fraction(const Particles<D>& p, const std::vector<std::uint32_t>& ids,
                        const std::vector<float>& vx0) {
    std::size_t changed = 0;
    for (std::size_t k = 0; k < vx0.size(); ++k) changed += float(p.v[k][0]) != vx0[ids[k]] ? 1 : 0;
    return double(changed) / double(vx0.size());
}

// Sanity: elastic dynamics conserve energy and momentum; the lattice must have melted. Warns and
// clears res.ok otherwise.
void check_sanity(Result& res, std::uint64_t n_timed) {
    const Case& c = res.c;
    if (res.collisions != n_timed) {
        std::fprintf(stderr, "WARNING %s: %llu collisions timed, %llu requested\n",
                     c.name().c_str(), static_cast<unsigned long long>(res.collisions),
                     static_cast<unsigned long long>(n_timed));
        res.ok = false;
    }
    if (!(res.energy_rel_err <= 1e-9)) {
        std::fprintf(stderr,
                     "WARNING %s: kinetic energy not conserved, relative error %.3e > 1e-9\n",
                     c.name().c_str(), res.energy_rel_err);
        res.ok = false;
    }
    if (!(res.momentum_err <= 1e-9)) {
        std::fprintf(stderr, "WARNING %s: momentum not conserved, |dP|/sqrt(2E) = %.3e > 1e-9\n",
                     c.name().c_str(), res.momentum_err);
        res.ok = false;
    }
    if (res.melted_fraction < 0.99) {
        std::fprintf(
            stderr,
            "WARNING %s: only %.4f of the particles collided during equilibration; lattice "
            "not melted\n",
            c.name().c_str(), res.melted_fraction);
        res.ok = false;
    }
}

template <int D>
Result run_case(const Case& c, const Options& opt) {
    Result res;
    res.c = c;
    // Memory: the case's peak resident set over its start (the engine's arrays, the set-up's
    // transients and the bench's 4 bytes per particle of initial velocities).
    gran::bench::reset_peak_resident();
    const std::uint64_t rss0 = gran::bench::resident_bytes();
    const double t_setup = wall_seconds();
    const SpeciesTable table = monodisperse(c.n);
    const Box<D> box = periodic_box<D>(c);
    Particles<D> p = initial_particles<D>(box, table, opt);
    const double e0 = kinetic_energy<D>(p);
    const Vec<D> p0 = total_momentum<D>(p);
    std::vector<float> vx0(c.n);
    for (std::size_t i = 0; i < c.n; ++i) vx0[i] = float(p.v[i][0]);
    EngineSettings settings;
    settings.cell_layout = opt.cell_layout;
    settings.queue_layout = opt.queue;
    settings.neighbour_skin = opt.skin;
    EventDrivenEngine<D> engine(box, table, elastic(table, D), std::move(p), settings);
    res.setup_s = wall_seconds() - t_setup;
    res.skin = engine.neighbour_skin();

    // Equilibration: equil_per_particle collisions per particle = equil_per_particle * N / 2.
    const double t_equil = wall_seconds();
    const auto n_equil = static_cast<std::uint64_t>(opt.equil_per_particle * double(c.n) / 2);
    engine.advance(kInf, n_equil);
    res.equil_s = wall_seconds() - t_equil;
    res.melted_fraction = changed_fraction<D>(engine.particles(), engine.ids(), vx0);

    // Timed part.
    const std::uint64_t n_timed = std::max<std::uint64_t>(
        opt.timed_min, static_cast<std::uint64_t>(opt.timed_per_particle * double(c.n)));
    const EngineCounters before = engine.counters();
    const double t0 = engine.now();
    const double w0 = wall_seconds();
    const double c0 = cpu_seconds();
    engine.advance(kInf, before.collisions + n_timed);
    const double c1 = cpu_seconds();
    const double w1 = wall_seconds();
    const double t1 = engine.now();
    const std::uint64_t peak = gran::bench::peak_resident_bytes();
    res.bytes_per_particle = peak > rss0 ? double(peak - rss0) / double(c.n) : 0;
    res.delta = counters_minus(engine.counters(), before);
    res.collisions = res.delta.collisions;
    res.cpu_s = c1 - c0;
    res.wall_s = w1 - w0;

    engine.synchronize();
    const double e1 = kinetic_energy<D>(engine.particles());
    res.energy_rel_err = std::abs(e1 - e0) / e0;
    res.momentum_err = (total_momentum<D>(engine.particles()) - p0).norm() / std::sqrt(2 * e0);
    const double temperature = 2 * e0 / (D * double(c.n));  // m = 1
    // The Enskog frequency is exact given the contact value (Carnahan-Starling in 3D, Henderson
    // in 2D, both within ~1% up to freezing): a lattice that stayed crystalline shows as a ratio
    // far from 1.
    const double density = (D == 3 ? 6 : 4) * c.phi / std::numbers::pi;  // sigma = 1
    res.omega_over_enskog = 2 * double(res.collisions) / (double(c.n) * (t1 - t0)) /
                            theory::enskog_collision_frequency(
                                D, density, 1.0, theory::contact_value(D, c.phi), temperature, 1.0);
    check_sanity(res, n_timed);
    return res;
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t end = s.find(',', start);
        const std::string tok =
            s.substr(start, end == std::string::npos ? std::string::npos : end - start);
        if (!tok.empty()) out.push_back(tok);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

// The value named by a command-line word, or std::invalid_argument (a usage error).
template <class E>
E parse_choice(const std::string& word, std::initializer_list<std::pair<const char*, E>> choices) {
    for (const auto& [name, value] : choices)
        if (word == name) return value;
    throw std::invalid_argument(word);
}

void usage(std::FILE* f) {
    std::fprintf(
        f,
        "usage: gran_bench [--quick] [--cases F1,F2,...] [--n N1,N2,...] [--csv PATH] "
        "[--equil C] [--shuffle] [--seed S] [--cell-layout L] [--queue Q] [--slice-entries E]\n"
        "  [--skin S]\n"
        "  Collisions per CPU second of the event-driven engine, elastic monodisperse hard\n"
        "  disks (phi 0.1, 0.5) and spheres (phi 0.1, 0.2, 0.3), N = 1e4 and 1e5, periodic.\n"
        "  --quick    short smoke run (fewer collisions)\n"
        "  --cases    keep cases whose name (e.g. 3d_phi0.3_N100000) contains any filter\n"
        "  --n        keep only these particle numbers\n"
        "  --equil    equilibration collisions per particle (default 20, --quick 10)\n"
        "  --shuffle  relabel particles randomly (no memory locality, as random placement)\n"
        "  --seed     placement and velocity seed (default 12345)\n"
        "  --cell-layout auto|blocks|lists: the engine's choice (default), or the cells' contents\n"
        "             forced to per-cell blocks or linked lists (cell_list.hpp)\n"
        "  --queue auto|heap|calendar: the engine's choice (default), or the event queue forced\n"
        "             to one heap or to a calendar of time slices (event_queue.hpp)\n"
        "  --slice-entries E  entries per calendar slice (default 4; EventQueue::slice_entries)\n"
        "  --skin S   neighbour shells of skin S largest diameters (0: cells only); default: the\n"
        "             engine's choice from the packing fraction (neighbour_shells.hpp)\n"
        "  --dimension D1,D2 and --packing-fraction P1,P2,...: run these geometries instead of\n"
        "             the default five (every pair; 2D up to 0.8, 3D up to 0.55; one flag alone\n"
        "             filters the default five)\n"
        "  --csv      write case,engine,dimension,N,packing_fraction,rate,unit to PATH\n"
        "  Columns besides the rates: events, cell crossings, shell exits and stale events per\n"
        "  collision; skin, the neighbour shells' skin the engine used (0: cells);\n"
        "  B/part, the case's peak resident memory over its start per particle; w/Enskog, the\n"
        "  collisions per particle and time over the Enskog value (~1 in the fluid).\n"
        "  Exits 1 if energy/momentum conservation or lattice melting fails in any case.\n");
}

std::optional<Options> parse(int argc, char** argv) {
    Options opt;
    std::optional<double> equil;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        auto value = [&]() -> std::optional<std::string> {
            if (k + 1 >= argc) {
                std::fprintf(stderr, "gran_bench: %s needs a value\n", a.c_str());
                return std::nullopt;
            }
            return std::string(argv[++k]);
        };
        try {
            if (a == "--quick") {
                opt.quick = true;
            } else if (a == "--shuffle") {
                opt.shuffle = true;
            } else if (a == "--cases") {
                auto v = value();
                if (!v) return std::nullopt;
                for (auto& s : split(*v)) opt.case_filters.push_back(s);
            } else if (a == "--n") {
                auto v = value();
                if (!v) return std::nullopt;
                for (auto& s : split(*v)) {
                    const double x = std::stod(s);  // accepts 1e4
                    if (!(x >= 1)) throw std::invalid_argument(s);
                    opt.sizes.push_back(static_cast<std::size_t>(std::llround(x)));
                }
            } else if (a == "--dimension") {
                auto v = value();
                if (!v) return std::nullopt;
                for (auto& s : split(*v)) {
                    if (s != "2" && s != "3") throw std::invalid_argument(s);
                    opt.dimensions.push_back(std::stoi(s));
                }
            } else if (a == "--packing-fraction") {
                auto v = value();
                if (!v) return std::nullopt;
                for (auto& s : split(*v)) {
                    const double x = std::stod(s);
                    if (!(x > 0 && x <= 0.8)) throw std::invalid_argument(s);
                    opt.packing_fractions.push_back(x);
                }
            } else if (a == "--csv") {
                auto v = value();
                if (!v) return std::nullopt;
                opt.csv = *v;
            } else if (a == "--equil") {
                auto v = value();
                if (!v) return std::nullopt;
                equil = std::stod(*v);
                if (!(*equil >= 0)) throw std::invalid_argument(*v);
            } else if (a == "--cell-layout") {
                auto v = value();
                if (!v) return std::nullopt;
                opt.cell_layout = parse_choice<CellLayout>(*v, {{"auto", CellLayout::automatic},
                                                                {"blocks", CellLayout::blocks},
                                                                {"lists", CellLayout::lists}});
            } else if (a == "--queue") {
                auto v = value();
                if (!v) return std::nullopt;
                opt.queue = parse_choice<QueueLayout>(*v, {{"auto", QueueLayout::automatic},
                                                           {"heap", QueueLayout::heap},
                                                           {"calendar", QueueLayout::calendar}});
            } else if (a == "--slice-entries") {
                auto v = value();
                if (!v) return std::nullopt;
                EventQueue::slice_entries = std::stod(*v);
                if (!(EventQueue::slice_entries > 0)) throw std::invalid_argument(*v);
            } else if (a == "--skin") {
                auto v = value();
                if (!v) return std::nullopt;
                opt.skin = std::stod(*v);
            } else if (a == "--seed") {
                auto v = value();
                if (!v) return std::nullopt;
                opt.seed = std::stoull(*v);
            } else if (a == "-h" || a == "--help") {
                usage(stdout);
                std::exit(0);
            } else {
                std::fprintf(stderr, "gran_bench: unknown argument '%s'\n", a.c_str());
                return std::nullopt;
            }
        } catch (const std::exception&) {
            std::fprintf(stderr, "gran_bench: bad value for %s\n", a.c_str());
            return std::nullopt;
        }
    }
    if (opt.quick) {
        opt.equil_per_particle = 10;
        opt.timed_min = 200'000;
        opt.timed_per_particle = 2;
    }
    if (equil) opt.equil_per_particle = *equil;
    // Above these the hard-sphere (0.545) and hard-disk (~0.72) fluids crystallise: the start
    // would not melt and the rate would be that of a solid.
    for (double phi : opt.packing_fractions) {
        for (int dim : opt.dimensions.empty() ? std::vector<int>{2, 3} : opt.dimensions) {
            if (phi > (dim == 3 ? 0.55 : 0.8)) {
                std::fprintf(stderr,
                             "gran_bench: --packing-fraction %g is above the %dD fluid range "
                             "(up to %g)\n",
                             phi, dim, dim == 3 ? 0.55 : 0.8);
                return std::nullopt;
            }
        }
    }
    return opt;
}

// The cases of the geometries and sizes that pass the filters.
std::vector<Case> select_cases(const Options& opt) {
    std::vector<Case> cases;
    std::vector<std::pair<int, double>> geometries;
    if (!opt.dimensions.empty() && !opt.packing_fractions.empty()) {
        for (int dim : opt.dimensions)
            for (double phi : opt.packing_fractions) geometries.emplace_back(dim, phi);
    } else {
        for (auto g : std::vector<std::pair<int, double>>{
                 {2, 0.1}, {2, 0.5}, {3, 0.1}, {3, 0.2}, {3, 0.3}}) {
            const bool dim_ok = opt.dimensions.empty() ||
                                std::find(opt.dimensions.begin(), opt.dimensions.end(), g.first) !=
                                    opt.dimensions.end();
            const bool phi_ok =
                opt.packing_fractions.empty() ||
                std::find(opt.packing_fractions.begin(), opt.packing_fractions.end(), g.second) !=
                    opt.packing_fractions.end();
            if (dim_ok && phi_ok) geometries.push_back(g);
        }
    }
    const std::vector<std::size_t> default_sizes = {10'000, 100'000};
    for (const auto& [dim, phi] : geometries) {
        for (std::size_t n : opt.sizes.empty() ? default_sizes : opt.sizes) {
            Case c{dim, phi, n};
            bool keep = opt.case_filters.empty();
            for (const auto& f : opt.case_filters)
                keep = keep || c.name().find(f) != std::string::npos;
            if (keep) cases.push_back(c);
        }
    }
    return cases;
}

void print_header(const Options& opt) {
    std::printf("gran_bench: event-driven engine, elastic monodisperse, periodic, one core%s%s\n",
                opt.quick ? " (--quick)" : "", opt.shuffle ? " (--shuffle)" : "");
    std::printf("equilibration %g collisions/particle; timed max(%llu, %g N) collisions\n",
                opt.equil_per_particle, static_cast<unsigned long long>(opt.timed_min),
                opt.timed_per_particle);
    const std::string header = fmt::format(
        "{:<20} {:>3} {:>7} {:>5} {:>12} {:>12} {:>12} {:>8} {:>8} {:>8} {:>7} {:>9} {:>7} {:>9} "
        "{:>9} {:>5} {:>9}",
        "case", "dim", "N", "phi", "coll/s(cpu)", "coll/s(wall)", "events/s", "ev/coll", "cell/col",
        "stale/c", "cpu_s", "dE/E", "B/part", "w/Enskog", "shell/c", "skin", "check");
    std::printf("%s\n", header.c_str());
    std::fflush(stdout);
}

void print_row(const Result& r) {
    const Case& c = r.c;
    std::printf(
        "%s\n",
        fmt::format("{:<20} {:>3} {:>7} {:>5} {:>12.4g} {:>12.4g} {:>12.4g} {:>8.3f} "
                    "{:>8.3f} {:>8.3f} {:>7.2f} {:>9.1e} {:>7.0f} {:>9.4f} {:>9.3f} {:>5.2f} {:>9}",
                    c.name(), c.dim, c.n, c.phi, r.rate_cpu(), r.rate_wall(), r.events_per_s(),
                    r.per_collision(r.delta.events), r.per_collision(r.delta.cell_crossings),
                    r.per_collision(r.delta.stale_events), r.cpu_s, r.energy_rel_err,
                    r.bytes_per_particle, r.omega_over_enskog, r.per_collision(r.delta.shell_exits),
                    r.skin, r.ok ? "ok" : "FAILED")
            .c_str());
    std::fflush(stdout);
}

// How the rate degrades from N = 1e4 to the other sizes, per (dim, phi).
void print_size_ratios(const std::vector<Result>& results) {
    std::map<std::pair<int, double>, std::map<std::size_t, double>> by_geometry;
    for (const auto& r : results) by_geometry[{r.c.dim, r.c.phi}][r.c.n] = r.rate_cpu();
    for (const auto& [g, rates] : by_geometry) {
        const auto base = rates.find(10'000);
        if (base == rates.end()) continue;
        for (const auto& [n, rate] : rates) {
            if (n == 10'000) continue;
            std::printf("ratio vs N=1e4: %dd phi=%g  N=%zu/N=10000 = %.3f (%.4g -> %.4g coll/s)\n",
                        g.first, g.second, n, rate / base->second, base->second, rate);
        }
    }
}

// --csv: false when the file cannot be written.
bool write_csv(const std::string& csv, const std::vector<Result>& results) {
    const std::filesystem::path path(csv);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    if (!out) {
        std::fprintf(stderr, "gran_bench: cannot write %s\n", csv.c_str());
        return false;
    }
    out << "case,engine,dimension,N,packing_fraction,rate,unit\n";
    for (const auto& r : results) {
        out << fmt::format("{},event_driven,{},{},{},{:.0f},collisions/s\n", r.c.name(), r.c.dim,
                           r.c.n, r.c.phi, r.rate_cpu());
    }
    std::printf("wrote %s\n", csv.c_str());
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    gran::use_huge_pages(argv);  // may re-execute this program once (huge_pages.hpp)
    const auto parsed = parse(argc, argv);
    if (!parsed) {
        usage(stderr);
        return 2;
    }
    const Options& opt = *parsed;
    const std::vector<Case> cases = select_cases(opt);
    if (cases.empty()) {
        std::fprintf(stderr, "gran_bench: no case matches the filters\n");
        return 2;
    }
    print_header(opt);
    std::vector<Result> results;
    bool all_ok = true;
    for (const Case& c : cases) {
        Result r = c.dim == 2 ? run_case<2>(c, opt) : run_case<3>(c, opt);
        all_ok = all_ok && r.ok;
        print_row(r);
        results.push_back(r);
    }
    print_size_ratios(results);
    if (!opt.csv.empty() && !write_csv(opt.csv, results)) return 1;
    if (!all_ok) {
        std::fprintf(stderr, "gran_bench: sanity check FAILED (see warnings above)\n");
        return 1;
    }
    return 0;
}
