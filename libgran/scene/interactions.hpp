#pragma once
// The `interactions` section: the single home of contact physics, for both engines. A default law
// with its parameters applies to every contact, grain-grain and grain-wall; `walls` changes the
// parameters (or the law) of every grain-wall contact; `pairs` entries change one contact: two
// species, or a species and a wall partner. A wall partner is named by the wall driver that puts it
// there (its `name`, by default its type), or `box` for the walls of bounded axes no driver claims.
//
//   interactions:
//     law: linear_dashpot            # default: constant_restitution
//     restitution: 0.9               # the law's keys (`gran list laws`)
//     stiffness: 2.0e+5
//     walls: {friction: 0.4}         # every grain-wall contact
//     pairs:
//       - {between: [heavy, light], restitution: 0.8}
//       - {between: [heavy, box], restitution: 1}
//
// Keys a `walls` or `pairs` entry leaves out take the values of the level above when it has the
// same law (pairs of a wall: `walls`, else the defaults), else the law's own defaults.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "libgran/core/params.hpp"
#include "libgran/core/species.hpp"
#include "libgran/plugins/law.hpp"

namespace gran {

// `wall_partners`: the names grain-wall contacts can have in this scene. Resolved values go to
// `resolved` (a valid `interactions` section that reruns identically).
ContactTable read_interactions(const YAML::Node& node, const SpeciesTable& species,
                               const std::vector<std::string>& wall_partners,
                               const LawContext& context, const Where& where, YAML::Node& resolved);

// The keys of the section itself (besides the default law's), for `gran list` and the reference.
Schema interactions_schema();
Schema pair_override_schema();

}  // namespace gran
