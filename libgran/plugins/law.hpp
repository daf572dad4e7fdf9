#pragma once
// Interaction laws as types (issue 12). A law is one file in species/ holding
//   - its parameter struct `Pair`: everything its kernel reads for one contact, resolved once;
//   - its schema (the keys of `interactions`, of `interactions.walls` and of a `pairs` entry);
//   - `resolve(params, a, b, context)`: the Pair of one contact from its two partners (two species,
//     or a species and a wall), e.g. a damping from a restitution and the reduced mass;
//   - its kernel as a plain function: for hard particles the normal and tangential restitution of
//     one collision (event-driven engine), for soft particles the contact force (DEM engine);
// and one registration, `register_law<L>(...)` (libgran/engines/register_law.hpp), which puts the
// law in Registry<LawPlugin> and instantiates the engine loops templated on it. Nothing else is
// edited to add a law: no enum of law kinds, no switch.
//
// A law may have a hard-sphere form, a soft-contact form or both: the soft-contact laws also run
// on the event-driven engine as their hard limit (instantaneous collisions with the requested
// restitution) when they are frictionless, which is how one scene runs on both engines.
//
// Interfaces a law type L provides (checked by the concepts below):
//   struct Pair;                              trivially copyable
//   static Pair resolve(const Params&, const ContactPartner&, const ContactPartner&,
//                       const LawContext&);   refuses with params.fail(key, why)
//   static double nominal_restitution(const Pair&);   e.g. for the Enskog equation of state
//   static bool rotates(const Pair&);         the contact needs angular velocities
//   static PartnerProperties partner_properties(const Params&);   optional: what of a species
//                                             partner resolve() reads (default: all of it)
// hard-sphere form:
//   static constexpr bool impact_dependent;   the restitution depends on the impact speed
//   static double normal_restitution(const Pair&, double impact_speed);  alpha (sign ignored)
//   static double tangential_restitution(const Pair&);                  beta, -1 = smooth
// soft-contact form (libgran/engines/dem/contact_force.hpp):
//   static constexpr bool history;            one tangential spring per contact
//   template <int D> static ContactForce<D> force(const Pair&, double delta, const Vec<D>& n,
//                                                 const Vec<D>& g, double l_i, double l_j,
//                                                 Vec<D>& spring);
//   static double elastic_energy(const Pair&, double delta, double spring2);
//   static double duration(const Pair&);      head-on contact duration t_c
//   static double restitution(const Pair&);   the requested normal restitution
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "libgran/core/params.hpp"
#include "libgran/core/registry.hpp"

namespace gran {

// One side of a contact: a species, or a wall (a partner of infinite mass that does not rotate,
// with no radius: its contact distance is the grain's radius).
struct ContactPartner {
    std::string name;
    double mass = 1;              // +inf for a wall
    double diameter = 1;          // 0 for a wall
    double inertia_factor = 0.5;  // I = q m sigma^2 / 4
    bool wall = false;
};

// What of a species partner a law's resolve() reads, for given parameters (besides whether the
// partner is a wall, and its name in messages). Species that differ only in properties no law of
// their contacts reads share one contact class, and so one entry of the pair table
// (ContactTable): constant_restitution reads none of them, so 10^4 species of distinct diameters
// cost one pair entry; a soft law reads the mass (its damping follows from the reduced mass).
struct PartnerProperties {
    bool mass = true;
    bool diameter = true;
    bool inertia_factor = true;
};
inline constexpr PartnerProperties kNoPartnerProperties{false, false, false};

// Scene facts a law may read when it resolves a contact.
struct LawContext {
    int dimension = 2;
    double initial_temperature = 1;  // initial.temperature
    double lightest_mass = 1;        // of the species, for a default thermal speed sqrt(T0 / m)
};

// The resolved contacts of one scene, of one law type: pairs of contact classes first (index
// ContactTable::pair_index), then walls (ContactTable::wall_index).
struct LawTableBase {
    virtual ~LawTableBase() = default;
};
template <class L>
struct LawTable final : LawTableBase {
    std::vector<typename L::Pair> contacts;
};

// What a law offers, type-erased: libgran resolves and inspects contacts through these without
// knowing the law's type. Filled by register_law<L>.
struct LawPlugin : PluginInfo {
    std::function<std::unique_ptr<LawTableBase>(std::size_t contacts)> make_table;
    std::function<void(LawTableBase&, std::size_t index, const Params&, const ContactPartner&,
                       const ContactPartner&, const LawContext&)>
        resolve;
    // dst[to] = src[from] (tables of this law).
    std::function<void(LawTableBase& dst, std::size_t to, const LawTableBase& src,
                       std::size_t from)>
        copy;
    std::function<double(const LawTableBase&, std::size_t)> nominal_restitution;
    std::function<bool(const LawTableBase&, std::size_t)> rotates;
    // What resolve() reads of a species partner with these parameters (null: everything).
    std::function<PartnerProperties(const Params&)> partner_properties;
    // Hard-sphere form (null: none): the restitutions of one contact, for laws mixed per pair.
    struct HardSphere {
        bool impact_dependent = false;
        double (*normal_restitution)(const void* pair, double impact_speed) = nullptr;
        double (*tangential_restitution)(const void* pair) = nullptr;
        std::size_t pair_size = 0;  // bytes of one Pair (copied into a mixed table)
        const void* (*pair_at)(const LawTableBase&, std::size_t) = nullptr;
        // Why this contact has no hard-sphere form (e.g. friction of a soft law), null if it has.
        const char* (*problem)(const void* pair) = nullptr;
    };
    std::shared_ptr<const HardSphere> hard_sphere;
    // Soft-contact form (null: none): what the DEM engine and the checks at load need to know.
    struct SoftContact {
        bool history = false;
        double (*duration)(const LawTableBase&, std::size_t) = nullptr;
        double (*restitution)(const LawTableBase&, std::size_t) = nullptr;
    };
    std::shared_ptr<const SoftContact> soft_contact;
};

using LawRegistry = Registry<LawPlugin>;

// Introduction of the laws in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kLawsDescription =
    R"md(
`interactions.law` chooses the law of every contact, `interactions.walls.law` that of every
grain-wall contact and `interactions.pairs[].law` that of one contact; the law's keys are keys of
the same map. Hard-particle laws run on the `event_driven` engine; soft-contact laws run on the
`dem` engine and, frictionless, on the `event_driven` engine too as their hard limit
(instantaneous collisions with the same restitution). Kinetic-theory estimates that need a single
restitution (the Enskog pressure of `profiles`) use the law's nominal value, given with each law
below. A law is one file in `species/` (docs/architecture.md).)md";

template <class L>
concept InteractionLaw = std::is_trivially_copyable_v<typename L::Pair> &&
    requires(const Params& p, const ContactPartner& a, const LawContext& c,
             const typename L::Pair& pair) {
    { L::resolve(p, a, a, c) } -> std::same_as<typename L::Pair>;
    { L::nominal_restitution(pair) } -> std::convertible_to<double>;
    { L::rotates(pair) } -> std::convertible_to<bool>;
};

template <class L>
concept HardSphereLaw = InteractionLaw<L> && requires(const typename L::Pair& pair, double v) {
    { L::impact_dependent } -> std::convertible_to<bool>;
    { L::normal_restitution(pair, v) } -> std::convertible_to<double>;
    { L::tangential_restitution(pair) } -> std::convertible_to<double>;
};

template <class L>
concept SoftContactLaw = InteractionLaw<L> && requires(const typename L::Pair& pair, double x) {
    { L::history } -> std::convertible_to<bool>;
    { L::elastic_energy(pair, x, x) } -> std::convertible_to<double>;
    { L::duration(pair) } -> std::convertible_to<double>;
    { L::restitution(pair) } -> std::convertible_to<double>;
};

// The resolved contacts of a scene, engine-agnostic (libgran/scene/interactions.cpp builds it):
// one law for every contact (several hard-sphere laws mixed per pair are combined into the
// built-in mixed law), its table, and the wall partners.
//
// Grain-grain contacts are stored per pair of contact classes, not per pair of species, so the
// table does not grow with the square of the number of species when the contacts cannot tell the
// species apart: a species named in a `pairs` entry has a class of its own, the others share one
// per distinct value of the properties the default law reads (PartnerProperties). Grain-wall
// contacts stay per species (walls x species). The engines pay one lookup of a species' class per
// contact (a small array, hot in cache), no allocation and no call.
struct ContactTable {
    const LawPlugin* law = nullptr;
    std::shared_ptr<const LawTableBase> table;
    std::size_t species = 0;
    std::size_t classes = 0;                  // contact classes
    std::vector<std::uint32_t> class_of;      // per species
    std::vector<std::string> laws;            // the laws the scene names, in order of first use
    std::vector<std::string> walls;           // wall partner names (a wall driver's name, or "box")
    bool rotating = false;                    // some contact needs angular velocities
    std::vector<double> nominal_restitution;  // per pair of contact classes (pair_index)

    std::size_t pair_index(std::size_t a, std::size_t b) const {
        return std::size_t(class_of[a]) * classes + class_of[b];
    }
    // Stored grain-grain contacts: classes x classes, the first entries of the table.
    std::size_t pair_contacts() const { return classes * classes; }
    std::size_t wall_index(std::size_t w, std::size_t s) const {
        return pair_contacts() + w * species + s;
    }
    // Index of a wall partner by name, walls.size() if absent.
    std::size_t wall_named(const std::string& name) const {
        for (std::size_t w = 0; w < walls.size(); ++w) {
            if (walls[w] == name) return w;
        }
        return walls.size();
    }
    template <class L>
    const typename L::Pair* contacts() const {
        return static_cast<const LawTable<L>&>(*table).contacts.data();
    }
};

// The law of a scene whose contacts use several hard-sphere laws: each contact keeps its own law's
// restitution functions and parameters (one indirect call per collision, paid only by such scenes;
// libgran/engines/event_driven/mixed_law.cpp).
const LawPlugin& mixed_hard_sphere_law();
// Sets contact `index` of a table made by mixed_hard_sphere_law() to `pair` of a law with that
// hard-sphere form.
void set_mixed_contact(LawTableBase& table, std::size_t index, const LawPlugin::HardSphere& form,
                       const void* pair, double nominal_restitution, bool rotates);

}  // namespace gran
