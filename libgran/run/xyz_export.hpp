#pragma once
// `gran export --xyz`: a run's trajectory as extended XYZ (the format OVITO, ASE and VMD read):
// per frame the particle count, a comment line with the box (`Lattice`, `pbc`), the columns
// (`Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1`) and the frame's time and step, then
// one line per particle. 2D positions get z = 0 and a unit third lattice vector (pbc F).
#include <string>

namespace gran {

// Reads the frames of `input` (a result file, through its /particles link, or the trajectory
// file itself) and writes `output`; returns the number of frames. OutputError naming the path
// when `input` holds no frames or `output` cannot be written.
std::size_t export_xyz(const std::string& input, const std::string& output);

}  // namespace gran
