#pragma once
// Species (name, mass, diameter, count, inertia factor) and the per-pair coefficients of the
// hard-particle pair laws.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/params.hpp"
#include "species/impact_restitution.hpp"

namespace gran {

struct Species {
    std::string name;
    double mass = 1;
    double diameter = 1;
    double inertia_factor = 0.5;  // I = q m sigma^2 / 4
    std::size_t count = 0;
};

// Coefficients of one unordered species pair.
struct PairCoefficients {
    std::string law = "constant_restitution";
    double alpha = 1;  // normal restitution, (0, 1]
    double beta = -1;  // tangential restitution, [-1, 1]; -1 = smooth
    // Normal restitution as a function of the impact speed; `alpha` is its nominal value (used by
    // kinetic-theory estimates). Constant laws set both.
    ImpactRestitution restitution = constant_impact_restitution(1.0);
};

struct SpeciesTable {
    std::vector<Species> species;
    std::vector<PairCoefficients> pairs;  // ns x ns, symmetric

    std::size_t size() const { return species.size(); }
    std::size_t total_count() const;
    double max_diameter() const;
    const PairCoefficients& pair(std::size_t a, std::size_t b) const {
        return pairs[a * size() + b];
    }
    PairCoefficients& pair(std::size_t a, std::size_t b) { return pairs[a * size() + b]; }
    // True when some pair has beta != -1: only then are angular velocities allocated.
    bool rough() const;
    std::size_t index_of(const std::string& name) const;  // size() if absent
};

Schema species_schema();
// The interactions section's own keys; the parameters of its law join them.
Schema interactions_schema();
Schema pair_override_schema();

// Parses the `species` list and the `interactions` section. `total_particles` (>0) resolves
// number_fraction entries. Resolved YAML (defaults, counts) is stored into `resolved_species` and
// `resolved_interactions`.
SpeciesTable read_species(const YAML::Node& species, const YAML::Node& interactions,
                          std::int64_t total_particles, const Where& where,
                          YAML::Node& resolved_species, YAML::Node& resolved_interactions);

}  // namespace gran
