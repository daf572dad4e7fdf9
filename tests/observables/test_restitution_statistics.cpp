// Effective restitution in a vibrated gas (Barrat & Trizac 2002, Sec. III E, Figs. 7-8): the
// projected restitution alpha_1d = -v'_12,x / v_12,x exceeds 1 for a sizeable fraction of
// collisions, its distribution decays as alpha_1d^-2 at large alpha_1d (least-squares fit of the
// logarithmic-bin histogram over 3 < alpha_1d < 100: slope -2 within 0.2), and the horizontal
// velocity distribution is non-Gaussian (kurtosis above 3). A gas without energy transfer between
// components (e.g. elastic smooth collisions in 1D) would give alpha_1d = 1 exactly.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "libgran/core/h5.hpp"
#include "tests/support/run_scene.hpp"

namespace gran {
namespace {

const char* kObservables =
    "[{type: restitution_statistics}, {type: velocity_pdf}, {type: slab_velocity_pdf, slabs: "
    "[0.03, 0.5], width: 0.06}]";

TEST(RestitutionStatistics, VibratedGasHasAlpha1dAboveOneWithInverseSquareTail) {
    const YAML::Node s =
        testing::run_yaml_once(testing::vibrated_gas(500, 0.9, kObservables), "vibrated_500");
    auto f = h5::File::open_read((testing::shared_dir() / "vibrated_500.h5").string());
    auto g = f.root().group("observables/restitution_statistics");
    const double above =
        testing::value(s["observables"]["restitution_statistics"]["fraction_above_one"]);
    EXPECT_GT(above, 0.1);
    const auto edges = g.read_doubles("alpha_1d_tail/edges");
    const auto density = g.read_doubles("alpha_1d_tail/density");
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
        const double c = std::sqrt(edges[k] * edges[k + 1]);
        if (c > 3 && c < 100 && density[k] > 0) {
            const double x = std::log(c), y = std::log(density[k]);
            sx += x;
            sy += y;
            sxx += x * x;
            sxy += x * y;
            n += 1;
        }
    }
    ASSERT_GT(n, 10);
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    RecordProperty("tail_slope", fmt::format("{:.3f}", slope));
    RecordProperty("fraction_above_one", fmt::format("{:.4f}", above));
    EXPECT_NEAR(slope, -2.0, 0.2);
    const YAML::Node k = s["observables"]["velocity_pdf"]["a"]["x"]["kurtosis"];
    EXPECT_GT(testing::value(k) - 3.0, 5 * testing::error(k))
        << "horizontal PDF should be non-Gaussian";
}

}  // namespace
}  // namespace gran
