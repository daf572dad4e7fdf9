// Throughput benchmark of the soft-sphere DEM engine: particle-steps per CPU second for the 3D
// vibrated bed of Bhateja, Sharma & Singh 2016 (Sec. III): grains of diameter d and mass m in a
// periodic column of width 5d, 20d and 50d (100, 1600 and 10^4 grains, about four layers), a floor
// vibrated at A sin(omega t) with A = d and W = (A omega)^2 / (d g) = 9, no lid, linear
// spring-dashpot with k_n = 2e5 m g / d, e_p = e_w = 0.9, mu_p = 0.4, dt = t_c / 50. One core,
// plain timers. Units m = d = g = 1.
//
//   gran_bench_dem [--sizes 100,1600,10000] [--warmup-periods P] [--particle-steps X] [--W W]
//                  [--threads T] [--sort-interval S] [--stages] [--csv PATH]
//
// --csv appends one row per size to PATH in the columns of gran_bench's results/bench.csv
// (case,engine,dimension,N,packing_fraction,rate,unit; rate in particle-steps per CPU second),
// writing the header if the file is new.
//
// --threads T runs each step on T threads (DemSettings::threads); the CSV rate is then per
// wall-clock second (unit particle-steps/wall-s, case suffix _T<T>). The last column, a hash of
// the final positions and velocities, is the same for any T: the threads change no bit.
//
// --sort-interval S renumbers the grains in space every S steps whatever N (0: never;
// DemSettings::sort_interval); without it the engine's defaults (every 1000 steps from 8192
// grains on). The state hash is over storage order, so it differs between sort settings.
//
// --stages times the stages of each step (DemEngine::time_stages) and prints, after each size's
// row, their wall-clock nanoseconds per particle-step: the half kicks and the drift, the
// neighbour list (rebuild test, builds, sorts), the grain-grain and the grain-wall contacts, and
// the rest of the timed loop (the clock reads themselves, about five per step, among it). On
// more than one thread a second line says how evenly the work was cut, averaged over the timed
// list builds: the halo grains of the pair shares (their contacts go through per-entry slots)
// and the list search's largest share of work over the mean share. A last line, on any number
// of threads, gives the list search's milliseconds per build: the slowest thread's and all
// threads' together.
//
// --W 0 keeps the floor static: the bed settles during the warm-up (periods of the W = 9 drive)
// and the timed part measures a dense bed at rest (about 6 contacts per grain) instead of the
// dilute fluidised one.
//
// Each case: grains on a square lattice (spacing 1.2 d) from 3 d up, small random velocities,
// `warmup-periods` periods of vibration (fluidisation), then at least `particle-steps`
// particle-steps (and 1000 steps) timed. Prints N, steps, particle-steps per second (CPU and wall),
// neighbour-list rebuilds per step, contacts per grain, T_z and the largest overlap seen.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_clock.hpp"
#include "bench/vibrated_bed.hpp"
#include "libgran/core/huge_pages.hpp"
#include "libgran/core/random.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/placement.hpp"

namespace {

using gran::bench::cpu_seconds;
using gran::bench::wall_seconds;
using namespace gran::bench;

using namespace gran;

struct Options {
    std::vector<std::size_t> sizes{100, 1600, 10000};
    double warmup_periods = 2;
    double particle_steps = 5e7;
    double W = 9;  // (A omega)^2 / (d g); 0: static floor
    int threads = 1;
    std::int64_t sort_interval = -1;  // -1: the engine's default
    bool stages = false;
    std::string csv;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool has_value = i + 1 < argc;
        if (a == "--sizes" && has_value) {
            o.sizes.clear();
            std::stringstream ss(argv[++i]);
            std::string item;
            while (std::getline(ss, item, ',')) o.sizes.push_back(std::stoul(item));
        } else if (a == "--warmup-periods" && has_value) {
            o.warmup_periods = std::stod(argv[++i]);
        } else if (a == "--particle-steps" && has_value) {
            o.particle_steps = std::stod(argv[++i]);
        } else if (a == "--W" && has_value) {
            o.W = std::stod(argv[++i]);
        } else if (a == "--threads" && has_value) {
            o.threads = std::stoi(argv[++i]);
        } else if (a == "--sort-interval" && has_value) {
            o.sort_interval = std::stoll(argv[++i]);
        } else if (a == "--stages") {
            o.stages = true;
        } else if (a == "--csv" && has_value) {
            o.csv = argv[++i];
        } else {
            std::fprintf(stderr,
                         "usage: %s [--sizes 100,1600,10000] [--warmup-periods P] "
                         "[--particle-steps X] [--W W] [--threads T] [--sort-interval S] "
                         "[--stages] [--csv PATH]\n",
                         argv[0]);
            std::exit(2);
        }
    }
    return o;
}

// FNV-1a over the bits of every position and velocity: equal hashes, equal states.
std::uint64_t state_hash(const Particles<3>& ps) {
    std::uint64_t h = 1469598103934665603ull;
    const auto mix = [&](const std::vector<Vec<3>>& xs) {
        for (const Vec<3>& x : xs) {
            for (int a = 0; a < 3; ++a) {
                std::uint64_t bits = 0;
                std::memcpy(&bits, &x[a], sizeof bits);
                for (int b = 0; b < 8; ++b) {
                    h ^= (bits >> (8 * b)) & 0xffu;
                    h *= 1099511628211ull;
                }
            }
        }
    };
    mix(ps.r);
    mix(ps.v);
    return h;
}

// The stages' wall-clock nanoseconds per particle-step, and the share of the timed loop.
void print_stages(const DemStageTimes& t, double wall, double psteps) {
    const double ns = 1e9 / psteps;
    std::printf(
        "# stages, ns per particle-step: kicks+drift %.2f, list %.2f, pairs %.2f, walls %.2f, "
        "rest %.2f (of %.2f)\n",
        t.kicks_and_drift * ns, t.neighbour_list * ns, t.pair_contacts * ns, t.wall_contacts * ns,
        (wall - t.total()) * ns, wall * ns);
}

// How evenly the threads' work was cut (threaded runs): the halo grains of the pair shares and
// the list search's largest share over the mean, averaged over the timed list builds.
void print_shares(const DemThreadShares& s) {
    if (s.splits == 0 || s.searches == 0) return;
    std::printf(
        "# thread shares, mean of %llu list builds: halo grains %.0f (%.2f%% of N), "
        "search work max / mean %.3f\n",
        static_cast<unsigned long long>(s.splits), s.halo_grains / double(s.splits),
        100.0 * s.halo_grains / s.grains, s.search_imbalance / double(s.searches));
}

// The list search's wall-clock milliseconds per build (any thread count): the slowest thread's
// and all threads' together, averaged over the timed builds. On two threads of equal speed
// that scale perfectly, the slowest thread's time is half the one-thread search's and all
// threads together take as long as one thread alone.
void print_search(const DemThreadShares& s) {
    if (s.timed_searches == 0) return;
    const double per = 1e3 / double(s.timed_searches);
    std::printf(
        "# list search, ms per build (%llu builds): slowest thread %.3f, all threads %.3f\n",
        static_cast<unsigned long long>(s.timed_searches), s.search_slowest * per,
        s.search_all * per);
}

}  // namespace

int main(int argc, char** argv) {
    gran::use_huge_pages(argv);  // may re-execute this program once (huge_pages.hpp)
    const Options opt = parse(argc, argv);
    const double period = kBedPeriod;
    std::printf("%8s %6s %10s %14s %14s %10s %10s %8s %10s %18s\n", "N", "width", "steps",
                "psteps/s_cpu", "psteps/s_wall", "rebuild/st", "contacts/N", "T_z", "max_ovl",
                "state_hash");
    for (std::size_t n : opt.sizes) {
        const double width = bed_width(n);
        const SpeciesTable table = bed_species(n);
        const ContactTable contacts = bed_contacts(table);
        DemEngine<3> e = vibrated_bed(table, contacts, n, opt.W, opt.threads, opt.sort_interval);
        e.advance(opt.warmup_periods * period);

        const auto steps =
            static_cast<std::uint64_t>(std::max(1000.0, std::ceil(opt.particle_steps / double(n))));
        const DemCounters before = e.counters();
        e.time_stages(opt.stages);
        const double c0 = cpu_seconds(), w0 = wall_seconds();
        e.steps(steps);  // fused, as advance() steps
        const std::uint64_t contact_sum =
            e.counters().active_contact_steps - before.active_contact_steps;
        const double cpu = cpu_seconds() - c0, wall = wall_seconds() - w0;
        const auto& ps = e.particles();
        double mean = 0, tz = 0;
        for (const auto& v : ps.v) mean += v[2] / double(n);
        for (const auto& v : ps.v) tz += (v[2] - mean) * (v[2] - mean) / double(n);
        const double psteps = double(steps) * double(n);
        std::printf("%8zu %6.1f %10llu %14.4g %14.4g %10.4f %10.3f %8.3f %10.3g %18llx\n", n, width,
                    static_cast<unsigned long long>(steps), psteps / cpu, psteps / wall,
                    double(e.counters().rebuilds - before.rebuilds) / double(steps),
                    2.0 * double(contact_sum) / (double(steps) * double(n)), tz,
                    e.counters().max_overlap, static_cast<unsigned long long>(state_hash(ps)));
        if (opt.stages) {
            print_stages(e.stage_times(), wall, psteps);
            print_shares(e.thread_shares());
            print_search(e.thread_shares());
        }
        std::fflush(stdout);
        if (!opt.csv.empty()) {
            const bool fresh = !std::ifstream(opt.csv).good();
            std::ofstream out(opt.csv, std::ios::app);
            if (!out) {
                std::fprintf(stderr, "gran_bench_dem: cannot write %s\n", opt.csv.c_str());
                return 1;
            }
            if (fresh) out << "case,engine,dimension,N,packing_fraction,rate,unit\n";
            // packing fraction: grains over the bed volume at rest (four layers), as N/(W^2 4d)
            const double phi = double(n) * std::numbers::pi / 6 / (width * width * 4.0);
            const bool threaded = opt.threads > 1;
            out << "3d_vibrated_bed_W" << opt.W << "_N" << n
                << (threaded ? "_T" + std::to_string(opt.threads) : std::string()) << ",dem,3," << n
                << "," << phi << "," << static_cast<long long>(psteps / (threaded ? wall : cpu))
                << (threaded ? ",particle-steps/wall-s\n" : ",particle-steps/s\n");
        }
    }
    return 0;
}
