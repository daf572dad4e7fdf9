// Cell list of the event-driven engine: a scan's candidates are exactly the particles of the
// neighbouring cells, in both layouts (per-cell blocks, linked lists), after crossings, after a
// block overflows and grows, and after a re-sort.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "libgran/engines/event_driven/cell_list.hpp"

namespace gran {
namespace {

constexpr int kCells = 8;  // per axis, cells of width 1 in a periodic cube of side 8

Box<3> periodic_cube() {
    Box<3> box;
    box.length = Vec<3>::Constant(kCells);
    box.periodic.fill(true);
    return box;
}

// n positions, uniform in the cube, and `crowd` more inside the cell (2, 3, 4).
std::vector<Vec<3>> positions(std::size_t n, std::size_t crowd, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, kCells), in_cell(0.0, 1.0);
    std::vector<Vec<3>> r;
    for (std::size_t i = 0; i < n; ++i) r.push_back(Vec<3>(u(rng), u(rng), u(rng)));
    for (std::size_t i = 0; i < crowd; ++i) {
        r.push_back(Vec<3>(2 + in_cell(rng), 3 + in_cell(rng), 4 + in_cell(rng)));
    }
    return r;
}

// The particles whose cells are within one cell of i's along every (periodic) axis: what a full
// scan must return, from the list's own cell coordinates.
std::multiset<std::uint32_t> brute_force_neighbourhood(const CellList<3>& cells, std::size_t n,
                                                       std::uint32_t i) {
    std::multiset<std::uint32_t> out;
    for (std::uint32_t j = 0; j < n; ++j) {
        bool near = true;
        for (int a = 0; a < 3; ++a) {
            const int d = std::abs(cells.coordinate(j, a) - cells.coordinate(i, a));
            near = near && (d <= 1 || d == kCells - 1);
        }
        if (near) out.insert(j);
    }
    return out;
}

std::multiset<std::uint32_t> scanned(CellList<3>& cells, std::uint32_t i) {
    std::int32_t ids[CellList<3>::kMaxNeighbours];
    const std::size_t m = cells.gather(ids, cells.neighbours(i, ids));
    return {cells.candidates(), cells.candidates() + m};
}

void expect_every_scan_exact(CellList<3>& cells, std::size_t n) {
    for (std::uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(scanned(cells, i), brute_force_neighbourhood(cells, n, i)) << "particle " << i;
    }
}

// Random crossings, each checked against the particle's new coordinate.
void cross_at_random(CellList<3>& cells, std::size_t n, int crossings, unsigned seed) {
    std::mt19937 rng(seed);
    for (int k = 0; k < crossings; ++k) {
        const auto i = std::uint32_t(rng() % n);
        const int a = int(rng() % 3);
        const int dir = rng() % 2 ? 1 : -1;
        const int before = cells.coordinate(i, a);
        const int wrap = cells.cross(i, a, dir);
        EXPECT_EQ(cells.coordinate(i, a), ((before + dir) % kCells + kCells) % kCells);
        EXPECT_EQ(wrap, before + dir >= kCells ? 1 : before + dir < 0 ? -1 : 0);
    }
}

void check_layout(std::size_t uniform, std::size_t crowd, bool blocks,
                  CellLayout layout = CellLayout::automatic) {
    const auto r = positions(uniform, crowd, 7);
    const std::size_t n = r.size();
    CellList<3> cells;
    cells.build(periodic_cube(), 1.0, r, layout);
    ASSERT_EQ(cells.cells(0), kCells);
    ASSERT_EQ(cells.blocks(), blocks);
    expect_every_scan_exact(cells, n);
    cross_at_random(cells, n, 5000, 11);
    expect_every_scan_exact(cells, n);
    // A re-sort permutes the particles: particle k of the new order is the old order[k].
    std::vector<std::uint32_t> order, inv;
    cells.sort_order(order, inv);
    std::vector<std::array<int, 3>> before(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        for (int a = 0; a < 3; ++a) before[i][std::size_t(a)] = cells.coordinate(i, a);
    }
    cells.reorder(order);
    for (std::uint32_t k = 0; k < n; ++k) {
        EXPECT_EQ(inv[order[k]], k);
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(cells.coordinate(k, a), before[order[k]][std::size_t(a)]);
        }
        // Stored in cell order: the cell ids never decrease.
        if (k > 0) {
            EXPECT_LE(cells.cell_of(k - 1), cells.cell_of(k));
        }
    }
    expect_every_scan_exact(cells, n);
}

TEST(CellList, BlocksOfADenseGridGatherExactlyTheNeighbourCellsAcrossCrossingsAndResorts) {
    check_layout(400, 0, true);  // 0.78 particles per cell: blocks
}

TEST(CellList, ACellOverflowingItsBlockGrowsAndKeepsEveryParticle) {
    // 7 ids fit a 3D block; 40 in one cell make the blocks grow three times (to 63 ids), at
    // build and while
    // particles cross into and out of the crowd.
    check_layout(400, 40, true);
}

TEST(CellList, LinkedListsOfADiluteGridGatherExactlyTheNeighbourCells) {
    check_layout(60, 5, false);  // 0.12 particles per cell: linked lists
}

TEST(CellList, LinkedListsOfACrowdedGridKeepEveryParticleAsCellsFillAndEmpty) {
    // Lists forced at 0.86 particles per cell and a crowd of 40: cells go from one particle to
    // several and back at every crossing, so a head's tag (its first particle has a successor)
    // is set and cleared from every position in a list.
    check_layout(400, 40, false, CellLayout::lists);
}

// n particles on a simple cubic lattice at 0.8 per cell (cells of width 1).
CellList<3> lattice_cells(std::size_t n) {
    const double side = std::cbrt(double(n) / 0.8);
    const auto per_row = std::size_t(std::ceil(std::cbrt(double(n))));
    const double spacing = side / double(per_row);
    std::vector<Vec<3>> r;
    for (std::size_t k = 0; r.size() < n; ++k) {
        r.push_back(spacing * Vec<3>(double(k % per_row) + 0.5, double(k / per_row % per_row) + 0.5,
                                     double(k / per_row / per_row) + 0.5));
    }
    Box<3> box;
    box.length = Vec<3>::Constant(side);
    box.periodic.fill(true);
    CellList<3> cells;
    cells.build(box, 1.0, r);
    return cells;
}

TEST(CellList, ADenseGridUsesBlocksUpToTheSizeWhereLinkedListsBecomeFaster) {
    // Both grids hold ~0.8 particles per cell; beyond kMaxBlockParticles the state outgrows the
    // last-level cache and linked lists are faster and smaller (cell_list.hpp).
    EXPECT_TRUE(lattice_cells(CellList<3>::kMaxBlockParticles - 1000).blocks());
    CellList<3> large = lattice_cells(CellList<3>::kMaxBlockParticles + 1000);
    EXPECT_FALSE(large.blocks());
    // The large grid's scans are still exact (a sample of particles).
    const std::size_t n = CellList<3>::kMaxBlockParticles + 1000;
    for (std::uint32_t i = 0; i < n; i += 9973) {
        std::multiset<std::uint32_t> expected;
        for (std::uint32_t j = 0; j < n; ++j) {
            bool near = true;
            for (int a = 0; a < 3; ++a) {
                const int d = std::abs(large.coordinate(j, a) - large.coordinate(i, a));
                near = near && (d <= 1 || d == large.cells(a) - 1);
            }
            if (near) expected.insert(j);
        }
        EXPECT_EQ(scanned(large, i), expected) << "particle " << i;
    }
}

// CellList::interior lets a scan skip the minimum image: for every interior particle, each
// particle of its neighbourhood is separated from it by the plain difference, bit for bit. The
// first and last cells of a periodic axis are never interior (there the neighbourhood wraps and
// some pair needs the image), nor is any cell of a periodic axis with fewer than 5 cells; a
// bounded axis does not restrict it.
TEST(CellList, InteriorParticlesMeetTheirWholeNeighbourhoodWithoutAPeriodicImage) {
    for (const int cells_per_axis : {4, 5, 8}) {
        Box<3> box;
        box.length = Vec<3>::Constant(cells_per_axis);
        box.periodic = {true, true, false};
        std::mt19937 rng(31);
        std::uniform_real_distribution<double> u(0.0, cells_per_axis);
        std::vector<Vec<3>> r;
        for (int k = 0; k < 40 * cells_per_axis * cells_per_axis * cells_per_axis; ++k) {
            r.push_back(Vec<3>(u(rng), u(rng), u(rng)));
        }
        CellList<3> cells;
        cells.build(box, 1.0, r);
        ASSERT_EQ(cells.cells(0), cells_per_axis);
        std::size_t inside = 0, wrapping_outside = 0;
        for (std::uint32_t i = 0; i < r.size(); ++i) {
            bool expected = cells_per_axis >= 5;
            for (int a = 0; a < 2; ++a) {
                const int c = cells.coordinate(i, a);
                expected = expected && c >= 1 && c <= cells_per_axis - 2;
            }
            ASSERT_EQ(cells.interior(i), expected) << "particle " << i;
            bool wraps = false;
            for (std::uint32_t j : scanned(cells, i)) {
                const Vec<3> plain = r[i] - r[j];
                if (cells.interior(i)) {
                    ASSERT_EQ(box.separation(r[i], r[j]), plain) << i << " and " << j;
                }
                wraps = wraps || box.separation(r[i], r[j]) != plain;
            }
            inside += cells.interior(i);
            wrapping_outside += !cells.interior(i) && wraps;
        }
        // The check above ran, and the excluded cells are the ones that needed excluding.
        EXPECT_EQ(inside == 0, cells_per_axis == 4);
        EXPECT_GT(wrapping_outside, r.size() / 4);
    }
}

}  // namespace
}  // namespace gran
