// The DEM neighbour list on several threads (libgran/engines/dem/neighbour_list.cpp): the
// threads' shares of the cell search follow the work, and any shares give the same entries; a
// list whose caller stores the grains sorted searches its cells in that order and finds the same
// pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "libgran/core/random.hpp"
#include "libgran/engines/dem/neighbour_list.hpp"

namespace gran {
namespace {

// Grains of diameter 1 in a 30 x 30 x 60 box, periodic sideways, bounded in z: 6000 of them in
// the lowest sixth (packing fraction about 0.35) and 1500 spread over the rest, like a vibrated
// bed. Cell order runs z slowest, so equal numbers of slots give the first share the dense
// layer and more of the pair tests (1.32 times the second share's).
std::vector<Vec<3>> layered_bed() {
    Rng rng(11);
    std::vector<Vec<3>> r;
    for (int k = 0; k < 7500; ++k) {
        const double top = k < 6000 ? 10.0 : 60.0;
        const double x = 30 * uniform01(rng);  // one statement each: a fixed order of draws
        const double y = 30 * uniform01(rng);
        const double z = top * uniform01(rng);
        r.push_back(Vec<3>(x, y, z));
    }
    return r;
}

DemNeighbourList<3> configured(std::size_t n, bool sorted = false) {
    Box<3> box;
    box.length = Vec<3>(30, 30, 60);
    box.periodic = {true, true, false};
    DemNeighbourList<3> list;
    list.configure(box, {1.2}, 1, n, false, sorted);
    return list;
}

// Each row's partners in increasing order: the pairs, whatever order the search met them in.
std::vector<std::vector<std::uint32_t>> rows(const DemNeighbourList<3>& list) {
    std::vector<std::vector<std::uint32_t>> out(list.start.size() - 1);
    for (std::size_t i = 0; i + 1 < list.start.size(); ++i) {
        out[i].assign(list.partner.begin() + list.start[i],
                      list.partner.begin() + list.start[i + 1]);
        std::sort(out[i].begin(), out[i].end());
    }
    return out;
}

double imbalance(const std::vector<std::uint64_t>& work) {
    const auto [lo, hi] = std::minmax_element(work.begin(), work.end());
    return double(*hi) / double(*lo);
}

TEST(DemNeighbourList, SecondBuildCutsTheThreadsSharesToEvenOutTheirWork) {
    const std::vector<Vec<3>> r = layered_bed();
    const std::vector<std::uint32_t> species(r.size(), 0);
    DemNeighbourList<3> one = configured(r.size());
    DemNeighbourList<3> two = configured(r.size());
    one.build(r, species, 1);
    two.build(r, species, 2);
    ASSERT_EQ(two.search_work().size(), 2u);
    const double first = imbalance(two.search_work());
    EXPECT_GT(first, 1.25) << "equal slots: the dense layer's share does more of the work";
    two.build(r, species, 2);
    const double second = imbalance(two.search_work());
    EXPECT_LT(second, 1.05) << "shares cut by the first build's work";
    // The same entries, in the same order, as one thread finds.
    EXPECT_EQ(two.start, one.start);
    EXPECT_EQ(two.partner, one.partner);
    EXPECT_GT(one.entries(), r.size()) << "the comparison needs pairs";
}

// The grains renumbered in spatial_order() (as the engine stores them), then listed by a list
// that searches x fastest and by one configured `sorted` (its cells in the storage order): the
// same pairs, met in another order; and on 1, 2 and 3 threads (the binning and the search split)
// each finds its own entries in the same order.
TEST(DemNeighbourList, SortedListFindsThePairsOfXFastestCellsOnAnyThreads) {
    const std::vector<Vec<3>> unsorted = layered_bed();
    const std::vector<std::uint32_t> species(unsorted.size(), 0);
    DemNeighbourList<3> x_fastest = configured(unsorted.size());
    const std::vector<std::uint32_t> order = x_fastest.spatial_order(unsorted, species);
    std::vector<Vec<3>> r;
    for (const std::uint32_t i : order) r.push_back(unsorted[i]);
    x_fastest.build(r, species, 1);
    DemNeighbourList<3> sorted = configured(r.size(), true);
    sorted.build(r, species, 1);
    EXPECT_EQ(rows(sorted), rows(x_fastest));
    EXPECT_NE(sorted.partner, x_fastest.partner) << "the search's order should differ";
    for (const int threads : {2, 3}) {
        for (const bool is_sorted : {false, true}) {
            DemNeighbourList<3> split = configured(r.size(), is_sorted);
            split.build(r, species, threads);
            split.build(r, species, threads);  // the shares cut by the work, as in a run
            const DemNeighbourList<3>& one = is_sorted ? sorted : x_fastest;
            EXPECT_EQ(split.start, one.start) << threads << " threads, sorted " << is_sorted;
            EXPECT_EQ(split.partner, one.partner) << threads << " threads, sorted " << is_sorted;
        }
    }
}

}  // namespace
}  // namespace gran
