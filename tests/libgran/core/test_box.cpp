// The box's minimum image: Box::separation against a direct reading of the convention, and its
// two-lane form (MinimumImageTwo, used by the event-driven scan) bit for bit against it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "libgran/core/box.hpp"

namespace gran {
namespace {

// Pairs whose separations fall inside, at and beyond half the box on every axis: positions in
// the box, within one box length outside it (particles between a crossing and its wrap), and
// pairs exactly half a box apart (the separation is then +-L/2, kept as it is).
template <int D>
std::vector<std::pair<Vec<D>, Vec<D>>> pairs_across_the_box(const Box<D>& box, int n) {
    std::mt19937_64 rng(20261128 + D);
    std::uniform_real_distribution<double> u(-1.0, 2.0);
    std::vector<std::pair<Vec<D>, Vec<D>>> out;
    for (int m = 0; m < n; ++m) {
        Vec<D> a, b;
        for (int k = 0; k < D; ++k) {
            if (m % 7 == 0) {  // exactly half a box apart: the boundary of the wrap
                b[k] = m % 2 ? 0.0 : box.length[k];
                a[k] = b[k] + (m % 3 ? 0.5 : -0.5) * box.length[k];
            } else {
                a[k] = u(rng) * box.length[k];
                b[k] = u(rng) * box.length[k];
            }
        }
        out.emplace_back(a, b);
    }
    return out;
}

template <int D>
Box<D> mixed_box() {
    Box<D> box;
    for (int k = 0; k < D; ++k) box.length[k] = 3.7 + 2.1 * k;
    box.periodic.fill(true);
    box.periodic[1] = false;  // a walled axis keeps the plain difference
    return box;
}

TEST(Box, SeparationIsTheNearestImageOnPeriodicAxesAndThePlainDifferenceOnWalledOnes) {
    const Box<3> box = mixed_box<3>();
    for (const auto& [a, b] : pairs_across_the_box(box, 20000)) {
        const Vec<3> d = box.separation(a, b);
        for (int k = 0; k < 3; ++k) {
            const double plain = a[k] - b[k];
            if (!box.periodic[std::size_t(k)]) {
                EXPECT_EQ(d[k], plain);
                continue;
            }
            // Within half a box of zero wherever the plain difference is within 1.5 boxes.
            const double L = box.length[k];
            if (std::abs(plain) == 0.5 * L) {  // at half a box: kept as it is
                EXPECT_EQ(d[k], plain);
            }
            if (std::abs(plain) <= 1.5 * L) {
                EXPECT_LE(std::abs(d[k]), 0.5 * L);
            }
            // A whole number of boxes away from the plain difference.
            const double shift = (plain - d[k]) / L;
            EXPECT_NEAR(shift, std::round(shift), 1e-12);
        }
    }
}

template <int D>
void expect_two_lanes_bit_for_bit_the_one_pair_form() {
    const Box<D> box = mixed_box<D>();
    const MinimumImageTwo<D> image(box);
    const auto pairs = pairs_across_the_box(box, 50000);
    for (std::size_t m = 0; m + 1 < pairs.size(); m += 2) {
        const auto& [a0, b0] = pairs[m];
        const auto& [a1, b1] = pairs[m + 1];
        const Vec<D> d0 = box.separation(a0, b0), d1 = box.separation(a1, b1);
        for (int k = 0; k < D; ++k) {
            const __m128d lanes =
                image(_mm_sub_pd(_mm_set_pd(a1[k], a0[k]), _mm_set_pd(b1[k], b0[k])), k);
            double got[2];
            _mm_storeu_pd(got, lanes);
            ASSERT_EQ(std::memcmp(&got[0], &d0[k], sizeof(double)), 0)
                << "pair " << m << " axis " << k << ": " << got[0] << " vs " << d0[k];
            ASSERT_EQ(std::memcmp(&got[1], &d1[k], sizeof(double)), 0)
                << "pair " << m + 1 << " axis " << k << ": " << got[1] << " vs " << d1[k];
        }
    }
}

TEST(Box, TwoLaneMinimumImageIsBitForBitSeparationInEachLane) {
    expect_two_lanes_bit_for_bit_the_one_pair_form<2>();
    expect_two_lanes_bit_for_bit_the_one_pair_form<3>();
}

}  // namespace
}  // namespace gran
