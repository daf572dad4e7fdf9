#include "libgran/scene/species.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "libgran/core/h5.hpp"

namespace gran {

Schema species_schema() {
    return {
        text("name", "", "name of the species (used in results and pair overrides)"),
        real("mass", "1", "mass", "particle mass", 0, 1e308, true),
        real("diameter", "1", "length", "particle diameter sigma", 0, 1e308, true),
        optional(integer("count", "", "number of particles of this species", 1, 1e9)),
        optional(real("number_fraction", "", "",
                      "fraction of `particles` (scene key) in this species", 0, 1, true, false)),
        optional(real("inertia_factor", "", "",
                      "q in I = q m sigma^2/4 (default 1/2 for disks, 2/5 for spheres)", 0, 1, true,
                      false)),
    };
}

SpeciesTable read_species(const YAML::Node& species, std::int64_t total_particles, int dimension,
                          const Where& where, YAML::Node& resolved_species) {
    SpeciesTable table;
    const Where ws = where.child("species");
    if (!species.IsDefined() || !species.IsSequence() || species.size() == 0) {
        fail(ws, species.IsDefined() ? species : YAML::Node(),
             "expected a non-empty list of species (each with name, mass, diameter, count)");
    }
    resolved_species = YAML::Node(YAML::NodeType::Sequence);
    double fraction_sum = 0;
    bool any_fraction = false;
    for (std::size_t k = 0; k < species.size(); ++k) {
        const Where wk = ws.item(k);
        Params p = read_params(species[k], species_schema(), wk);
        Species s;
        s.name = p.str("name");
        if (s.name.empty()) p.fail("name", "expected a non-empty species name");
        if (const std::string why = h5::name_problem(s.name); !why.empty())
            p.fail("name", "species name '" + s.name + "' cannot name a result group: " + why);
        if (table.index_of(s.name) != table.size())
            p.fail("name", "species name '" + s.name + "' is used twice");
        s.mass = p.real("mass");
        s.diameter = p.real("diameter");
        s.inertia_factor =
            p.has("inertia_factor") ? p.real("inertia_factor") : 0;  // 0: set by dimension
        if (p.has("count") == p.has("number_fraction")) {
            p.fail("", "give exactly one of 'count' or 'number_fraction'");
        }
        if (p.has("count")) {
            s.count = static_cast<std::size_t>(p.integer("count"));
        } else {
            any_fraction = true;
            if (total_particles <= 0) {
                p.fail("number_fraction",
                       "number_fraction needs the scene key 'particles' (total number)");
            }
            fraction_sum += p.real("number_fraction");
            s.count = static_cast<std::size_t>(
                std::llround(p.real("number_fraction") * double(total_particles)));
            if (s.count == 0)
                p.fail("number_fraction", "this fraction of `particles` rounds to zero particles");
        }
        table.species.push_back(s);
        resolved_species.push_back(p.resolved());
    }
    if (any_fraction) {
        for (std::size_t k = 0; k < species.size(); ++k) {
            if (child(species[k], "count").IsDefined()) {
                fail(
                    ws.item(k), species[k],
                    "give either 'count' for every species or 'number_fraction' for every species");
            }
        }
        if (std::abs(fraction_sum - 1.0) > 1e-9) {
            fail(ws, species,
                 fmt::format("number fractions add up to {:g}, expected 1", fraction_sum));
        }
        // Rounding can leave the total off by a few: the last species absorbs the difference.
        const auto diff = total_particles - std::int64_t(table.total_count());
        table.species.back().count = std::size_t(std::int64_t(table.species.back().count) + diff);
        if (table.species.back().count == 0)
            fail(ws, species, "number fractions leave the last species empty");
    }
    // The resolved scene gives counts only (number fractions are resolved), so it reruns exactly.
    for (std::size_t k = 0; k < table.size(); ++k) {
        Species& s = table.species[k];
        if (s.inertia_factor == 0) s.inertia_factor = dimension == 2 ? 0.5 : 0.4;
        resolved_species[k].remove("number_fraction");
        resolved_species[k]["count"] = s.count;
        resolved_species[k]["inertia_factor"] = s.inertia_factor;
    }

    return table;
}

}  // namespace gran
