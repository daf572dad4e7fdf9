// The trajectory files of a run (libgran/run/trajectory.hpp): H5MD elements with the real step,
// periodic images that unwrap the motion on both engines, the XDMF sidecar, and the companion
// files following their result (an interrupted rerun beside a completed result keeps both).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/run/run.hpp"
#include "libgran/run/trajectory.hpp"
#include "libgran/scene/scene.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace gran {
namespace {

namespace fs = std::filesystem;

class Trajectory : public testing::TempDirTest {};

RunReport run_text(const std::string& yaml, const std::string& out,
                   const std::atomic<bool>* interrupt = nullptr,
                   std::function<void(std::size_t, double)> on_sample = {}) {
    RunOptions opt;
    opt.output = out;
    opt.progress = false;
    opt.interrupt = interrupt;
    opt.on_sample = std::move(on_sample);
    return run_scene(parse_scene(YAML::Load(yaml), "scene.yaml"), opt);
}

// Frame by frame: the unwrapped displacement r + image L must stay below L / 2 (the frames are
// close in time: a particle moves a fraction of a free path between them), while without the
// images it jumps by about L for the particles that crossed a periodic axis. Returns {largest
// unwrapped step in units of L, crossings seen} along the periodic axes.
std::pair<double, int> unwrap_check(const std::string& trajectory, std::size_t d,
                                    const std::vector<bool>& periodic) {
    h5::File f = h5::File::open_read(trajectory);
    h5::Group all = f.root().group("particles/all");
    const auto shape = all.shape("position/value");
    const std::size_t frames = shape[0], n = shape[1];
    const auto r = all.read_doubles("position/value");
    const auto image = all.read_int64s("image/value");
    const auto edges = all.read_doubles("box/edges/value");
    double largest = 0;
    int crossings = 0;
    for (std::size_t k = 0; k + 1 < frames; ++k) {
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t a = 0; a < d; ++a) {
                if (!periodic[a]) continue;
                const std::size_t now = (k * n + i) * d + a, next = ((k + 1) * n + i) * d + a;
                const double L = edges[a * d + a];
                const double wrapped = r[next] - r[now];
                const double unwrapped = wrapped + double(image[next] - image[now]) * L;
                largest = std::max(largest, std::abs(unwrapped) / L);
                if (image[next] != image[now]) ++crossings;
                EXPECT_GE(r[next], 0.0);
                EXPECT_LT(r[next], L);
            }
        }
    }
    return {largest, crossings};
}

TEST_F(Trajectory, PeriodicImagesUnwrapTheMotionOfTheEventDrivenEngine) {
    const std::string out = path("gas.h5");
    ASSERT_TRUE(run_text(R"(
dimension: 3
seed: 5
species: [{name: a, count: 100}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.05}]
observables: [{type: temperatures}]
output: {frames: 400}
run: {equilibration: 5, measurement: 40, sample_interval: 0.1}
)",
                         out)
                    .completed);
    const auto [largest, crossings] = unwrap_check(trajectory_path_for(out), 3, {true, true, true});
    EXPECT_GT(crossings, 20);  // the images were needed
    EXPECT_LT(largest, 0.4);   // and they make the motion continuous
}

TEST_F(Trajectory, PeriodicImagesUnwrapTheMotionOfTheDemEngine) {
    const std::string out = path("bed.h5");
    ASSERT_TRUE(run_text(R"(
dimension: 2
seed: 1
gravity: [0, -1]
box: {lengths: [10, 60], periodic: [true, false]}
species: [{name: grain, count: 40}]
interactions: {law: linear_dashpot, restitution: 0.9, stiffness: 2.0e+5}
initial: {placement: random, temperature: 1}
engine: {type: dem}
drivers: [{type: vibrating_wall, axis: y, side: lower, waveform: sinusoid, amplitude: 1, frequency: 0.5}]
observables: [{type: barycentric_height}]
output: {frames: 300}
run: {unit: time, equilibration: 5, measurement: 30, sample_interval: 0.1}
)",
                         out)
                    .completed);
    const auto [largest, crossings] = unwrap_check(trajectory_path_for(out), 2, {true, false});
    EXPECT_GT(crossings, 5);
    EXPECT_LT(largest, 0.4);
    h5::File f = h5::File::open_read(trajectory_path_for(out));
    EXPECT_EQ(f.root().group("particles/all").read_attr_string("step_unit"), "steps");
}

// From 8192 grains on the DEM engine renumbers its grains in space (engine.sort_interval); the
// frames follow each grain by its input index all the same: frame for frame, the species and the
// positions of a run sorted every 20 steps are those of the unsorted run (to the round-off of the
// force sums, which a few hundred steps of a dilute gas do not amplify beyond ~1e-12). Rows in
// storage order would put other grains, on average half the box away, in most rows.
TEST_F(Trajectory, DemFramesFollowEachGrainThroughTheSpatialSorts) {
    struct Frames {
        std::vector<std::int64_t> species;
        std::vector<double> positions;
        std::int64_t sorts = 0;
    };
    const auto run = [&](int sort_interval) {
        const std::string out = path("bed" + std::to_string(sort_interval) + ".h5");
        EXPECT_TRUE(run_text(R"(
dimension: 2
seed: 3
box: {packing_fraction: 0.3}
species: [{name: a, count: 5000, diameter: 1}, {name: b, count: 5000, diameter: 1.2}]
interactions: {law: linear_dashpot, contact_time: 0.05, restitution: 0.9}
engine: {type: dem, sort_interval: )" +
                                 std::to_string(sort_interval) + R"(}
observables: [{type: temperatures}]
output: {frames: 15}
run: {unit: time, equilibration: 0, measurement: 0.3, sample_interval: 0.02}
)",
                             out)
                        .completed);
        Frames f;
        h5::File result = h5::File::open_read(out);
        f.sorts = result.root().read_int64s("performance/spatial_sorts").at(0);
        h5::File t = h5::File::open_read(trajectory_path_for(out));
        f.species = t.root().read_int64s("particles/all/species");
        f.positions = t.root().read_doubles("particles/all/position/value");
        return f;
    };
    const Frames sorted = run(20), plain = run(0);
    EXPECT_GE(sorted.sorts, 3);
    EXPECT_EQ(plain.sorts, 0);
    EXPECT_EQ(sorted.species, plain.species);
    ASSERT_EQ(sorted.positions.size(), plain.positions.size());
    ASSERT_GE(plain.positions.size(), 10u * 10000u * 2u) << "at least 10 frames";
    double largest = 0;
    for (std::size_t k = 0; k < plain.positions.size(); ++k)
        largest = std::max(largest, std::abs(sorted.positions[k] - plain.positions[k]));
    EXPECT_LT(largest, 1e-9) << "rows out of the input order";
}

TEST_F(Trajectory, XdmfNamesEveryFrameWithItsTimeAndEveryField) {
    FrameLayout layout{.particles = 7, .dimension = 3, .images = true, .angular_width = 3};
    const std::string x = xdmf_text(layout, {0.5, 1.5}, "run.trajectory.h5");
    auto count = [&](const std::string& s) {
        std::size_t c = 0;
        for (std::size_t p = x.find(s); p != std::string::npos; p = x.find(s, p + 1)) ++c;
        return c;
    };
    EXPECT_EQ(count("<Grid Name=\"frame "), 2u);
    EXPECT_EQ(count("<Time Value=\"1.5\"/>"), 1u);
    EXPECT_EQ(count("GeometryType=\"XYZ\""), 2u);
    for (const char* field :
         {"velocity", "species", "diameter", "mass", "image", "angular_velocity"}) {
        EXPECT_EQ(count(std::string("<Attribute Name=\"") + field + "\""), 2u) << field;
    }
    // Frame 1 of position, velocity, image and angular velocity (3 components in 3D).
    EXPECT_EQ(count(">1 0 0 1 1 1 1 7 3<"), 4u);
    EXPECT_EQ(count("run.trajectory.h5:/particles/all/position/value"), 2u);
}

TEST_F(Trajectory, InterruptedRerunBesideACompletedResultKeepsBothTrajectories) {
    const std::string gas = R"(
dimension: 2
seed: 5
species: [{name: a, count: 50}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.1}
drivers: [{type: stochastic_thermostat, strength: 1}]
observables: [{type: temperatures}]
output: {frames: 10}
run: {equilibration: 5, measurement: 20, sample_interval: 1}
)";
    const std::string out = path("gas.h5");
    ASSERT_TRUE(run_text(gas, out).completed);
    const auto before = fs::last_write_time(path("gas.trajectory.h5"));
    std::atomic<bool> stop{false};
    const RunReport rep = run_text(gas, out, &stop, [&](std::size_t samples, double) {
        if (samples == 8) stop = true;
    });
    ASSERT_FALSE(rep.completed);
    EXPECT_EQ(rep.output, path("gas.partial.h5"));
    EXPECT_EQ(fs::last_write_time(path("gas.trajectory.h5")), before);
    h5::File partial = h5::File::open_read(path("gas.partial.h5"));  // through the link
    EXPECT_EQ(partial.root().shape("particles/all/position/value")[0], 4u);
    std::ifstream xdmf(path("gas.partial.trajectory.xdmf"));
    std::stringstream text;
    text << xdmf.rdbuf();
    EXPECT_NE(text.str().find("gas.partial.trajectory.h5:/particles"), std::string::npos);
}

}  // namespace
}  // namespace gran
