#pragma once
// Verlet neighbour list with a skin for the DEM engine, built through a cell list.
//
//  - Half list in compressed rows: the partners j > i of particle i are partner[start[i]] ..
//    partner[start[i + 1] - 1] (in no particular order), for every pair closer than its cutoff
//    sigma_ij + skin (minimum image on periodic axes).
//  - Build: the particles are binned once per build (one cell index per particle, counting sort,
//    positions and species copied in cell order), then every non-empty cell is paired with itself
//    and with the 13 (3D; 4 in 2D) cells of a half stencil, through per-axis neighbour tables that
//    wrap periodic axes and carry the image shift, so every pair of adjacent cells is visited once
//    and no separation needs a minimum-image test.
//  - Cells at least one largest cutoff wide. Periodic axes with fewer than 3 cells use a single
//    cell (those pairs take the minimum-image separation, which the caller keeps unique by
//    requiring cutoffs below half the box length). Bounded axes are binned over the range the
//    particles occupy at the build (a tall, open box costs no empty cells); the grid is coarsened
//    to at most ~8 cells per particle.
//  - Each entry carries the contact state of the pair (touching at the last force evaluation)
//    and, when `history` is on, its tangential spring. Only the entries in contact are carried
//    over to the next build (a pair in contact is closer than sigma_ij, hence in the new list).
//  - On several threads, each bins its share of the particles into the slots one thread gives
//    them (per-thread counts per cell: 4 bytes per cell and thread, at most max(8 N, 2^16)
//    cells), then searches the cells whose particles fall in its share of the slots into its own
//    segment; the segments in thread order are the one-thread sequence of pairs and the rows are
//    filled as that sequence would fill them: the same entries in the same order.
//  - No allocation in steady state: every buffer keeps its capacity across builds.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/core/vec.hpp"

namespace gran {

template <int D>
class DemNeighbourList {
  public:
    // cutoff: ns x ns pair cutoffs sigma_ij + skin. history: keep tangential springs per entry.
    // sorted: the caller stores its particles in spatial_order()'s order; the builds then bin
    // and search the cells in that order too, so both walk the particles' memory forwards.
    void configure(const Box<D>& box, std::vector<double> cutoff, std::size_t ns,
                   std::size_t n_particles, bool history, bool sorted = false);
    // On `threads` threads: the same entries in the same order for any count. `new_index`: the
    // particles were renumbered since the last build (the one at i is now at new_index[i]), so
    // the contacts carried over are renumbered too; null: they were not.
    void build(const std::vector<Vec<D>>& r, const std::vector<std::uint32_t>& species,
               int threads = 1, const std::uint32_t* new_index = nullptr);
    // The particles in the order of this grid's cells, increasing index within a cell: slot ->
    // particle. Neighbours in space then lie near each other in memory (the engine renumbers its
    // particles in this order, DemEngine::sort_particles). The periodic axis of most cells runs
    // slowest (x fastest otherwise): cut into consecutive shares of the grains (the threads' rows
    // of the pair loop), the bed is cut across that axis, where the cut meets the fewest grains
    // (in a bed on a floor the density varies along the bounded axis, and a cut across it went
    // through 10% of the grains of a wide bed at N = 10^5). Configured `sorted`, the builds'
    // cells run in this order too; otherwise x fastest.
    const std::vector<std::uint32_t>& spatial_order(const std::vector<Vec<D>>& r,
                                                    const std::vector<std::uint32_t>& species) {
        grid(r, true);
        bin(r, species);
        return order_;
    }

    std::size_t entries() const { return partner.size(); }
    // Per thread, the work of its share of the last build's search: pair tests and stencil
    // visits. The next build's shares are cut to even it out (balance_search).
    const std::vector<std::uint64_t>& search_work() const { return search_work_; }
    // Per thread, the wall-clock seconds of its share of the last build's search (the pair tests
    // and stencil visits, and the pairs written to its segment): how the search scales.
    const std::vector<double>& search_seconds() const { return search_seconds_; }
    std::size_t cells() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

    std::vector<std::uint32_t> start;    // n + 1 row offsets
    std::vector<std::uint32_t> partner;  // j > i
    std::vector<std::uint32_t> owner;    // i of each entry (the row it belongs to)
    std::vector<std::uint8_t> touching;  // 1: in contact at the last force evaluation
    std::vector<Vec<D>> spring;          // tangential spring xi (history laws only)
    // The entries in their order (the order forces are summed in) with their contact state, and
    // the grid of the last build; the rest is rebuilt by each build.
    void checkpoint(StateArchive& ar) {
        ar.section("dem neighbour list");
        ar.io(start);
        ar.io(partner);
        ar.io(owner);
        ar.io(touching);
        ar.io(spring);
        ar.io(ncell_);
        ar.io(stride_);
        ar.io(lo_);
        ar.io(inv_width_);
        ar.io(min_image_);
        ar.io(near_);
        ar.io(shift_);
        ar.io(cell_start_);
    }

  private:
    static constexpr int kStencil = D == 2 ? 4 : 13;  // half of the 3^D - 1 neighbour offsets
    struct Carried {
        std::uint32_t i, j;
        Vec<D> spring;
    };

    void grid(const std::vector<Vec<D>>& r, bool across_periodic = false);
    std::uint32_t cell_index(const Vec<D>& x) const;
    void bin(const std::vector<Vec<D>>& r, const std::vector<std::uint32_t>& species,
             int threads = 1);
    template <bool MinImage>
    std::uint64_t find_pairs(std::size_t c0, std::size_t c1, std::vector<std::uint64_t>& out) const;
    void find_rows(std::size_t n, int threads);
    void balance_search(std::size_t n, std::size_t parts);

    bool history_ = false;
    bool sorted_ = false;  // builds bin in spatial_order()'s axis order
    std::size_t ns_ = 0;
    double widest_ = 0;
    std::size_t cap_ = 0;          // most cells
    std::vector<double> cutoff2_;  // ns x ns
    std::array<bool, D> periodic_{};
    std::array<double, D> length_{};
    std::array<std::int32_t, D> ncell_{};
    std::array<std::int32_t, D> stride_{};
    std::array<std::size_t, D> axes_{};  // the axes from the fastest-running stride to the slowest
    std::array<double, D> lo_{}, inv_width_{};
    bool min_image_ = false;  // a periodic axis has a single cell
    std::array<std::array<std::int8_t, D>, kStencil> stencil_{};
    // Per axis, 3 entries per cell coordinate (offsets -1, 0, 1): the neighbour's coordinate
    // (-1: none) and the shift added to x_i - x_j (the periodic image).
    std::array<std::vector<std::int32_t>, D> near_;
    std::array<std::vector<double>, D> shift_;

    std::vector<std::uint32_t> cell_;        // per particle
    std::vector<std::uint32_t> cell_start_;  // cells + 1
    std::vector<std::uint32_t> order_;       // slot (cell order) -> particle
    std::vector<Vec<D>> xs_;                 // positions by slot
    std::vector<std::uint32_t> ss_;          // species by slot
    std::vector<Carried> carried_;
    // Per thread: its pairs i << 32 | j (i < j) in cell order, and its pairs per row.
    std::vector<std::vector<std::uint64_t>> segments_;
    std::vector<std::vector<std::uint32_t>> row_count_;
    // Per thread: the first slot it searches (parts + 1 cuts), and its work at the last build,
    // pair tests and stencil visits (balance_search).
    std::vector<std::size_t> search_split_, search_cut_;
    std::vector<std::uint64_t> search_work_;
    std::vector<double> search_seconds_;
    // bin() on several threads: per thread, its grains per cell, then its next slot per cell;
    // and the grains of each thread's share of the cells.
    std::vector<std::vector<std::uint32_t>> bin_count_;
    std::vector<std::uint32_t> bin_total_;
};

extern template class DemNeighbourList<2>;
extern template class DemNeighbourList<3>;

}  // namespace gran
