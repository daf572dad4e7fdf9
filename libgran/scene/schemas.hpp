#pragma once
// The schemas of the scene's own sections (the plugins declare theirs).
#include "libgran/core/params.hpp"

namespace gran {

ParamSpec list_of(ParamType t, std::string name, std::string doc, bool opt = true);
Schema top_schema();
Schema box_schema();
Schema initial_schema();
Schema run_schema();
Schema watchdog_schema();
Schema checkpoint_schema();
Schema output_schema();

}  // namespace gran
