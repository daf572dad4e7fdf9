#include "libgran/scene/interactions.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace gran {

namespace {

constexpr const char* kDefaultLaw = "constant_restitution";

const LawPlugin& find_law(const std::string& name, const Where& w, const YAML::Node& n) {
    const LawPlugin* law = LawRegistry::instance().find(name);
    if (!law) {
        fail(
            w, n,
            fmt::format("unknown law '{}'; known laws: {}", name, LawRegistry::instance().names()));
    }
    return *law;
}

// The law a level names (`law: ...`), or `fallback`.
const LawPlugin& law_of(const YAML::Node& section, const std::string& fallback, const Where& w) {
    const YAML::Node n = child(section, "law");
    if (n.IsDefined() && !n.IsScalar()) fail(w.child("law"), n, "expected the name of a law");
    return find_law(n.IsDefined() ? n.as<std::string>() : fallback, w.child("law"), n);
}

// The law's keys with the values of `from` as defaults (a level inheriting from the one above).
Schema inheriting(const LawPlugin& law, const std::optional<Params>& from, Schema extra) {
    Schema s = law.schema;
    if (from) {
        for (auto& spec : s) {
            const YAML::Node v = child(from->resolved(), spec.name);
            if (v.IsDefined() && v.IsScalar()) spec.default_value = v.Scalar();
        }
    }
    s.insert(s.end(), extra.begin(), extra.end());
    return s;
}

// The law and parameters of one level (defaults, walls) or one contact.
struct Level {
    const LawPlugin* law = nullptr;
    Params params;
};

std::optional<Params> same_law(const Level& above, const LawPlugin& law) {
    if (above.law == &law) return above.params;
    return std::nullopt;
}

YAML::Node resolved_keys(const Level& l) {
    YAML::Node r(YAML::NodeType::Map);
    r["law"] = l.law->name;
    for (const auto& spec : l.law->schema) {
        const YAML::Node v = child(l.params.resolved(), spec.name);
        if (v.IsDefined() && !v.IsNull()) r[spec.name] = v;
    }
    return r;
}

ContactPartner species_partner(const Species& s) {
    return {s.name, s.mass, s.diameter, s.inertia_factor, false};
}
ContactPartner wall_partner(const std::string& name) {
    return {name, std::numeric_limits<double>::infinity(), 0.0, 0.0, true};
}

// Every contact's level: pairs of contact classes (nc x nc) then walls (nw x ns), as
// ContactTable indexes. Levels are referred to, never assigned: a yaml-cpp node assigned to
// another rebinds the node it shares with its copies, so copying a Params and assigning over it
// would change the original.
struct Contacts {
    std::size_t ns = 0, nw = 0, nc = 0;   // species, wall partners, contact classes
    std::vector<std::uint32_t> class_of;  // per species
    std::vector<std::size_t> first;       // per class: its first species, the one resolved
    std::deque<Level> overrides;
    std::vector<const Level*> levels;
    std::size_t pair(std::size_t a, std::size_t b) const {
        return std::size_t(class_of[a]) * nc + class_of[b];
    }
    std::size_t wall(std::size_t w, std::size_t s) const { return nc * nc + w * ns + s; }
};

// One `pairs` entry as read: its level and partners (i0 a species, i1 a species or a wall).
struct Override {
    const Level* level = nullptr;
    std::size_t i0 = 0, i1 = 0;
    bool wall = false;
};

// Index of a partner name: a species (wall = false) or a wall partner (wall = true).
std::size_t partner_index(const std::string& name, const SpeciesTable& species,
                          const std::vector<std::string>& walls, const Where& w,
                          const YAML::Node& node, bool& wall) {
    const std::size_t s = species.index_of(name);
    if (s < species.size()) {
        wall = false;
        return s;
    }
    const auto it = std::find(walls.begin(), walls.end(), name);
    if (it == walls.end()) {
        std::string known;
        for (const auto& sp : species.species) known += (known.empty() ? "" : ", ") + sp.name;
        for (const auto& wn : walls) known += ", " + wn + " (wall)";
        fail(w, node, fmt::format("unknown partner '{}'; known: {}", name, known));
    }
    wall = true;
    return std::size_t(it - walls.begin());
}

// One `pairs` entry: a species and a species or wall partner, and the contact's level. `given`
// holds the contacts already given (species pairs in order, walls after the species).
Override read_pair(const YAML::Node& entry, const Where& wk, const SpeciesTable& species,
                   const std::vector<std::string>& walls, const Level& defaults,
                   const Level& at_walls, Contacts& c,
                   std::set<std::pair<std::size_t, std::size_t>>& given, YAML::Node& resolved) {
    const YAML::Node between = child(entry, "between");
    if (!entry.IsMap() || !between.IsSequence() || between.size() != 2 || !between[0].IsScalar() ||
        !between[1].IsScalar()) {
        fail(wk.child("between"), between.IsDefined() ? between : entry,
             "expected `between: [a, b]`, two species or a species and a wall partner");
    }
    const std::string n0 = between[0].as<std::string>(), n1 = between[1].as<std::string>();
    bool wall0 = false, wall1 = false;
    std::size_t i0 = partner_index(n0, species, walls, wk.child("between"), between, wall0);
    std::size_t i1 = partner_index(n1, species, walls, wk.child("between"), between, wall1);
    if (wall0 && wall1)
        fail(wk.child("between"), between, "a contact between two walls has no law");
    if (wall0) std::swap(i0, i1);  // i0: the species, i1: the species or wall
    const bool wall = wall0 || wall1;
    const Level& above = wall ? at_walls : defaults;
    const LawPlugin& law = law_of(entry, above.law->name, wk);
    const Level& level = c.overrides.emplace_back(Level{
        &law,
        read_params(entry, inheriting(law, same_law(above, law), pair_override_schema()), wk)});
    const std::pair<std::size_t, std::size_t> key =
        wall ? std::pair{i0, c.ns + i1} : std::pair{std::min(i0, i1), std::max(i0, i1)};
    if (!given.insert(key).second) {
        fail(wk.child("between"), between,
             fmt::format("the contact {}-{} is already given by another entry", n0, n1));
    }
    YAML::Node r = resolved_keys(level);
    r["between"].push_back(n0);
    r["between"].push_back(n1);
    resolved.push_back(r);
    return {&level, i0, i1, wall};
}

// The defaults (law and keys at the top of the section).
Level read_defaults(const YAML::Node& node, const Where& wi) {
    if (node.IsDefined() && !node.IsNull() && !node.IsMap()) {
        fail(wi, node, "expected a map (law, its keys, walls, pairs)");
    }
    const LawPlugin& law = law_of(node, kDefaultLaw, wi);
    return {&law, read_params(node, inheriting(law, std::nullopt, interactions_schema()), wi)};
}

// `walls`: every grain-wall contact; absent, the defaults.
Level read_walls(const YAML::Node& node, const Level& defaults, const Where& ww) {
    if (!node.IsDefined() || node.IsNull()) return defaults;
    if (!node.IsMap()) fail(ww, node, "expected a map: `law` and its keys");
    const LawPlugin& law = law_of(node, defaults.law->name, ww);
    Schema schema = inheriting(law, same_law(defaults, law),
                               {optional(text("law", "", "law of every grain-wall contact"))});
    return {&law, read_params(node, schema, ww)};
}

// The contact classes: a species named in a grain-grain `pairs` entry has a class of its own;
// the others, whose contacts all take the defaults, share a class when they agree in every
// property the default law reads (PartnerProperties). Classes are numbered in order of their first
// species, so a scene whose species all differ keeps the species' order.
void assign_classes(Contacts& c, const SpeciesTable& species, const Level& defaults,
                    const std::vector<Override>& overrides) {
    std::vector<bool> named(c.ns, false);
    for (const Override& o : overrides) {
        if (o.wall) continue;
        named[o.i0] = true;
        named[o.i1] = true;
    }
    const PartnerProperties reads = defaults.law->partner_properties
                                        ? defaults.law->partner_properties(defaults.params)
                                        : PartnerProperties{};
    std::map<std::array<double, 3>, std::uint32_t> shared;
    c.class_of.resize(c.ns);
    for (std::size_t s = 0; s < c.ns; ++s) {
        const Species& sp = species.species[s];
        auto fresh = [&] {
            c.first.push_back(s);
            return std::uint32_t(c.first.size() - 1);
        };
        if (named[s]) {
            c.class_of[s] = fresh();
            continue;
        }
        const std::array<double, 3> key{reads.mass ? sp.mass : 0.0,
                                        reads.diameter ? sp.diameter : 0.0,
                                        reads.inertia_factor ? sp.inertia_factor : 0.0};
        const auto it = shared.find(key);
        c.class_of[s] =
            it != shared.end() ? it->second : shared.emplace(key, fresh()).first->second;
    }
    c.nc = c.first.size();
}

// Every contact's level: the defaults, the walls' level, then the `pairs` entries.
void assign_levels(Contacts& c, const Level& defaults, const Level& at_walls,
                   const std::vector<Override>& overrides) {
    c.levels.assign(c.nc * c.nc, &defaults);
    c.levels.resize(c.nc * c.nc + c.nw * c.ns, &at_walls);
    for (const Override& o : overrides) {
        if (o.wall) {
            c.levels[c.wall(o.i1, o.i0)] = o.level;
        } else {
            c.levels[c.pair(o.i0, o.i1)] = o.level;
            c.levels[c.pair(o.i1, o.i0)] = o.level;
        }
    }
}

// The laws the levels name, in order of first use; several are mixed per contact, which only laws
// with a hard-particle form can be.
std::vector<std::string> laws_of(const Contacts& c) {
    std::vector<std::string> laws;
    for (const Level* l : c.levels) {
        if (std::find(laws.begin(), laws.end(), l->law->name) == laws.end())
            laws.push_back(l->law->name);
    }
    for (const Level* l : c.levels) {
        if (laws.size() > 1 && !l->law->hard_sphere) {
            throw std::invalid_argument(fmt::format(
                "the contacts use the laws {}; only laws with a hard-particle form can be mixed "
                "per contact, and law '{}' has none",
                fmt::join(laws, ", "), l->law->name));
        }
    }
    return laws;
}

// Resolves every contact with its level's law into one table (or the mixed table of several
// hard-sphere laws). A pair of classes is resolved between their first species.
ContactTable resolve_contacts(const Contacts& c, const SpeciesTable& species,
                              const std::vector<std::string>& walls, const LawContext& ctx) {
    ContactTable t;
    t.species = c.ns;
    t.classes = c.nc;
    t.class_of = c.class_of;
    t.walls = walls;
    t.laws = laws_of(c);
    const bool mixed = t.laws.size() > 1;
    t.law = mixed ? &mixed_hard_sphere_law() : c.levels.front()->law;
    auto table = t.law->make_table(c.levels.size());
    const std::size_t pairs = c.nc * c.nc;
    t.nominal_restitution.assign(pairs, 1.0);
    const auto partner = [&](std::size_t k, bool second) {
        if (k < pairs)
            return species_partner(species.species[c.first[second ? k % c.nc : k / c.nc]]);
        const std::size_t wk = k - pairs;
        return second ? wall_partner(walls[wk / c.ns])
                      : species_partner(species.species[wk % c.ns]);
    };
    for (std::size_t k = 0; k < c.levels.size(); ++k) {
        const bool pair = k < pairs;
        if (pair && k % c.nc < k / c.nc && !mixed) {  // (b, a) of a resolved (a, b)
            t.law->copy(*table, k, *table, (k % c.nc) * c.nc + k / c.nc);
        } else {
            const LawPlugin& law = *c.levels[k]->law;
            auto one = law.make_table(1);
            law.resolve(*one, 0, c.levels[k]->params, partner(k, false), partner(k, true), ctx);
            const double nominal = law.nominal_restitution(*one, 0);
            const bool rotates = law.rotates(*one, 0);
            if (mixed) {
                set_mixed_contact(*table, k, *law.hard_sphere, law.hard_sphere->pair_at(*one, 0),
                                  nominal, rotates);
            } else {
                law.copy(*table, k, *one, 0);
            }
        }
        if (pair) t.nominal_restitution[k] = t.law->nominal_restitution(*table, k);
        t.rotating = t.rotating || t.law->rotates(*table, k);
    }
    t.table = std::move(table);
    return t;
}

}  // namespace

Schema interactions_schema() {
    ParamSpec walls;
    walls.name = "walls";
    walls.type = ParamType::Map;
    walls.optional = true;
    walls.doc = "every grain-wall contact: `law` and its keys (default: the values above)";
    ParamSpec pairs;
    pairs.name = "pairs";
    pairs.type = ParamType::List;
    pairs.optional = true;
    pairs.doc =
        "one contact each: {between: [a, b], <law keys>}, a and b two species or a species and a "
        "wall partner (a wall driver's name, or `box` for walls no driver claims)";
    return {text("law", kDefaultLaw, "law of every contact (`gran list laws`)"), walls, pairs};
}

Schema pair_override_schema() {
    ParamSpec between;
    between.name = "between";
    between.type = ParamType::StringList;
    between.length = 2;
    between.doc = "the two partners: species names, or a species and a wall partner";
    return {between, optional(text("law", "", "law of this contact (default: the level above)"))};
}

ContactTable read_interactions(const YAML::Node& node, const SpeciesTable& species,
                               const std::vector<std::string>& wall_partners,
                               const LawContext& context, const Where& where,
                               YAML::Node& resolved) {
    const Where wi = where.child("interactions");
    for (const auto& w : wall_partners) {
        if (species.index_of(w) < species.size()) {
            fail(wi, node,
                 fmt::format("'{}' names both a species and a wall: give the wall driver another "
                             "`name`",
                             w));
        }
    }
    const Level defaults = read_defaults(node, wi);
    const Level at_walls = read_walls(child(node, "walls"), defaults, wi.child("walls"));
    Contacts c;
    c.ns = species.size();
    c.nw = wall_partners.size();
    resolved = resolved_keys(defaults);
    if (child(node, "walls").IsDefined()) resolved["walls"] = resolved_keys(at_walls);
    std::vector<Override> overrides;
    const YAML::Node pairs = child(node, "pairs");
    if (pairs.IsDefined() && !pairs.IsNull()) {
        YAML::Node rp(YAML::NodeType::Sequence);
        std::set<std::pair<std::size_t, std::size_t>> given;
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            overrides.push_back(read_pair(pairs[k], wi.child("pairs").item(k), species,
                                          wall_partners, defaults, at_walls, c, given, rp));
        }
        resolved["pairs"] = rp;
    }
    assign_classes(c, species, defaults, overrides);
    assign_levels(c, defaults, at_walls, overrides);
    try {
        return resolve_contacts(c, species, wall_partners, context);
    } catch (const std::invalid_argument& e) {  // a mixed table of a law without hard form
        fail(wi, node, e.what());
    }
}

}  // namespace gran
