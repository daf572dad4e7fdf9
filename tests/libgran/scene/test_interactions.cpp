// `interactions`, the single home of contact physics: a default law and its keys for every
// contact, `walls` for every grain-wall contact, `pairs` for single contacts between two species or
// a species and a wall partner (named by its wall driver, `box` for unclaimed walls), the keys each
// level leaves out inherited from the level above when the law is the same; keys that moved there
// from `engine` and the wall drivers refused with the new spelling.
#include <gtest/gtest.h>

#include <string>

#include "libgran/scene/scene.hpp"
#include "tests/support/contacts.hpp"
#include "tests/support/contains.hpp"

namespace gran {
namespace {

SpeciesTable two_species() {
    SpeciesTable t;
    t.species.push_back(Species{"heavy", 3.0, 1.0, 0.5, 10});
    t.species.push_back(Species{"light", 1.0, 1.0, 0.5, 10});
    return t;
}

// The normal restitution of every contact of a table, through the law's hard-sphere form.
double alpha(const ContactTable& c, std::size_t index) {
    return c.law->hard_sphere->normal_restitution(c.law->hard_sphere->pair_at(*c.table, index),
                                                  1.0);
}

TEST(Interactions, PairsOverrideOneContactAndWallsInheritTheDefaults) {
    const auto t = two_species();
    const ContactTable c = testing::contacts_of(
        t,
        "{alpha: 0.9, pairs: [{between: [heavy, light], alpha: 0.8}, {between: [light, lid], "
        "alpha: 0.5}]}",
        2, {"lid", "box"});
    EXPECT_EQ(c.law->name, "constant_restitution");
    EXPECT_EQ(alpha(c, c.pair_index(0, 0)), 0.9);
    EXPECT_EQ(alpha(c, c.pair_index(0, 1)), 0.8);
    EXPECT_EQ(alpha(c, c.pair_index(1, 0)), 0.8);
    EXPECT_EQ(alpha(c, c.pair_index(1, 1)), 0.9);
    EXPECT_EQ(alpha(c, c.wall_index(0, 1)), 0.5);  // light against the lid
    EXPECT_EQ(alpha(c, c.wall_index(0, 0)), 0.9);  // heavy against the lid: the default
    EXPECT_EQ(alpha(c, c.wall_index(1, 0)), 0.9);  // the box's walls: the default
}

TEST(Interactions, WallsLevelAppliesToEveryGrainWallContactAndPairsOfWallsInheritIt) {
    const auto t = two_species();
    const ContactTable c = testing::contacts_of(
        t, "{alpha: 0.9, walls: {alpha: 1}, pairs: [{between: [heavy, box], beta: -1}]}", 2);
    EXPECT_EQ(alpha(c, c.wall_index(0, 0)), 1.0);  // the pair inherits the walls' alpha
    EXPECT_EQ(alpha(c, c.wall_index(0, 1)), 1.0);
    EXPECT_EQ(alpha(c, c.pair_index(0, 1)), 0.9);
}

TEST(Interactions, AnOverrideWithAnotherLawTakesThatLawsDefaultsAndMixesLaws) {
    const auto t = two_species();
    const ContactTable c = testing::contacts_of(
        t, "{alpha: 0.7, pairs: [{between: [heavy, light], law: mcnamara_falcon, v0: 1}]}", 2);
    EXPECT_EQ(c.laws.size(), 2u);
    EXPECT_EQ(alpha(c, c.pair_index(0, 0)), 0.7);
    // r(v0) = r0 = 0.95, the law's default, not the 0.7 of the other law.
    const auto& hs = *c.law->hard_sphere;
    EXPECT_DOUBLE_EQ(hs.normal_restitution(hs.pair_at(*c.table, c.pair_index(0, 1)), 1.0), 0.95);
    EXPECT_DOUBLE_EQ(c.nominal_restitution[c.pair_index(1, 0)], 0.95);
}

TEST(Interactions, SoftContactKeysResolvePerPairWithTheReducedMass) {
    const auto t = two_species();
    const ContactTable c = testing::contacts_of(
        t,
        "{law: linear_dashpot, restitution: 0.9, contact_time: 0.01, pairs: [{between: "
        "[heavy, light], friction: 0.3}]}",
        3);
    const auto& soft = *c.law->soft_contact;
    // The contact time is what every contact was resolved for, whatever its reduced mass.
    EXPECT_NEAR(soft.duration(*c.table, c.pair_index(0, 0)), 0.01, 1e-15);
    EXPECT_NEAR(soft.duration(*c.table, c.pair_index(0, 1)), 0.01, 1e-15);
    EXPECT_NEAR(soft.duration(*c.table, c.wall_index(0, 1)), 0.01, 1e-15);
    EXPECT_TRUE(c.rotating);  // one contact has friction
}

void expect_refused(const std::string& interactions, const std::vector<std::string>& needles) {
    const auto t = two_species();
    try {
        testing::contacts_of(t, interactions, 2);
        ADD_FAILURE() << "accepted: " << interactions;
    } catch (const SceneError& e) {
        for (const auto& n : needles) EXPECT_TRUE(testing::contains(e.what(), n)) << e.what();
    }
}

TEST(Interactions, RefusesUnknownPartnersTwiceGivenContactsWallWallPairsAndUnknownLaws) {
    expect_refused("{pairs: [{between: [heavy, piston], alpha: 0.5}]}",
                   {"interactions.pairs[0].between", "unknown partner 'piston'", "box (wall)"});
    expect_refused(
        "{pairs: [{between: [heavy, light], alpha: 0.5}, {between: [light, heavy], alpha: 0.6}]}",
        {"interactions.pairs[1].between", "already given"});
    expect_refused("{pairs: [{between: [box, box], alpha: 0.5}]}", {"two walls"});
    expect_refused("{law: hertzian}",
                   {"interactions.law", "unknown law 'hertzian'", "constant_restitution"});
    expect_refused("{walls: {stiffness: 1}}", {"interactions.walls.stiffness", "unknown key"});
}

const char* kBase = R"(dimension: 2
box: {lengths: [10, 10], periodic: [true, false]}
species: [{name: a, count: 10}]
run: {unit: time, measurement: 1}
)";

void expect_scene_refused(const std::string& body, const std::vector<std::string>& needles) {
    try {
        parse_scene(YAML::Load(std::string(kBase) + body), "moved.yaml");
        ADD_FAILURE() << "accepted:\n" << body;
    } catch (const SceneError& e) {
        for (const auto& n : needles) EXPECT_TRUE(testing::contains(e.what(), n)) << e.what();
    }
}

TEST(Interactions, KeysThatMovedFromEngineAndWallDriversAreRefusedWithTheNewSpelling) {
    expect_scene_refused("engine: {type: dem, friction: 0.4}\n",
                         {"moved.yaml:5:", "engine.friction", "interactions: {friction: <mu>}"});
    expect_scene_refused("engine: {type: dem, contact_law: hertz_mindlin}\n",
                         {"engine.contact_law", "interactions: {law: <name>}"});
    expect_scene_refused("engine: {type: dem, wall_friction: 0}\n",
                         {"interactions: {walls: {friction: <mu_w>}}"});
    expect_scene_refused("drivers: [{type: static_wall, axis: y, name: lid, restitution: 0.5}]\n",
                         {"drivers[0].restitution", "between: [<species>, lid]", "interactions"});
}

TEST(Interactions, EveryRefusalHappensWhenTheSceneIsLoadedWithoutAnEngine) {
    // parse_scene builds no engine: what the dem engine cannot do is refused there already.
    expect_scene_refused(
        "interactions: {law: linear_dashpot, stiffness: 1e4}\nengine: {type: dem}\n"
        "drivers: [{type: stochastic_thermostat}]\n",
        {"drivers[0].type", "not available on the dem engine"});
    expect_scene_refused("interactions: {law: linear_dashpot, stiffness: 1e4, friction: 0.2}\n",
                         {"friction > 0 has no hard-particle limit"});
    expect_scene_refused("drivers: [{type: static_wall, axis: y, name: box}]\n",
                         {"drivers[0].name", "`box` names the walls no driver claims"});
    expect_scene_refused(
        "drivers: [{type: static_wall, axis: y}, {type: thermal_wall, axis: y, side: lower, "
        "temperature: 1}]\n",
        {"drivers[1]", "already given by driver 'static_wall'"});
}

}  // namespace
}  // namespace gran
