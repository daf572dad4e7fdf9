// Physics check of the LAMMPS comparison (bench/lammps/README.md): gran's DEM benchmark case
// (bench/bench_dem.cpp: same species, contact table, box, lattice, floor and warm-up) with the
// observables that vibrated_bed.in prints in its "-var sample K" mode, so the two codes can be
// compared on the same numbers:
//   contacts/N  2 x (particle-particle contacts) / N
//   T_z         variance of v_z over the grains
//   <z>         mean height of the grains
// each printed after the warm-up (one snapshot), averaged every K steps over the run that follows
// (the benchmark's timed part), and at its end. Not a benchmark: nothing is timed.
//
//   gran_lammps_observables [--N 1600] [--warmup-periods 2] [--psteps 2e7] [--steps S] [--W 9]
//                           [--sample K]
//
// Not part of the CMake build; bench/lammps/README.md gives the compile line.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "bench/vibrated_bed.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/placement.hpp"
#include "species/contact_laws.hpp"

using namespace gran;

namespace {

struct Observables {
    double contacts = 0, tz = 0, zmean = 0;
};

Observables measure(const DemEngine<3>& e) {
    const auto& p = e.particles();
    const double n = double(p.size());
    Observables o;
    double vz = 0, vz2 = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        vz += p.v[i][2] / n;
        vz2 += p.v[i][2] * p.v[i][2] / n;
        o.zmean += p.r[i][2] / n;
    }
    o.tz = vz2 - vz * vz;
    o.contacts = 2.0 * double(e.counters().active_contacts) / n;
    return o;
}

struct Args {
    std::size_t n = 1600;
    double warmup_periods = 2, psteps = 2e7, W = 9;
    std::uint64_t steps = 0, sample = 10;
};

// False, after a message, on an unknown option or a missing value.
bool parse_args(int argc, char** argv, Args& args) {
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        const char* v = argv[i + 1];
        if (a == "--N") {
            args.n = std::stoul(v);
        } else if (a == "--warmup-periods") {
            args.warmup_periods = std::stod(v);
        } else if (a == "--psteps") {
            args.psteps = std::stod(v);
        } else if (a == "--steps") {
            args.steps = std::stoull(v);
        } else if (a == "--W") {
            args.W = std::stod(v);
        } else if (a == "--sample") {
            args.sample = std::max<std::uint64_t>(1, std::stoull(v));
        } else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            return false;
        }
    }
    if (argc % 2 == 0) {
        std::fprintf(stderr,
                     "usage: %s [--N n] [--warmup-periods P] [--psteps X] [--steps S] [--W W] "
                     "[--sample K]\n",
                     argv[0]);
        return false;
    }
    return true;
}

// The run that follows the warm-up (the benchmark's timed part): averages every `sample` steps,
// then the state at its end.
void timed_run(DemEngine<3>& e, std::size_t n, std::uint64_t steps, std::uint64_t sample) {
    Observables sum;
    std::uint64_t samples = 0;
    const std::uint64_t rebuilds0 = e.counters().rebuilds;
    for (std::uint64_t k = 1; k <= steps; ++k) {
        e.step();
        if (k % sample == 0) {
            const Observables o = measure(e);
            sum.contacts += o.contacts;
            sum.tz += o.tz;
            sum.zmean += o.zmean;
            ++samples;
        }
    }
    const double m = double(samples);
    std::printf(
        "gran: timed-run averages every %llu steps: contacts/N %.4f T_z %.4f <z> %.4f "
        "(rebuilds/step "
        "%.4f)\n",
        static_cast<unsigned long long>(sample), sum.contacts / m, sum.tz / m, sum.zmean / m,
        double(e.counters().rebuilds - rebuilds0) / double(steps));
    const Observables o = measure(e);
    std::printf(
        "gran: timed %llu steps with %zu grains; at the end: contacts/N %.4f T_z %.4f <z> %.4f\n",
        static_cast<unsigned long long>(steps), n, o.contacts, o.tz, o.zmean);
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parse_args(argc, argv, args)) return 2;
    const std::size_t n = args.n;

    // The system of bench/bench_dem.cpp (bench/vibrated_bed.hpp).
    const double period = gran::bench::kBedPeriod;
    const double width = gran::bench::bed_width(n);
    const SpeciesTable table = gran::bench::bed_species(n);
    const ContactTable contacts = gran::bench::bed_contacts(table);
    DemEngine<3> e = gran::bench::vibrated_bed(table, contacts, n, args.W);
    e.advance(args.warmup_periods * period);
    const std::uint64_t warm_steps = e.counters().steps;
    const std::uint64_t warm_rebuilds = e.counters().rebuilds;

    // The dashpots of Eq. A9 for the grain pair (m_eff = 1/2) and the floor (m_eff = 1).
    const double t_c = contacts.law->soft_contact->duration(*contacts.table, 0);
    const double c_n = gran::linear_damping_from_restitution(2e5, 0.5, 0.9);
    const double c_n_wall = gran::linear_damping_from_restitution(2e5, 1.0, 0.9);
    std::printf(
        "gran: N %zu width %.6g dt %.15g t_c %.15g c_n %.15g (wall %.15g) c_t %.6g (wall %.6g)\n",
        n, width, e.dt(), t_c, c_n, c_n_wall, 20.0, 20.0);
    const Observables o = measure(e);
    std::printf(
        "gran: after a warm-up of %llu steps: contacts/N %.4f T_z %.4f <z> %.4f (rebuilds/step "
        "%.4f)\n",
        static_cast<unsigned long long>(warm_steps), o.contacts, o.tz, o.zmean,
        double(warm_rebuilds) / double(warm_steps));

    std::uint64_t steps = args.steps;
    if (steps == 0) {
        steps = static_cast<std::uint64_t>(std::max(1000.0, std::ceil(args.psteps / double(n))));
    }
    // As vibrated_bed.in's sample mode.
    steps = args.sample * ((steps + args.sample - 1) / args.sample);
    timed_run(e, n, steps, args.sample);
    return 0;
}
