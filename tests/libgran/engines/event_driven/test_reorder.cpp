// The in-place permutation of the engine's per-particle arrays at a re-sort: the same result as
// gathering into a new array, v[k] = old v[order[k]], for every shape of permutation.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {
namespace {

void expect_gather(const std::vector<std::uint32_t>& order) {
    std::vector<double> v(order.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 1.5 * double(i) + 0.25;
    std::vector<double> expected(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) expected[k] = v[order[k]];
    apply_order(v, order);
    EXPECT_EQ(v, expected);
}

TEST(ApplyOrder, PermutesInPlaceAsAGatherForRandomPermutations) {
    std::mt19937 rng(3);
    for (std::size_t n : {1, 2, 3, 10, 1000, 65537}) {
        std::vector<std::uint32_t> order(n);
        std::iota(order.begin(), order.end(), 0u);
        std::shuffle(order.begin(), order.end(), rng);
        expect_gather(order);
    }
}

TEST(ApplyOrder, KeepsFixedPointsAndHandlesOneLongCycleAndSwaps) {
    std::vector<std::uint32_t> identity(100);
    std::iota(identity.begin(), identity.end(), 0u);
    expect_gather(identity);
    std::vector<std::uint32_t> rotation(100);  // one cycle through every position
    for (std::uint32_t k = 0; k < 100; ++k) rotation[k] = (k + 1) % 100;
    expect_gather(rotation);
    std::vector<std::uint32_t> swaps = identity;  // 50 cycles of two
    for (std::uint32_t k = 0; k < 100; k += 2) std::swap(swaps[k], swaps[k + 1]);
    expect_gather(swaps);
}

TEST(ApplyOrder, LeavesAnEmptyArrayEmpty) {
    std::vector<double> none;
    apply_order(none, std::vector<std::uint32_t>{1, 0});
    EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace gran
