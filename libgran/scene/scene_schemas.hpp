#pragma once
// The schemas of the scene's own sections: read by parse_scene (scene.cpp), documented by
// scene_sections() (scene_sections.cpp).
#include "libgran/core/params.hpp"

namespace gran {

Schema top_schema();
Schema box_schema();
Schema initial_schema();
Schema engine_schema();
Schema run_schema();
Schema watchdog_schema();
Schema output_schema();

}  // namespace gran
