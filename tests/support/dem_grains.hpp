#pragma once
// Grains, boxes and contact tables shared by the DEM engine's tests of single collisions
// (test_dem_engine.cpp) and of many grains (test_dem_many_grains.cpp).
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "libgran/engines/dem/engine.hpp"
#include "tests/support/contacts.hpp"

namespace gran::testing::dem {

constexpr double kPi = std::numbers::pi;

inline Species make_species(const std::string& name, double mass, double diameter, double q,
                            std::size_t count) {
    Species s;
    s.name = name;
    s.mass = mass;
    s.diameter = diameter;
    s.inertia_factor = q;
    s.count = count;
    return s;
}

inline SpeciesTable table_of(std::vector<Species> species) {
    SpeciesTable t;
    t.species = std::move(species);
    return t;
}

// Soft contacts of `law` with the keys `keys` (the body of a YAML map) for every contact and
// `walls` (likewise) for grain-wall contacts (empty: the same as the grains'). The one wall
// partner is the box's (index 0).
inline ContactTable soft(const SpeciesTable& t, const std::string& law, const std::string& keys,
                         const std::string& walls = "") {
    std::string yaml = "{law: " + law + ", " + keys;
    if (!walls.empty()) yaml += ", walls: {" + walls + "}";
    return testing::contacts_of(t, yaml + "}");
}

inline double duration(const ContactTable& c, std::size_t index) {
    return c.law->soft_contact->duration(*c.table, index);
}

template <int D>
Box<D> make_box(double length, bool periodic, double height = 0) {
    Box<D> box;
    box.length = Vec<D>::Constant(length);
    box.periodic.fill(periodic);
    if (height > 0) {
        box.length[D - 1] = height;
        box.periodic[D - 1] = false;
    }
    return box;
}

template <int D>
Vec<D> momentum(const DemEngine<D>& e) {
    Vec<D> p = Vec<D>::Zero();
    const auto& ps = e.particles();
    for (std::size_t i = 0; i < ps.size(); ++i) p += e.species_mass(ps.species[i]) * ps.v[i];
    return p;
}

inline std::string sci(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", x);
    return buf;
}

}  // namespace gran::testing::dem
