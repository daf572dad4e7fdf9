#pragma once
// register_law<L>: the one registration of an interaction law (libgran/plugins/law.hpp). It puts
// the law in Registry<LawPlugin> with type-erased access to its contacts, and instantiates the
// engine loops templated on it: the event-driven collision loop for a law with a hard-sphere form,
// the DEM force loop for a law with a soft-contact form. A law file in species/ (or a test) calls
// it once, in a static initialiser:
//
//   const bool registered = register_law<MyLaw>("my_law", "one-line summary", schema);
#include <memory>
#include <string>

#include "libgran/engines/dem/law_loop.hpp"
#include "libgran/engines/event_driven/law_loop.hpp"
#include "libgran/plugins/law.hpp"

namespace gran {

template <class L>
concept HasHardSphereProblem = requires(const typename L::Pair& p) {
    { L::hard_sphere_problem(p) } -> std::convertible_to<const char*>;
};

template <class L>
concept HasPartnerProperties = requires(const Params& p) {
    { L::partner_properties(p) } -> std::same_as<PartnerProperties>;
};

namespace law_detail {

template <class L>
const typename L::Pair& at(const LawTableBase& t, std::size_t i) {
    return static_cast<const LawTable<L>&>(t).contacts[i];
}

template <HardSphereLaw L>
std::shared_ptr<const LawPlugin::HardSphere> hard_sphere_form() {
    using Pair = typename L::Pair;
    auto hs = std::make_shared<LawPlugin::HardSphere>();
    hs->impact_dependent = L::impact_dependent;
    hs->normal_restitution = [](const void* pair, double v) {
        return double(L::normal_restitution(*static_cast<const Pair*>(pair), v));
    };
    hs->tangential_restitution = [](const void* pair) {
        return double(L::tangential_restitution(*static_cast<const Pair*>(pair)));
    };
    hs->pair_size = sizeof(Pair);
    hs->pair_at = [](const LawTableBase& t, std::size_t i) -> const void* { return &at<L>(t, i); };
    if constexpr (HasHardSphereProblem<L>) {
        hs->problem = [](const void* pair) -> const char* {
            return L::hard_sphere_problem(*static_cast<const Pair*>(pair));
        };
    }
    return hs;
}

template <SoftContactLaw L>
std::shared_ptr<const LawPlugin::SoftContact> soft_contact_form() {
    auto sc = std::make_shared<LawPlugin::SoftContact>();
    sc->history = L::history;
    sc->duration = [](const LawTableBase& t, std::size_t i) {
        return double(L::duration(at<L>(t, i)));
    };
    sc->restitution = [](const LawTableBase& t, std::size_t i) {
        return double(L::restitution(at<L>(t, i)));
    };
    return sc;
}

}  // namespace law_detail

// The LawPlugin of L (not registered), with its engine loops registered under `name`.
template <InteractionLaw L>
LawPlugin make_law_plugin(std::string name, std::string summary, Schema schema,
                          std::string description = {}) {
    static_assert(HardSphereLaw<L> || SoftContactLaw<L>,
                  "a law needs a hard-sphere form, a soft-contact form, or both");
    using law_detail::at;
    LawPlugin p;
    p.name = std::move(name);
    p.summary = std::move(summary);
    p.schema = std::move(schema);
    p.description = std::move(description);
    p.make_table = [](std::size_t n) -> std::unique_ptr<LawTableBase> {
        auto t = std::make_unique<LawTable<L>>();
        t->contacts.resize(n);
        return t;
    };
    p.resolve = [](LawTableBase& t, std::size_t i, const Params& prm, const ContactPartner& a,
                   const ContactPartner& b, const LawContext& c) {
        static_cast<LawTable<L>&>(t).contacts[i] = L::resolve(prm, a, b, c);
    };
    p.copy = [](LawTableBase& dst, std::size_t to, const LawTableBase& src, std::size_t from) {
        static_cast<LawTable<L>&>(dst).contacts[to] = at<L>(src, from);
    };
    p.nominal_restitution = [](const LawTableBase& t, std::size_t i) {
        return double(L::nominal_restitution(at<L>(t, i)));
    };
    p.rotates = [](const LawTableBase& t, std::size_t i) { return bool(L::rotates(at<L>(t, i))); };
    // A law that does not say what it reads of its partners is taken to read all of it.
    p.partner_properties = [](const Params& prm) {
        if constexpr (HasPartnerProperties<L>) {
            return L::partner_properties(prm);
        } else {
            (void)prm;
            return PartnerProperties{};
        }
    };
    if constexpr (HardSphereLaw<L>) {
        p.hard_sphere = law_detail::hard_sphere_form<L>();
        register_event_driven_loops<L>(p.name);
    }
    if constexpr (SoftContactLaw<L>) {
        p.soft_contact = law_detail::soft_contact_form<L>();
        register_dem_loops<L>(p.name);
    }
    return p;
}

template <InteractionLaw L>
bool register_law(std::string name, std::string summary, Schema schema,
                  std::string description = {}) {
    return LawRegistry::instance().add(make_law_plugin<L>(
        std::move(name), std::move(summary), std::move(schema), std::move(description)));
}

}  // namespace gran
