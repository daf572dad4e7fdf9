#pragma once
// Verlet neighbour list with a skin for the DEM engine, built through a cell list.
//
//  - Half list in compressed rows: the partners j > i of particle i are partner[start[i]] ..
//    partner[start[i + 1] - 1], sorted by j, for every pair closer than its cutoff
//    sigma_ij + skin (minimum image on periodic axes).
//  - Cells at least one largest cutoff wide; periodic axes with fewer than 3 cells use a single
//    cell (all images are then found by the minimum-image separation, which the caller keeps
//    unique by requiring cutoffs below half the box length). Bounded axes clamp positions outside
//    [0, L) into the edge cells.
//  - Each entry carries the contact state of the pair (touching at the last force evaluation)
//    and, when `history` is on, its tangential spring. Both are carried over to the next build by
//    merging the sorted rows: a pair in contact is closer than sigma_ij, hence in the new list.
//  - No allocation in steady state: every buffer keeps its capacity across builds.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "libgran/box.hpp"
#include "libgran/vec.hpp"

namespace gran {

template <int D>
class DemNeighbourList {
  public:
    // cutoff: ns x ns pair cutoffs sigma_ij + skin. history: keep tangential springs per entry.
    void configure(const Box<D>& box, std::vector<double> cutoff, std::size_t ns,
                   std::size_t n_particles, bool history);
    void build(const Box<D>& box, const std::vector<Vec<D>>& r,
               const std::vector<std::uint32_t>& species);

    std::size_t entries() const { return partner.size(); }
    std::size_t cells() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

    std::vector<std::uint32_t> start;    // n + 1 row offsets
    std::vector<std::uint32_t> partner;  // j > i
    std::vector<std::uint8_t> touching;  // 1: in contact at the last force evaluation
    std::vector<Vec<D>> spring;          // tangential spring xi (history laws only)

  private:
    std::int32_t cell_of(const Vec<D>& x) const;

    bool history_ = false;
    std::size_t ns_ = 0;
    std::vector<double> cutoff2_;  // ns x ns
    std::array<std::int32_t, D> ncell_{};
    std::array<std::int32_t, D> stride_{};
    std::array<bool, D> periodic_{};
    Vec<D> inv_width_ = Vec<D>::Zero();
    std::vector<std::int32_t> cell_;  // per particle
    std::vector<std::uint32_t> cell_start_, cell_members_, cursor_;
    // The previous list, kept to carry the contact state over.
    std::vector<std::uint32_t> old_start_, old_partner_;
    std::vector<std::uint8_t> old_touching_;
    std::vector<Vec<D>> old_spring_;
};

extern template class DemNeighbourList<2>;
extern template class DemNeighbourList<3>;

}  // namespace gran
