#pragma once
// Keys that moved in issue 12: contact physics left `engine` and the wall drivers for
// `interactions`. A scene that still uses one is refused with the new spelling.
#include <yaml-cpp/yaml.h>

#include "libgran/core/scene_error.hpp"

namespace gran {

void refuse_moved_keys(const YAML::Node& root, const Where& top);

}  // namespace gran
