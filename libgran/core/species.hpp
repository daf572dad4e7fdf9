#pragma once
// The species of a scene: name, mass, diameter, count and inertia factor of each kind of grain.
// How two species (or a species and a wall) interact is not a property of either: it lives in the
// scene's `interactions` (libgran/plugins/law.hpp, libgran/scene/interactions.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace gran {

struct Species {
    std::string name;
    double mass = 1;
    double diameter = 1;
    double inertia_factor = 0.5;  // q in I = q m sigma^2 / 4
    std::size_t count = 0;
};

struct SpeciesTable {
    std::vector<Species> species;

    std::size_t size() const { return species.size(); }
    std::size_t total_count() const {
        std::size_t n = 0;
        for (const auto& s : species) n += s.count;
        return n;
    }
    double max_diameter() const {
        double d = 0;
        for (const auto& s : species) d = d > s.diameter ? d : s.diameter;
        return d;
    }
    double min_mass() const {
        double m = species.empty() ? 0 : species.front().mass;
        for (const auto& s : species) m = m < s.mass ? m : s.mass;
        return m;
    }
    // Moment of inertia I = q m sigma^2 / 4 of one grain of species s.
    double inertia(std::size_t s) const {
        const Species& sp = species[s];
        return sp.inertia_factor * sp.mass * sp.diameter * sp.diameter / 4;
    }
    std::size_t index_of(const std::string& name) const {  // size() if absent
        for (std::size_t k = 0; k < species.size(); ++k) {
            if (species[k].name == name) return k;
        }
        return species.size();
    }
};

}  // namespace gran
