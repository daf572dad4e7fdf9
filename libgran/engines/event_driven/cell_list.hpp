#pragma once
// Cell list of the event-driven engine: which particles may meet particle i before one of them
// crosses a cell boundary. The engine owns the physics (collision, crossing and wall times); this
// class owns the grid, the cell contents and the candidates of a scan.
//  - Geometry: cells at least one largest diameter wide; a periodic axis has >= 4 cells or a single
//    one (see build()); at most cell_cap(N) cells. Periodic axes with one cell need every image of
//    a partner within reach tried: image_offsets().
//  - Contents, two layouts chosen by occupancy and size in build():
//    - dense (>= 0.25 particles per cell) and fewer than kMaxBlockParticles particles: one
//      fixed-size block per cell, its count followed by
//      the ids (count and ids share a cache line: at N = 10^6 a separate count array was one more
//      line from memory per cell row of a scan). A scan gathers the ids of all neighbouring cells
//      without branches (whole blocks are copied, the write position advances by the count), so
//      the unpredictable "how many particles in this cell" branch is not paid per cell (+18% at
//      phi 0.2-0.3 in 3D);
//    - dilute, or large: doubly linked lists (a few bytes per mostly empty cell; slots cost -30
//      to -45% at N = 1e5, phi = 0.1, through cache misses). From ~10^5 particles on, the state
//      outgrows the last-level cache and the blocks' empty slots cost more misses than the
//      branches they save: on this machine class (32 MiB L3) linked lists were 1.05-1.2x faster
//      and 10-64 bytes per particle smaller at N = 10^5 to 10^6 (2D phi 0.5, 3D phi 0.2-0.4),
//      while blocks were faster at 7e4 (mostly) and 5e4 (1.2x; docs/performance.md).
//  - Neighbour cells computed from cell coordinates (a per-cell table falls out of cache at 1e5).
// The functions the engine's event loop calls (cross, neighbours, gather) are defined in this
// header so that they inline into it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/cache_line.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/core/vec.hpp"

namespace gran {

// The blocks are allocated on 64-byte boundaries (CacheLineAllocator): a cell's block (32 bytes in
// 3D, 16 in 2D) then never straddles two cache lines, whatever the allocation history (in one
// layout the gather's memcpy of straddling slots took 1.3-1.7x longer: perf, gran_bench_features
// at phi 0.3 in 3D).
// Which layout build() uses: chosen from occupancy and size (automatic), or forced (benchmarks
// that time one layout against the other).
enum class CellLayout { automatic, blocks, lists };

template <int D>
class CellList {
  public:
    static constexpr int kMaxNeighbours = 27;  // room neighbours() needs (3^D written)
    // Systems of this many particles or more use linked lists at any occupancy (the layouts
    // above).
    static constexpr std::size_t kMaxBlockParticles = 100000;

    // Grid for cells at least `width` wide in `box`, filled with the particles at r (inside the
    // box, or within round-off of it: coordinates are clamped).
    void build(const Box<D>& box, double width, const std::vector<Vec<D>>& r,
               CellLayout layout = CellLayout::automatic);

    // The layout build() chose: per-cell blocks (true) or linked lists.
    bool blocks() const { return slots_; }
    std::int32_t cells(int a) const { return ncell_[a]; }
    double width(int a) const { return width_[a]; }
    std::int32_t coordinate(std::uint32_t i, int a) const { return cc_[i][a]; }
    // Periodic axes with one cell (shorter than 4 largest diameters): the minimum image is not
    // enough, a pair may meet through another image before either particle re-predicts (at its
    // next wrap, after travelling at most one period). The scan then tries the images k L,
    // |k| <= 2, along those axes (empty when no axis needs them).
    const std::vector<Vec<D>>& image_offsets() const { return image_offsets_; }

    // Moves particle i one cell along axis a (dir = +1 or -1). Returns +1 if it wrapped past the
    // upper boundary of a periodic axis (its position must move by -L), -1 past the lower one
    // (+L), 0 otherwise.
    int cross(std::uint32_t i, int a, int dir) {
        remove(i);
        auto& c = cc_[i][a];
        c += dir;
        int wrap = 0;
        if (c >= ncell_[a]) {
            c = 0;
            wrap = 1;
        } else if (c < 0) {
            c = ncell_[a] - 1;
            wrap = -1;
        }
        insert(i, id(cc_[i]));
        return wrap;
    }
    // Moves particle i to the cell of point x (inside the box or within round-off of it; clamped
    // like build()): the neighbour shells' centres move by jumps, not crossings.
    void relocate(std::uint32_t i, const Vec<D>& x) {
        remove(i);
        for (int a = 0; a < D; ++a) {
            const auto k = static_cast<std::int32_t>(std::floor(x[a] / width_[a]));
            cc_[i][a] = std::clamp(k, 0, ncell_[a] - 1);
        }
        insert(i, id(cc_[i]));
    }

    // Writes up to 3^D cell ids to out (room for kMaxNeighbours needed) and returns how many
    // are neighbours of i's cell: all of them, or with layer_axis >= 0 only the layer on side
    // layer_dir of that axis (the cells that became adjacent when i crossed in that direction).
    int neighbours(std::uint32_t i, std::int32_t* out, int layer_axis = -1,
                   int layer_dir = 0) const {
        std::int32_t ax[D][3];
        int ok[D][3];
        axis_candidates(i, layer_axis, layer_dir, ax, ok);
        int n = 0;
        if constexpr (D == 2) {
            for (int y = 0; y < 3; ++y) {
                for (int x = 0; x < 3; ++x) {
                    out[n] = ax[1][y] + ax[0][x];
                    n += ok[1][y] & ok[0][x];
                }
            }
        } else {
            for (int z = 0; z < 3; ++z) {
                for (int y = 0; y < 3; ++y) {
                    for (int x = 0; x < 3; ++x) {
                        out[n] = ax[2][z] + ax[1][y] + ax[0][x];
                        n += ok[2][z] & ok[1][y] & ok[0][x];
                    }
                }
            }
        }
        return n;
    }

    // Half of the neighbourhood, for passes that meet every pair once: writes the cells at
    // offsets after (0, ..., 0) in lexicographic order (4 in 2D, 13 in 3D, fewer at a bounded
    // wall) and returns how many. Of the two cells of a neighbouring pair exactly one lists the
    // other, since the offsets o and -o are distinct cells (periodic axes have >= 4 cells; not for
    // one-cell periodic axes, which need images).
    int forward_neighbours(std::uint32_t i, std::int32_t* out) const {
        std::int32_t ax[D][3];
        int ok[D][3];
        axis_candidates(i, -1, 0, ax, ok);
        int n = 0;
        if constexpr (D == 2) {
            for (int k = 5; k < 9; ++k) {
                out[n] = ax[1][k / 3] + ax[0][k % 3];
                n += ok[1][k / 3] & ok[0][k % 3];
            }
        } else {
            for (int k = 14; k < 27; ++k) {
                out[n] = ax[2][k / 9] + ax[1][(k / 3) % 3] + ax[0][k % 3];
                n += ok[2][k / 9] & ok[1][(k / 3) % 3] & ok[0][k % 3];
            }
        }
        return n;
    }
    std::int32_t cell_of(std::uint32_t i) const { return cell_of_[i]; }
    // True when no two points of i's neighbourhood (its cell and the adjacent ones) are
    // separated through a periodic boundary: along every periodic axis i's cell is neither the
    // first nor the last and there are at least 5 cells. Any two such points are then at most
    // 2 widths <= 0.4 periods apart, so Box::separation returns their plain difference and a
    // scan can skip the minimum image (about a third of a pair test's instructions in 3D).
    bool interior(std::uint32_t i) const {
        bool inside = true;
        for (int a = 0; a < D; ++a) {
            const std::int32_t c = cc_[i][a], nc = ncell_[a];
            inside &= !periodic_[a] || (nc >= 5 && c >= 1 && c <= nc - 2);
        }
        return inside;
    }

    // Copies the ids of the particles in the given cells to candidates() (i itself included);
    // returns how many.
    std::size_t gather(const std::int32_t* cells, int ncells) {
        std::uint32_t* buf = gather_.data();
        std::size_t n = 0;
        if (slots_) {
            // The usual block sizes get a copy of constant size, which the compiler inlines as a
            // few vector moves; a copy of run-time size is a libc memmove call per cell (15.6% of
            // the cycles of 3D phi 0.3 in issue 15's profile). Grown blocks take that path.
            switch (stride_) {
                case 4:
                    return gather_slots<4>(cells, ncells, buf);
                case 8:
                    return gather_slots<8>(cells, ncells, buf);
                case 16:
                    return gather_slots<16>(cells, ncells, buf);
                default:
                    break;
            }
            const std::size_t stride = std::size_t(stride_);
            for (int k = 0; k < ncells; ++k) {
                const std::uint32_t* block = &blocks_[std::size_t(cells[k]) * stride];
                std::copy_n(block + 1, stride - 1, buf + n);
                n += block[0];
            }
        } else {
            // A cell's head says whether its first particle has a successor (the tag bit), so a
            // cell of at most one particle is read without a branch on its contents and without
            // its particle's link. Most cells are such cells at the densities where lists are
            // used (0.38 spheres per cell at 3D phi 0.2: were the occupancy Poisson, 82% of the
            // occupied cells would hold one). Only the longer lists are walked. At N = 10^6 every
            // head is a miss; with no branch waiting on them they overlap (docs/performance.md,
            // "Tagged cell heads").
            for (int k = 0; k < ncells; ++k) {
                const std::int32_t h = head_[cells[k]];
                buf[n] = std::uint32_t(h >> 1);  // kEmpty >> 1 = -1: written, not counted
                n += std::size_t(h >= 0);
                if (h & 1) [[unlikely]] {
                    for (std::int32_t j = next_[h >> 1]; j >= 0; j = next_[j])
                        buf[n++] = std::uint32_t(j);
                }
            }
        }
        return n;
    }
    const std::uint32_t* candidates() const { return gather_.data(); }

    // Re-sort support: order[k] is the particle to store at k (counting sort by cell, stable),
    // inv its inverse; reorder() then permutes the per-particle data of the list by it.
    void sort_order(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& inv) const;
    void reorder(const std::vector<std::uint32_t>& order);

  private:
    // Per axis, the three candidate coordinates (offsets -1, 0, +1) as terms of the cell id, and
    // whether each is in the neighbourhood; every combination is then written with fixed trip
    // counts and the write position advanced only for valid ones. The fixed shape lets the
    // compiler keep the per-axis values in registers: the earlier variable-length lists were
    // stored element by element and read back with one vector load, a failed store-to-load
    // forwarding that cost ~8% of all cycles of the bare 2D gas at phi = 0.5 (perf annotate;
    // gran_bench_features).
    void axis_candidates(std::uint32_t i, int layer_axis, int layer_dir, std::int32_t (&ax)[D][3],
                         int (&ok)[D][3]) const {
        std::int32_t stride = 1;
        for (int a = 0; a < D; ++a) {
            const std::int32_t nc = ncell_[a];
            for (int o = 0; o < 3; ++o) {
                std::int32_t c = cc_[i][a] + o - 1;
                bool valid = true;
                if (nc == 1) {
                    // One cell along this axis: a crossing leaves the neighbourhood unchanged.
                    valid = o == 1 && a != layer_axis;
                    c = 0;
                } else {
                    if (a == layer_axis && o - 1 != layer_dir) valid = false;
                    if (c < 0 || c >= nc) {
                        if (!periodic_[a]) valid = false;
                        c = c < 0 ? c + nc : c - nc;
                    }
                }
                ax[a][o] = c * stride;
                ok[a][o] = valid ? 1 : 0;
            }
            stride *= nc;
        }
    }
    template <std::size_t Stride>
    std::size_t gather_slots(const std::int32_t* cells, int ncells, std::uint32_t* buf) const {
        std::size_t n = 0;
        for (int k = 0; k < ncells; ++k) {
            const std::uint32_t* block = &blocks_[std::size_t(cells[k]) * Stride];
            std::memcpy(buf + n, block + 1, (Stride - 1) * sizeof(std::uint32_t));
            n += block[0];
        }
        return n;
    }
    // Linked lists: head_[c] is kEmpty, or (first << 1) | (first has a successor).
    static constexpr std::int32_t kEmpty = -2;  // even: no tag bit; >> 1 gives -1
    std::int32_t first_of(std::int32_t c) const { return head_[c] >> 1; }
    void set_head(std::int32_t c, std::int32_t first) {
        head_[c] = first < 0 ? kEmpty : (first << 1) | std::int32_t(next_[first] >= 0);
    }
    std::int32_t id(const std::array<std::int32_t, D>& cc) const {
        std::int32_t c = 0;
        for (int a = D - 1; a >= 0; --a) c = c * ncell_[a] + cc[a];
        return c;
    }
    void insert(std::uint32_t i, std::int32_t c) {
        cell_of_[i] = c;
        if (!slots_) {
            const std::int32_t first = first_of(c);
            prev_[i] = -1;
            next_[i] = first;
            if (first >= 0) prev_[first] = static_cast<std::int32_t>(i);
            set_head(c, static_cast<std::int32_t>(i));
            return;
        }
        if (std::int32_t(blocks_[std::size_t(c) * stride_]) == stride_ - 1) grow();
        std::uint32_t* block = &blocks_[std::size_t(c) * stride_];
        const auto k = std::int32_t(block[0]++);
        slot_[i] = k;
        block[1 + k] = i;
    }
    void remove(std::uint32_t i) {
        const std::int32_t c = cell_of_[i];
        if (!slots_) {
            if (prev_[i] >= 0) {
                next_[prev_[i]] = next_[i];
            }
            if (next_[i] >= 0) prev_[next_[i]] = prev_[i];
            // The first particle changed, or its successor may have: the tag again.
            set_head(c, prev_[i] >= 0 ? first_of(c) : next_[i]);
            return;
        }
        std::uint32_t* block = &blocks_[std::size_t(c) * stride_];
        std::uint32_t* cell = block + 1;
        const auto last = std::int32_t(--block[0]);
        const std::int32_t k = slot_[i];
        if (k != last) {
            cell[k] = cell[last];
            slot_[cell[k]] = k;
        }
    }

  public:
    // Grid and contents as laid out (the order of a cell's particles is the order of a scan's
    // candidates, which breaks ties between equal collision times).
    void checkpoint(StateArchive& ar) {
        ar.section("cell list");
        ar.io(ncell_);
        ar.io(periodic_);
        ar.io(width_);
        ar.io(image_offsets_);
        ar.io(total_);
        ar.io(n_);
        ar.io(cc_);
        ar.io(cell_of_);
        ar.io(slots_);
        ar.io(slot_);
        ar.io(blocks_);
        ar.io(stride_);
        ar.io(next_);
        ar.io(prev_);
        ar.io(head_);
    }

  private:
    void size_grid(const Box<D>& box, double width, std::size_t n);
    void find_images(const Box<D>& box);
    void grow();

    std::array<std::int32_t, D> ncell_{};
    std::array<bool, D> periodic_{};
    Vec<D> width_ = Vec<D>::Zero();
    std::vector<Vec<D>> image_offsets_;
    std::size_t total_ = 0;                        // cells
    std::size_t n_ = 0;                            // particles
    std::vector<std::array<std::int32_t, D>> cc_;  // cell coordinates per particle
    std::vector<std::int32_t> cell_of_;            // cell id per particle
    bool slots_ = false;
    // dense layout: slot of each particle; per cell a block of stride_ words, the count then up
    // to stride_ - 1 ids
    std::vector<std::int32_t> slot_;
    std::vector<std::uint32_t, CacheLineAllocator<std::uint32_t>> blocks_;
    std::int32_t stride_ = 0;
    void clear_counts() {
        for (std::size_t c = 0; c < total_; ++c) blocks_[c * std::size_t(stride_)] = 0;
    }
    // dilute layout: links per particle (-1: none), first particle per cell with its tag
    // (first_of(), set_head())
    std::vector<std::int32_t> next_, prev_, head_;
    std::vector<std::uint32_t> gather_;  // candidates of one scan
};

extern template class CellList<2>;
extern template class CellList<3>;

}  // namespace gran
