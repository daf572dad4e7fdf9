#pragma once
// The headline numbers of a run, picked from its summary: the temperature ratios gamma = T_s/T_ref
// that the demo and most studies are after. Written into the summary as `headline` (what `gran
// run` prints last, and what the Python module's `Result.summary["gamma"]` gives).
#include <yaml-cpp/yaml.h>

namespace gran {

// From a summary's `observables` section: for every species pair `p` of a temperatures observable
// (`ratios/p/gamma`) and of a profiles observable with a middle window
// (`middle/ratios/p/gamma`):
//   gamma[/p]              the middle-of-the-cell value when a profile measured it (Barrat &
//                          Trizac 2002 quote gamma there, Tables I-II), else the whole system's;
//   gamma_whole_system[/p] the whole system's, when `gamma` is the middle's;
// (`/p` only when there is more than one pair). Each entry is {value, error, from: the summary
// key it was copied from}. An empty node when nothing was measured.
YAML::Node headline(const YAML::Node& summary);

}  // namespace gran
