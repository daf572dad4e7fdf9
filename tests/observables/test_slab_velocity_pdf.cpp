// Velocity distributions in slabs of a vibrated gas (Barrat & Trizac 2002, Figs. 6-7): next to a
// sawtooth wall the vertical distribution has two peaks, incoming particles (v_y < 0) and particles
// sent back at v_y >= 2 v0, separated by a deep dip; in the middle of the cell it has one peak; the
// rescaled horizontal distribution is non-Gaussian (kurtosis above 3).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "libgran/core/h5.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

// Number of prominent peaks: the highest bin, plus any bin on either side that rises above 10% of
// it and to more than twice the lowest density between them (a second population, not noise).
int prominent_peaks(const std::vector<double>& d) {
    const std::size_t top = std::size_t(std::max_element(d.begin(), d.end()) - d.begin());
    const double high = d[top];
    int peaks = 1;
    double low = high;
    for (std::size_t k = top + 1; k < d.size(); ++k) {
        low = std::min(low, d[k]);
        if (d[k] > 0.1 * high && d[k] > 2 * low) {
            ++peaks;
            break;
        }
    }
    low = high;
    for (std::size_t k = top; k-- > 0;) {
        low = std::min(low, d[k]);
        if (d[k] > 0.1 * high && d[k] > 2 * low) {
            ++peaks;
            break;
        }
    }
    return peaks;
}

TEST(SlabVelocityPdf, VerticalDistributionIsDoublePeakedNextToSawtoothWallOnly) {
    // The same run as tests/observables/test_restitution_statistics.cpp.
    const YAML::Node s = testing::run_yaml_once(
        testing::vibrated_gas(
            500, 0.9,
            "[{type: restitution_statistics}, {type: velocity_pdf}, {type: slab_velocity_pdf, "
            "slabs: [0.03, 0.5], width: 0.06}]"),
        "vibrated_500");
    auto f = h5::File::open_read((testing::shared_dir() / "vibrated_500.h5").string());
    auto g = f.root().group("observables/slab_velocity_pdf");
    EXPECT_EQ(prominent_peaks(g.read_doubles("slab_0/a/y/scaled_density")), 2)
        << "next to the wall";
    EXPECT_EQ(prominent_peaks(g.read_doubles("slab_1/a/y/scaled_density")), 1) << "in the middle";
    EXPECT_EQ(prominent_peaks(g.read_doubles("slab_0/a/x/scaled_density")), 1)
        << "horizontal, next to the wall";
    EXPECT_GT(s["observables"]["slab_velocity_pdf"]["slab_1"]["a"]["x"]["kurtosis"].as<double>(),
              3.1);
}

// With thermal walls instead, the distribution next to the wall is smooth (one peak), as in Fig. 6.
TEST(SlabVelocityPdf, VerticalDistributionNextToThermalWallHasOnePeak) {
    const char* scene = R"(
dimension: 2
seed: 3
species: [{name: a, count: 500}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.04, periodic: [true, false]}
drivers: [{type: thermal_wall, axis: y, temperature: 1}]
observables: [{type: slab_velocity_pdf, slabs: [0.03], width: 0.06}]
run: {equilibration: 200, measurement: 4000, sample_interval: 2}
)";
    testing::run_yaml(scene, "thermal_slab");
    auto f = h5::File::open_read((testing::temp_dir() / "thermal_slab.h5").string());
    auto g = f.root().group("observables/slab_velocity_pdf");
    EXPECT_EQ(prominent_peaks(g.read_doubles("slab_0/a/y/scaled_density")), 1);
}

}  // namespace
}  // namespace gran
