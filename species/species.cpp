#include "species/species.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "species/pair_law.hpp"

namespace gran {

std::size_t SpeciesTable::total_count() const {
    std::size_t n = 0;
    for (const auto& s : species) n += s.count;
    return n;
}

double SpeciesTable::max_diameter() const {
    double d = 0;
    for (const auto& s : species) d = std::max(d, s.diameter);
    return d;
}

bool SpeciesTable::rough() const {
    return std::any_of(pairs.begin(), pairs.end(),
                       [](const PairCoefficients& c) { return c.beta != -1.0; });
}

std::size_t SpeciesTable::index_of(const std::string& name) const {
    for (std::size_t k = 0; k < species.size(); ++k) {
        if (species[k].name == name) return k;
    }
    return species.size();
}

Schema species_schema() {
    return {
        text("name", "", "name of the species (used in results and pair overrides; unique)"),
        real("mass", "1", "mass", "particle mass", 0, 1e308, true),
        real("diameter", "1", "length", "particle diameter sigma", 0, 1e308, true),
        optional(integer("count", "",
                         "number of particles of this species (give count for every species, "
                         "or number_fraction for every species)",
                         1, 1e9)),
        optional(real("number_fraction", "", "",
                      "fraction of `particles` (scene key) in this species; the fractions must add "
                      "up to 1",
                      0, 1, true, false)),
        optional(real("inertia_factor", "", "",
                      "q in I = q m sigma^2/4 (default 1/2 for disks, 2/5 for spheres)", 0, 1, true,
                      false)),
    };
}

Schema interactions_schema() {
    ParamSpec pairs;
    pairs.name = "pairs";
    pairs.type = ParamType::List;
    pairs.optional = true;
    pairs.doc = "per-pair overrides: a list of {between: [a, b], <law parameters>}";
    return {text("law", "constant_restitution", "default pair law of every pair"), pairs};
}

Schema pair_override_schema() {
    ParamSpec between;
    between.name = "between";
    between.type = ParamType::StringList;
    between.length = 2;
    between.doc = "the two species names of the pair, e.g. [heavy, light]";
    return {between,
            optional(text("law", "", "pair law for this pair (default: the interactions' law)"))};
}

namespace {

const PairLaw& find_law(const std::string& name, const Where& w, const YAML::Node& n) {
    const PairLaw* law = PairLawRegistry::instance().find(name);
    if (!law) {
        std::string names;
        for (const auto& s : PairLawRegistry::instance().names())
            names += (names.empty() ? "" : ", ") + s;
        fail(w, n, fmt::format("unknown pair law '{}'; known laws: {}", name, names));
    }
    return *law;
}

}  // namespace

SpeciesTable read_species(const YAML::Node& species, const YAML::Node& interactions,
                          std::int64_t total_particles, const Where& where,
                          YAML::Node& resolved_species, YAML::Node& resolved_interactions) {
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
        resolved_species[k].remove("number_fraction");
        resolved_species[k]["count"] = table.species[k].count;
    }

    // Interactions: a default law with its parameters, plus per-pair overrides.
    const Where wi = where.child("interactions");
    if (interactions.IsDefined() && !interactions.IsNull() && !interactions.IsMap()) {
        fail(wi, interactions, "expected a map (law, its parameters, pairs)");
    }
    const YAML::Node law_node = child(interactions, "law");
    if (law_node.IsDefined() && !law_node.IsScalar())
        fail(wi.child("law"), law_node, "expected the name of a pair law");
    const std::string law_name =
        law_node.IsDefined() ? law_node.as<std::string>() : "constant_restitution";
    const PairLaw& law = find_law(law_name, wi.child("law"), law_node);
    Schema schema = law.schema;
    for (const auto& spec : interactions_schema()) schema.push_back(spec);
    Params ip = read_params(interactions, schema, wi);
    PairCoefficients base;
    base.law = law_name;
    law.apply(ip, base);
    const std::size_t ns = table.size();
    table.pairs.assign(ns * ns, base);
    resolved_interactions = ip.resolved();
    if (ip.has("pairs")) {
        const YAML::Node pairs = child(interactions, "pairs");
        YAML::Node resolved_pairs(YAML::NodeType::Sequence);
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            const Where wk = wi.child("pairs").item(k);
            const YAML::Node entry = pairs[k];
            const YAML::Node pl_node = child(entry, "law");
            if (pl_node.IsDefined() && !pl_node.IsScalar())
                fail(wk.child("law"), pl_node, "expected the name of a pair law");
            const std::string pl_name = pl_node.IsDefined() ? pl_node.as<std::string>() : law_name;
            const PairLaw& pl = find_law(pl_name, wk.child("law"), pl_node);
            Schema ps = pair_override_schema();
            ps.insert(ps.end(), pl.schema.begin(), pl.schema.end());
            // Parameters not given for the pair default to the interactions' values of the same
            // law.
            if (pl_name == law_name) {
                for (auto& spec : ps) {
                    if (ip.resolved()[spec.name] && spec.name != "law" && spec.name != "pairs") {
                        spec.default_value = ip.resolved()[spec.name].Scalar();
                    }
                }
            }
            Params pp = read_params(entry, ps, wk);
            const auto names = pp.strings("between");
            std::size_t a = table.index_of(names[0]);
            std::size_t b = table.index_of(names[1]);
            if (a == ns || b == ns) {
                pp.fail("between",
                        fmt::format("unknown species '{}'", a == ns ? names[0] : names[1]));
            }
            PairCoefficients c;
            c.law = pl_name;
            pl.apply(pp, c);
            table.pair(a, b) = c;
            table.pair(b, a) = c;
            YAML::Node r = pp.resolved();
            r["law"] = pl_name;
            resolved_pairs.push_back(r);
        }
        resolved_interactions["pairs"] = resolved_pairs;
    }
    return table;
}

}  // namespace gran
