#pragma once
// The trajectory of a run (`output.frames`) as files other tools open:
//  - OUT.trajectory.h5, an H5MD 1.1 file (/h5md, /parameters with the resolved scene, and
//    /particles/all): `position`, `velocity`, `image` (periodic images, when an axis is periodic),
//    `angular_velocity` (when the grains rotate) and the box `edges` as time-dependent elements
//    {step, time, value} (step: the engine's events or steps at the frame), `species`, `mass` and
//    `diameter` per particle; `unit` attributes in the scene's reduced units. It holds nothing
//    but the trajectory, so readers that expect a pure H5MD file (MDAnalysis) open it.
//  - OUT.trajectory.xdmf, an XDMF 2 sidecar pointing into it, so ParaView opens the frames as a
//    time series of point clouds with species, diameter, velocity (and images, angular
//    velocity) as point data.
// The result file links to it: /particles in OUT.h5 is an external link to the trajectory's
// /particles, so one file still reads everything (python/gran/results.py). Both are written
// complete to .part files and renamed with the result (ResultSink companions).
#include <string>
#include <vector>

#include "libgran/run/frames.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

// OUT.trajectory.h5 and OUT.trajectory.xdmf beside OUT.h5.
std::string trajectory_path_for(const std::string& result);
std::string xdmf_path_for(const std::string& result);

// The journal's frames as the trajectory of the result that will be at `destination`: writes
// both files as .part, links /particles of the sink's result to the trajectory and hands both
// to the sink to rename with it. Nothing when there are no frames. `step_unit`: "events" or
// "steps" (an attribute of /particles/all).
void write_trajectory(FrameWriter& frames, ResultSink& sink, const std::string& destination,
                      const Scene& sc, const std::vector<std::string>& command_line,
                      const std::string& step_unit);

// The XDMF 2 text for `frames` frames at `times` of the layout, reading `h5_name`.
std::string xdmf_text(const FrameLayout& layout, const std::vector<double>& times,
                      const std::string& h5_name);

}  // namespace gran
