#include "libgran/engines/event_driven/cell_list.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "libgran/engines/cell_grid.hpp"
#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {

template <int D>
void CellList<D>::build(const Box<D>& box, double width, const std::vector<Vec<D>>& r,
                        CellLayout layout) {
    n_ = r.size();
    // Particle ids are int32 links, and a list's head holds its first id shifted left by one
    // (the tag, cell_list.hpp): ids must stay below 2^30.
    if (n_ >= (std::size_t(1) << 30)) {
        throw std::length_error("CellList: at most 2^30 - 1 particles, " + std::to_string(n_) +
                                " given");
    }
    size_grid(box, width, n_);
    find_images(box);
    slots_ = layout == CellLayout::automatic
                 ? double(n_) >= 0.25 * double(total_) && n_ < kMaxBlockParticles
                 : layout == CellLayout::blocks;
    // Blocks of 16 bytes in 2D (3 disks) and 32 in 3D (7 spheres): 4 equal disks (8 spheres) fit
    // in a cell one diameter wide only in a square (cubic) arrangement with a gap, and smaller
    // species may need more; grow() doubles the blocks then.
    stride_ = D == 2 ? 4 : 8;
    if (slots_) {
        blocks_.assign(total_ * std::size_t(stride_), 0);
    } else {
        head_.assign(total_, kEmpty);
    }
    // A gather copies whole blocks (27 cells' worth at most); a linked-list gather may collect
    // every particle. Each layout keeps only its own per-particle arrays (memory at N = 10^6).
    gather_.assign(slots_ ? 28 * std::size_t(stride_) : n_ + 1, 0);
    cc_.assign(n_, {});
    cell_of_.assign(n_, -1);
    slot_.assign(slots_ ? n_ : 0, 0);
    next_.assign(slots_ ? 0 : n_, -1);
    prev_.assign(slots_ ? 0 : n_, -1);
    for (std::uint32_t i = 0; i < n_; ++i) {
        std::array<std::int32_t, D> cc;
        for (int a = 0; a < D; ++a) {
            auto k = static_cast<std::int32_t>(std::floor(r[i][a] / width_[a]));
            cc[a] = std::clamp(k, 0, ncell_[a] - 1);
        }
        cc_[i] = cc;
        insert(i, id(cc));
    }
}

template <int D>
void CellList<D>::size_grid(const Box<D>& box, double width, std::size_t n) {
    for (int a = 0; a < D; ++a) {
        periodic_[a] = box.periodic[a];
        auto nc = static_cast<std::int64_t>(std::floor(box.length[a] / width));
        // Periodic axes need >= 4 cells: then two particles in adjacent cells are less than half
        // a period apart, so the minimum image is the image through which they can meet before
        // one of them crosses a cell. With 3 cells, particles in cells 0 and 2 (adjacent through
        // the wrap) may recede in the minimum image and meet through the other one without
        // either crossing a cell: collisions were missed (overlaps of up to 35% of a diameter,
        // tests/extremes/test_mass_and_size_ratio.cpp). Fewer means one cell (image_offsets()).
        if (nc < 1 || (box.periodic[a] && nc < 4)) nc = 1;
        ncell_[a] = static_cast<std::int32_t>(nc);
    }
    // Very dilute systems: cap the cell count (memory, empty-cell scans).
    coarsen_cells<D>(ncell_, periodic_, cell_cap(n), 4, 4);
    total_ = 1;
    for (int a = 0; a < D; ++a) {
        width_[a] = box.length[a] / ncell_[a];
        total_ *= std::size_t(ncell_[a]);
    }
}

template <int D>
void CellList<D>::find_images(const Box<D>& box) {
    image_offsets_.clear();
    bool wrapped = false;
    for (int a = 0; a < D; ++a) wrapped = wrapped || (periodic_[a] && ncell_[a] == 1);
    if (!wrapped) return;
    // Every k in {-2..2}^D with k = 0 along the axes that are not one-cell periodic.
    std::array<int, D> k;
    k.fill(-2);
    while (true) {
        Vec<D> off = Vec<D>::Zero();
        bool ok = true;
        for (int a = 0; a < D; ++a) {
            const bool w = periodic_[a] && ncell_[a] == 1;
            if (!w && k[a] != 0) ok = false;
            off[a] = k[a] * box.length[a];
        }
        if (ok) image_offsets_.push_back(off);
        int a = 0;
        while (a < D && ++k[a] > 2) k[a++] = -2;
        if (a == D) break;
    }
}

template <int D>
void CellList<D>::grow() {
    const std::size_t old = std::size_t(stride_), stride = 2 * old;
    decltype(blocks_) grown(total_ * stride, 0);
    for (std::size_t c = 0; c < total_; ++c) {
        std::copy_n(&blocks_[c * old], 1 + blocks_[c * old], &grown[c * stride]);
    }
    blocks_.swap(grown);
    stride_ = std::int32_t(stride);
    gather_.assign(28 * stride, 0);
}

template <int D>
void CellList<D>::sort_order(std::vector<std::uint32_t>& order,
                             std::vector<std::uint32_t>& inv) const {
    // Counting sort of particles by cell: neighbours in space become neighbours in memory, so a
    // cell scan touches few cache lines.
    std::vector<std::uint32_t> start(total_ + 1, 0);
    for (std::size_t i = 0; i < n_; ++i) ++start[std::size_t(cell_of_[i]) + 1];
    for (std::size_t c = 0; c < total_; ++c) start[c + 1] += start[c];
    order.assign(n_, 0);
    inv.assign(n_, 0);
    for (std::uint32_t i = 0; i < n_; ++i) {
        const std::uint32_t k = start[std::size_t(cell_of_[i])]++;
        order[k] = i;
        inv[i] = k;
    }
}

template <int D>
void CellList<D>::reorder(const std::vector<std::uint32_t>& order) {
    apply_order(cc_, order);
    apply_order(cell_of_, order);
    // Refilled in the new order, so each cell's contents run in increasing storage order.
    if (slots_) clear_counts();
    std::fill(head_.begin(), head_.end(), kEmpty);
    for (std::size_t k = 0; k < n_; ++k) insert(std::uint32_t(k), cell_of_[k]);
}

template class CellList<2>;
template class CellList<3>;

}  // namespace gran
