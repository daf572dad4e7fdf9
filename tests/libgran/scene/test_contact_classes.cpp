// The contact table stores grain-grain contacts per pair of contact classes, not per pair of
// species (libgran/plugins/law.hpp, ContactTable): species that no contact tells apart share a
// class, so 10^4 species of a uniform law cost one pair entry and `gran check` builds the scene in
// seconds (it took minutes and 7 GB), while pair overrides and mass-dependent laws still give every
// contact its own parameters.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "libgran/run/run.hpp"
#include "libgran/scene/scene.hpp"
#include "species/contact_laws.hpp"
#include "species/soft_contact.hpp"
#include "tests/support/contacts.hpp"

namespace gran {
namespace {

// A polydisperse scene: `species` species of distinct diameters (and masses), `count` grains each.
std::string polydisperse_scene(std::size_t species, int count) {
    std::string s =
        "dimension: 2\nseed: 1\ninteractions: {law: constant_restitution, alpha: 0.9}\n"
        "box: {packing_fraction: 0.05, periodic: [true, true]}\n"
        "initial: {placement: random, temperature: 1}\n"
        "observables: [{type: kinetic_energy}]\n"
        "run: {unit: time, equilibration: 0, measurement: 1, sample_interval: 0.5}\n"
        "species:\n";
    for (std::size_t i = 0; i < species; ++i) {
        const double d = 1.0 + 0.5 * double(i) / double(species);
        s += "  - {name: s" + std::to_string(i) + ", mass: " + std::to_string(d * d) +
             ", diameter: " + std::to_string(d) + ", count: " + std::to_string(count) + "}\n";
    }
    return s;
}

// Every contact's normal restitution, through the law's hard-sphere form.
double alpha(const ContactTable& c, std::size_t index) {
    const auto& hs = *c.law->hard_sphere;
    return hs.normal_restitution(hs.pair_at(*c.table, index), 1.0);
}

TEST(ContactTable, TenThousandSpeciesWithUniformLawBuildInSecondsAndStoreOnePairContact) {
    const std::string text = polydisperse_scene(10000, 1);
    const auto start = std::chrono::steady_clock::now();
    const Scene scene = load_scene_text(text, "ten-thousand-species.yaml");
    check_scene(scene);  // what `gran check` does after loading
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(scene.species.size(), 10000u);
    // O(S): one class for every species (the law reads nothing of its partners), no walls.
    EXPECT_EQ(scene.contacts.classes, 1u);
    EXPECT_EQ(scene.contacts.pair_contacts(), 1u);
    EXPECT_EQ(scene.contacts.class_of.size(), 10000u);
    EXPECT_EQ(scene.info.nominal_restitution.size(), 1u);
    EXPECT_EQ(alpha(scene.contacts, scene.contacts.pair_index(0, 9999)), 0.9);
    // Generous (5.5 s on the development machine for the same scene through `gran check`, 84 s
    // and 7 GB before contact classes); the counts above are the real check.
    EXPECT_LT(seconds, 60.0);
}

TEST(ContactTable,
     PairOverridesOnTwoOfManySpeciesGiveThosePairsTheirOwnParametersAndOthersDefaults) {
    SpeciesTable t;
    for (int i = 0; i < 100; ++i) {
        const double d = 1.0 + 0.01 * i;
        t.species.push_back(Species{"s" + std::to_string(i), d * d, d, 0.5, 1});
    }
    const ContactTable c = testing::contacts_of(
        t,
        "{alpha: 0.9, pairs: [{between: [s3, s7], alpha: 0.5}, {between: [s7, s7], alpha: 0.6}, "
        "{between: [s5, box], alpha: 0.3}]}",
        2);
    // s3 and s7 have classes of their own; the 98 others (s5 too: walls are per species) share one.
    EXPECT_EQ(c.classes, 3u);
    EXPECT_EQ(c.pair_contacts(), 9u);
    EXPECT_EQ(alpha(c, c.pair_index(3, 7)), 0.5);
    EXPECT_EQ(alpha(c, c.pair_index(7, 3)), 0.5);
    EXPECT_EQ(alpha(c, c.pair_index(7, 7)), 0.6);
    EXPECT_EQ(alpha(c, c.pair_index(3, 3)), 0.9);
    EXPECT_EQ(alpha(c, c.pair_index(3, 8)), 0.9);
    EXPECT_EQ(alpha(c, c.pair_index(99, 7)), 0.9);
    EXPECT_EQ(alpha(c, c.pair_index(0, 99)), 0.9);
    EXPECT_EQ(c.nominal_restitution[c.pair_index(7, 3)], 0.5);
    EXPECT_EQ(alpha(c, c.wall_index(0, 5)), 0.3);
    EXPECT_EQ(alpha(c, c.wall_index(0, 6)), 0.9);
}

TEST(ContactTable, MassDependentLawGivesEveryPairOfDistinctMassesItsOwnDamping) {
    // linear_dashpot given a restitution: c_n = c_n(k_n, m_eff, e) with the pair's reduced mass.
    // s0 and s3 have equal masses (different diameters, which the law does not read): one class.
    SpeciesTable t;
    t.species.push_back(Species{"s0", 1.0, 1.0, 0.5, 1});
    t.species.push_back(Species{"s1", 2.0, 1.2, 0.5, 1});
    t.species.push_back(Species{"s2", 5.0, 1.5, 0.5, 1});
    t.species.push_back(Species{"s3", 1.0, 0.8, 0.5, 1});
    const double k_n = 1e4, e = 0.8;
    const ContactTable c =
        testing::contacts_of(t, "{law: linear_dashpot, restitution: 0.8, stiffness: 1e4}", 2);
    EXPECT_EQ(c.classes, 3u);
    EXPECT_EQ(c.pair_index(3, 2), c.pair_index(0, 2));
    using Pair = soft_contact::Resolved<LinearDashpotContact>;
    const auto& hs = *c.law->hard_sphere;
    for (std::size_t a = 0; a < t.size(); ++a) {
        for (std::size_t b = 0; b < t.size(); ++b) {
            const auto* p = static_cast<const Pair*>(hs.pair_at(*c.table, c.pair_index(a, b)));
            const double m_eff = reduced_mass(t.species[a].mass, t.species[b].mass);
            EXPECT_EQ(p->contact.gamma_n, linear_damping_from_restitution(k_n, m_eff, e))
                << t.species[a].name << "-" << t.species[b].name;
        }
        // Against the box: the grain's own mass.
        const auto* w = static_cast<const Pair*>(hs.pair_at(*c.table, c.wall_index(0, a)));
        EXPECT_EQ(w->contact.gamma_n, linear_damping_from_restitution(k_n, t.species[a].mass, e));
    }
}

}  // namespace
}  // namespace gran
