#pragma once
// Neighbour shells of the event-driven engine for dense gases: the "bounding neighbourhoods" of
// Donev, Torquato & Stillinger, J. Comput. Phys. 202, 737 (2005), the scheme of Smallenburg's EDMD.
//  - Particle i has a shell centred at c_i, the point where its list was last built, and stays
//    within skin / 2 of it: the engine schedules a shell-exit event (shell_exit_time,
//    event_times.hpp) that rebuilds the list around i's new position first.
//  - Two particles can then touch only if |c_i - c_j| <= R_i + R_j + skin, and the lists hold
//    exactly those pairs, each in both lists. A prediction scans i's list (5-15 particles in a
//    dense fluid) instead of the 3^D cells around it, and no particle crosses cells.
//  - A rebuild finds the new neighbours through the engine's cell grid, which holds the centres
//    (cells at least 2 R_max + skin wide) and is updated by CellList::relocate.
//  - A list holds 16-bit indices, so that a 3D row (count and 31 neighbours) is one cache line:
//    at phi 0.5 a scan's cost is mostly the misses on its row and its partners (docs/
//    performance.md, "Lists of 16-bit indices"). Shells therefore hold at most kMaxParticles.
// Bookkeeping only: the engine computes every event time.
#include <emmintrin.h>

#include <cstdint>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/cache_line.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/core/vec.hpp"
#include "libgran/engines/event_driven/cell_list.hpp"

namespace gran {

template <int D>
class NeighbourShells {
  public:
    using Index = std::uint16_t;
    static constexpr std::size_t kMaxParticles = 65535;

    // The per-species contact radii the lists are built with.
    struct Sizes {
        const std::uint32_t* species;
        const double* radius;
    };

    // Shells of width `skin` around every particle at r (at most kMaxParticles), whose centres
    // fill `cells` (built with cells at least 2 R_max + skin wide, no one-cell periodic axis);
    // every list is built.
    void build(const Box<D>& box, double skin, const std::vector<Vec<D>>& r, CellList<D>& cells,
               Sizes sizes);
    // Particle i, now at x, has reached the edge of its shell: a new shell centred at x, and
    // every list it enters or leaves updated.
    void rebuild(std::uint32_t i, const Vec<D>& x, const Box<D>& box, CellList<D>& cells,
                 Sizes sizes);

    double skin() const { return skin_; }
    const Vec<D>& centre(std::uint32_t i) const { return centre_[i]; }
    const Index* list(std::uint32_t i) const { return &rows_[i * stride_ + 1]; }
    std::size_t size(std::uint32_t i) const { return rows_[i * stride_]; }

    // The particles were re-sorted (order[k]: old index of the particle now at k, inv: its
    // inverse); the lists follow them.
    void reorder(const std::vector<std::uint32_t>& order, const std::vector<std::uint32_t>& inv);

    void checkpoint(StateArchive& ar) {
        ar.section("neighbour shells");
        ar.io(skin_);
        ar.io(centre_);
        ar.io(stride_);
        ar.io(rows_);
    }

  private:
    // Whether i and j can meet before one of them leaves its shell; the margin (1e-9 of the
    // reach) covers the round-off of positions at a shell-exit event.
    bool near(const Box<D>& box, std::uint32_t i, std::uint32_t j, Sizes sizes) const {
        const double reach =
            (sizes.radius[sizes.species[i]] + sizes.radius[sizes.species[j]] + skin_) *
            (1.0 + 1e-9);
        return box.separation(centre_[i], centre_[j]).squaredNorm() < reach * reach;
    }
    void add(std::uint32_t i, std::uint32_t j) {
        if (rows_[i * stride_] + 1u == stride_) grow();
        Index* row = &rows_[i * stride_];
        row[1 + row[0]++] = Index(j);
    }
    // Removes j from i's list (order not kept). j is found eight words at a time: the word
    // loop's exit was a misprediction per step of the search (perf, 3D phi 0.5: 13% of the
    // rebuilds' samples). Rows are multiples of 8 words long, the count (word 0, two mask bits)
    // is masked out, and the first match is j's entry (stale words lie after the count's end).
    void drop(std::uint32_t i, std::uint32_t j) {
        Index* row = &rows_[i * stride_];
        const __m128i key = _mm_set1_epi16(short(j));
        std::size_t k = 0;
        for (std::size_t q = 0;; q += 8) {
            const __m128i words = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + q));
            int mask = _mm_movemask_epi8(_mm_cmpeq_epi16(words, key));
            if (q == 0) mask &= ~3;
            if (mask) {
                k = q + std::size_t(__builtin_ctz(unsigned(mask))) / 2;
                break;
            }
        }
        row[k] = row[row[0]--];
    }
    // The candidates of i's new shell within reach, in candidate order, into found_; returns
    // how many. Two at a time, with no branch on the outcome.
    std::size_t within_reach(const Box<D>& box, std::uint32_t i, const std::uint32_t* candidates,
                             std::size_t m, Sizes sizes);
    void grow();

    double skin_ = 0;
    std::vector<Vec<D>> centre_;
    // Per particle a row of stride_ words: the count, then the neighbours (rows double when one
    // fills up).
    std::size_t stride_ = 0;
    std::vector<Index, CacheLineAllocator<Index>> rows_;
    std::vector<std::uint32_t> found_;  // rebuild's scratch (within_reach)
};

extern template class NeighbourShells<2>;
extern template class NeighbourShells<3>;

}  // namespace gran
