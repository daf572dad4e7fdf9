#pragma once
// What a Simulation has measured so far, written as a result file at any moment: the Python
// module's `Simulation.results()` reads observables mid-run through the same reader as a finished
// run's file (python/gran/results.py).
#include <yaml-cpp/yaml.h>

#include <string>

#include "libgran/run/simulation.hpp"

namespace gran {

// Writes /h5md, /parameters, /observables and /drivers of `sim` at its current state to a new
// HDF5 file at `path` (replaced if it exists) and returns the summary of those quantities as
// YAML text (the `observables` and `drivers` sections of a run's summary). No /performance: the
// run is not over. h5::Error naming the path when the file cannot be written.
std::string write_measurements(const Simulation& sim, const std::string& path);

// The `observables` section of the summary the observables would write now, without a file (an
// in-memory HDF5 file, discarded): how a run with a target looks at its error bars mid-run.
// Observables' warnings are silenced while they write (they speak at the end of the run).
template <int D>
YAML::Node observables_summary_now(const Scene& sc, const SimulationState<D>& st);

}  // namespace gran
