#pragma once
// The checks of a scene that need its plugins built: every driver and observable is constructed
// once (their constructors check cross-references such as species names and axes), the contacts
// are resolved with the wall partners the drivers create, and the engine checks that it can run
// the result. Nothing here builds an engine.
#include <yaml-cpp/yaml.h>

#include "libgran/scene/scene.hpp"

namespace gran {

template <int D>
void check_plugins(Scene& sc, const YAML::Node& root, const Where& top, YAML::Node& res);

}  // namespace gran
