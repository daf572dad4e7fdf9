#pragma once
// What a run will cost, as its engine estimates it at load (EnginePlugin::estimate): `gran check`
// prints it with the time it takes at the rate measured on this build, `gran run` logs it.
#include <string>

namespace gran {

struct RunCost {
    double work = 0;   // in `unit`; 0: no estimate
    std::string unit;  // "events", "particle-steps"
    // Units of `work` per unit of the runner's work() (events: 1; dem: the particles of a step),
    // to turn the rate `gran check` measures with the runner into the rate of `unit`.
    double per_runner_work = 1;
    std::string text;  // the line `gran check` prints and `gran run` logs
};

}  // namespace gran
