#pragma once
// Initial configurations generated from the scene: random non-overlapping placement or a lattice
// (registered as placement plugins, libgran/plugins/placement.hpp), and Maxwellian velocities with
// zero total momentum. Placements leave angular velocities unallocated; a scene whose contacts
// need them allocates them before drawing velocities.
#include <stdexcept>
#include <string>

#include "libgran/core/box.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/core/random.hpp"
#include "libgran/core/species.hpp"

namespace gran {

class PlacementError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Densest packing fraction of equal disks (hexagonal, pi/sqrt(12)) and spheres (pi/sqrt(18)).
double max_packing_fraction(int d);
// Packing fraction of the species in the box.
template <int D>
double packing_fraction(const Box<D>& box, const SpeciesTable& table);

// Random sequential insertion (largest particles first); throws PlacementError when a particle
// cannot be placed after `attempts` tries.
template <int D>
Particles<D> place_random(const Box<D>& box, const SpeciesTable& table, Rng& rng,
                          std::size_t attempts = 100000);
// Simple square/cubic lattice with spacing >= largest diameter; species shuffled over sites.
template <int D>
Particles<D> place_lattice(const Box<D>& box, const SpeciesTable& table, Rng& rng);
// Hexagonal (2D) or fcc (3D) lattice stretched to the box, up to the densest packing; vacancies
// (sites beyond n) spread evenly, species shuffled over the particles (close_packed_placement.cpp).
template <int D>
Particles<D> place_close_packed(const Box<D>& box, const SpeciesTable& table, Rng& rng);

// Gaussian velocities (and angular velocities if allocated) at temperature T for every species,
// total momentum removed, then rescaled so the total translational temperature is exactly T.
template <int D>
void maxwellian_velocities(Particles<D>& p, const SpeciesTable& table, double T, Rng& rng);

// A vibrated-bed start (tests and benchmarks of the DEM engine): n grains of diameter 1 on a square
// lattice of spacing 1.2 filling a periodic 3D column of width `width` layer by layer from height
// z0, with small random velocities (uniform in +-0.05) and no centre-of-mass motion.
Particles<3> vibrated_bed_lattice(std::size_t n, double width, double z0, std::uint64_t seed);

}  // namespace gran
