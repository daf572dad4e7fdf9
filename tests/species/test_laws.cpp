// The registered interaction laws, reached as the engines reach them (type-erased through the
// registry, libgran/plugins/law.hpp): their restitution is their kernel's, bit for bit, at either
// sign of the impact speed; out-of-range keys are refused with the key named; the soft-contact
// laws' hard limit keeps the restitution and refuses friction.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "species/impact_restitution.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/contains.hpp"

namespace gran {
namespace {

SpeciesTable one_species() {
    SpeciesTable t;
    t.species.push_back(Species{"a", 1.0, 1.0, 0.5, 1});
    return t;
}

// The normal restitution of the grain-grain contact at impact speed v.
double restitution_at(const ContactTable& c, double v) {
    const auto& hs = *c.law->hard_sphere;
    return hs.normal_restitution(hs.pair_at(*c.table, 0), v);
}

TEST(Laws, ConstantRestitutionIsExactAtEveryImpactSpeed) {
    for (double e : {0.3, 0.85, 1.0, 0.1 + 0.2}) {
        const auto c = testing::contacts_of(one_species(), "{alpha: " + std::to_string(e) + "}");
        const double want = std::stod(std::to_string(e));
        for (double v : {0.0, 1e-300, 0.5, -3.0, 1e300, std::numeric_limits<double>::infinity()})
            EXPECT_EQ(restitution_at(c, v), want);  // bitwise
    }
}

TEST(Laws, ImpactSpeedLawsAreTheirKernelsBitForBitAtEitherSignOfTheImpactSpeed) {
    const auto mf =
        testing::contacts_of(one_species(), "{law: mcnamara_falcon, r0: 0.95, v0: 0.3}");
    const auto ve = testing::contacts_of(one_species(), "{law: viscoelastic, gamma: 0.1}");
    for (double v = 1e-4; v < 1e4; v *= 1.7) {
        EXPECT_EQ(restitution_at(mf, v), mcnamara_falcon_restitution(v, 0.95, 0.3));
        EXPECT_EQ(restitution_at(mf, -v), mcnamara_falcon_restitution(v, 0.95, 0.3));
        EXPECT_EQ(restitution_at(ve, v), viscoelastic_restitution(v, 0.1));
        EXPECT_EQ(restitution_at(ve, -v), viscoelastic_restitution(v, 0.1));
    }
    EXPECT_TRUE(mf.law->hard_sphere->impact_dependent);
    EXPECT_DOUBLE_EQ(mf.nominal_restitution[0], 0.95);  // r(v0)
}

void expect_refused(const std::string& interactions, const std::string& key) {
    try {
        testing::contacts_of(one_species(), interactions);
        ADD_FAILURE() << "accepted: " << interactions;
    } catch (const SceneError& e) {
        EXPECT_TRUE(testing::contains(e.what(), key)) << e.what();
    }
}

TEST(Laws, OutOfRangeKeysAreRefusedNamingTheKey) {
    expect_refused("{alpha: 1.1}", "interactions.alpha");
    expect_refused("{alpha: 0}", "interactions.alpha");
    expect_refused("{beta: -1.5}", "interactions.beta");
    expect_refused("{law: mcnamara_falcon, r0: 1.2, v0: 0.3}", "interactions.r0");
    expect_refused("{law: mcnamara_falcon, v0: 0}", "interactions.v0");
    expect_refused("{law: mcnamara_falcon}", "missing required key 'v0'");
    expect_refused("{law: viscoelastic, gamma: -1e-3}", "interactions.gamma");
    expect_refused("{law: linear_dashpot, stiffness: 1, contact_time: 1}", "not both");
    expect_refused("{law: hertz_mindlin, contact_time: 1e-3}", "interactions.reference_speed");
    expect_refused("{law: hertz_mindlin, stiffness: 1e4, restitution: 0.005}", "[0.01, 1]");
}

TEST(Laws, SoftContactLawsKeepTheirRestitutionInTheHardLimitAndRefuseFrictionThere) {
    for (const char* law : {"linear_dashpot", "cundall_strack", "hertz_mindlin"}) {
        const auto c = testing::contacts_of(
            one_species(), std::string("{law: ") + law + ", restitution: 0.8, stiffness: 1e4}");
        EXPECT_EQ(restitution_at(c, 2.0), 0.8) << law;
        EXPECT_EQ(c.law->hard_sphere->problem(c.law->hard_sphere->pair_at(*c.table, 0)), nullptr);
        const auto rough = testing::contacts_of(
            one_species(), std::string("{law: ") + law + ", stiffness: 1e4, friction: 0.3}");
        EXPECT_TRUE(rough.rotating) << law;
        EXPECT_NE(rough.law->hard_sphere->problem(rough.law->hard_sphere->pair_at(*rough.table, 0)),
                  nullptr)
            << law;
    }
}

}  // namespace
}  // namespace gran
