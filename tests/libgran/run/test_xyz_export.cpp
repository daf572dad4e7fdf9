// `gran export --xyz` (libgran/run/xyz_export.hpp): every frame of the trajectory, with the box,
// time and step in the comment line and positions and velocities read back exactly.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/run.hpp"
#include "libgran/run/xyz_export.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace gran {
namespace {

class XyzExport : public testing::TempDirTest {};

TEST_F(XyzExport, EveryFrameWithBoxTimeStepAndExactPositions) {
    RunOptions opt;
    opt.output = path("mix.h5");
    opt.progress = false;
    ASSERT_TRUE(run_scene(parse_scene(YAML::Load(R"(
dimension: 2
seed: 5
species: [{name: heavy, mass: 3, count: 20}, {name: light, diameter: 0.5, count: 30}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.1, periodic: [true, false]}
drivers: [{type: sawtooth_wall, axis: y, velocity: 1}]
observables: [{type: temperatures}]
output: {frames: 3}
run: {equilibration: 5, measurement: 30, sample_interval: 1}
)"),
                                      "mix.yaml"),
                          opt)
                    .completed);
    EXPECT_EQ(export_xyz(path("mix.h5"), path("mix.xyz")), 3u);
    h5::File f = h5::File::open_read(path("mix.h5"));
    h5::Group all = f.root().group("particles/all");
    const auto r = all.read_doubles("position/value");
    const auto steps = all.read_int64s("position/step");
    std::ifstream in(path("mix.xyz"));
    std::string line;
    std::vector<std::string> lines;
    while (std::getline(in, line)) lines.push_back(line);
    ASSERT_EQ(lines.size(), 3u * (2 + 50));
    EXPECT_EQ(lines[0], "50");
    const std::string& comment = lines[52 + 1];  // frame 1
    EXPECT_NE(comment.find("pbc=\"T F F\""), std::string::npos) << comment;
    EXPECT_NE(comment.find("Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1"),
              std::string::npos);
    EXPECT_NE(comment.find("Step=" + std::to_string(steps[1]) + ""), std::string::npos);
    // Frame 1, particle 7: name, x, y, z = 0 as written in the trajectory, bit for bit.
    std::istringstream p(lines[52 + 2 + 7]);
    std::string name;
    double x = 0, y = 0, z = 1, vx, vy, vz, radius = 0;
    p >> name >> x >> y >> z >> vx >> vy >> vz >> radius;
    EXPECT_EQ(x, r[(50 + 7) * 2]);
    EXPECT_EQ(y, r[(50 + 7) * 2 + 1]);
    EXPECT_EQ(z, 0.0);
    EXPECT_TRUE((name == "heavy" && radius == 0.5) || (name == "light" && radius == 0.25))
        << name << " " << radius;
}

TEST_F(XyzExport, AResultWithoutFramesIsRefusedNamingTheKey) {
    {
        h5::File f = h5::File::create(path("empty.h5"));
        f.root().write_scalar("x", 1.0);
    }
    try {
        export_xyz(path("empty.h5"), path("empty.xyz"));
        FAIL() << "no error";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("output.frames"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace gran
