// The plotting script turns a result file into a PNG (Debian's python3 with h5py and matplotlib;
// the package gran found through PYTHONPATH, as the Makefile sets it).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

const std::string kPlotResult = "PYTHONPATH=" + std::string(GRAN_SOURCE_DIR) +
                                "/python /usr/bin/python3 " + std::string(GRAN_SOURCE_DIR) +
                                "/studies/plot_result.py ";

TEST(PlotScript, WritesAPngForAHeatedMixtureResult) {
    const char* scene = R"(
dimension: 2
seed: 2
particles: 200
species:
  - {name: heavy, mass: 3, number_fraction: 0.5}
  - {name: light, mass: 1, number_fraction: 0.5}
interactions: {alpha: 0.85}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.03}]
observables: [{type: temperatures}, {type: velocity_pdf}, {type: kinetic_energy}, {type: collision_statistics}]
run: {equilibration: 10, measurement: 50}
)";
    testing::run_yaml(scene, "plot");
    const auto dir = testing::temp_dir();
    const auto png = dir / "plot.png";
    const std::string cmd =
        kPlotResult + (dir / "plot.h5").string() + " -o " + png.string() + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[256];
    while (fgets(buf, sizeof buf, pipe)) out += buf;
    const int status = pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << out;
    ASSERT_TRUE(std::filesystem::exists(png)) << out;
    std::ifstream f(png, std::ios::binary);
    char magic[8] = {};
    f.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
    EXPECT_GT(std::filesystem::file_size(png), 10000u);
}

TEST(PlotScript, RefusesAFileThatIsNotAResult) {
    const auto dir = testing::temp_dir();
    const auto bogus = dir / "bogus.h5";
    std::ofstream(bogus) << "not hdf5";
    const std::string cmd = kPlotResult + bogus.string() + " > /dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_NE(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace gran
