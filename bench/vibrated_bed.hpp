#pragma once
// The 3D vibrated bed of the DEM benchmarks (Bhateja et al. 2016 parameters in units m = d = g =
// 1): n grains (q = 0.4) in a periodic column 5 sqrt(n/100) wide (4 layers), k_n = 2e5 m g / d, e =
// 0.9, mu = 0.4, gamma_t = 20, open top, floor A sin(omega t) with A = d and W = (A omega)^2 (W =
// 0: static floor). Shared by bench/bench_dem.cpp and the LAMMPS comparison
// (bench/lammps/gran_observables.cpp) so both time the same system.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>

#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/interactions.hpp"
#include "libgran/scene/placement.hpp"

namespace gran::bench {

inline double bed_width(std::size_t n) {
    return 5.0 * std::sqrt(double(n) / 100.0);
}
// Period of the W = 9 drive (warm-up lengths are counted in it whatever W is).
inline constexpr double kBedPeriod = 2 * std::numbers::pi / 3.0;

inline SpeciesTable bed_species(std::size_t n) {
    SpeciesTable table;
    Species s;
    s.name = "grain";
    s.count = n;
    s.inertia_factor = 0.4;
    table.species.push_back(s);
    return table;
}

// k_n = 2e5 m g / d, e = 0.9, mu = 0.4, c_t = 20 for grains and floor (the wall partner `box`).
inline ContactTable bed_contacts(const SpeciesTable& table) {
    YAML::Node resolved;
    return read_interactions(
        YAML::Load("{law: linear_dashpot, stiffness: 2.0e+5, restitution: 0.9, friction: 0.4, "
                   "tangential_damping: 20}"),
        table, {"box"}, {3, 1.0, table.min_mass()}, {"bench", ""}, resolved);
}

// The engine for the bed: keep `table` and `contacts` alive as long as it.
inline DemEngine<3> vibrated_bed(const SpeciesTable& table, const ContactTable& contacts,
                                 std::size_t n, double W, int threads = 1,
                                 std::int64_t sort_interval = -1) {
    const double width = bed_width(n);
    Box<3> box;
    box.length = Vec<3>(width, width, 80);
    box.periodic = {true, true, false};
    DemSettings settings;
    settings.gravity = {0, 0, -1};
    settings.threads = threads;
    if (sort_interval >= 0) {  // -1: the engine's defaults
        settings.sort_interval = std::uint64_t(sort_interval);
        settings.min_particles_to_sort = 0;
    }
    DemEngine<3> e(box, table, contacts, vibrated_bed_lattice(n, width, 3.0, 1), settings);
    e.remove_wall(2, 1);
    if (W > 0) e.set_wall(2, 0, WallMotion::sinusoid(1.0, std::sqrt(W)), 0);
    return e;
}

}  // namespace gran::bench
