#pragma once
// Sizing of the uniform cell grids of both engines (the event-driven cell list and the DEM
// neighbour list). How many cells an axis wants is each engine's own rule (the event-driven one
// needs >= 4 cells on a periodic axis for its minimum-image argument, the DEM half stencil >= 3);
// the cap on the total and the coarsening towards it are shared.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace gran {

// Most cells a grid for n particles may have: about 8 per particle (memory, and the scans of
// empty cells in very dilute systems), at least 2^16.
inline std::size_t cell_cap(std::size_t n) {
    return std::max<std::size_t>(std::size_t(1) << 16, 8 * n);
}

// Halves the axis with the most cells (the first of equals) until the grid holds at most `cap`
// cells. A halved axis keeps at least `min_periodic` cells if periodic, `min_bounded` otherwise,
// and the coarsening gives up once the largest axis has `min_periodic` cells or fewer.
template <int D>
void coarsen_cells(std::array<std::int32_t, D>& ncell, const std::array<bool, D>& periodic,
                   std::size_t cap, std::int32_t min_periodic, std::int32_t min_bounded) {
    for (;;) {
        std::size_t total = 1;
        for (std::size_t a = 0; a < std::size_t(D); ++a) total *= std::size_t(ncell[a]);
        if (total <= cap) return;
        std::size_t a_max = 0;
        for (std::size_t a = 1; a < std::size_t(D); ++a) {
            if (ncell[a] > ncell[a_max]) a_max = a;
        }
        if (ncell[a_max] <= min_periodic) return;
        ncell[a_max] = std::max(ncell[a_max] / 2, periodic[a_max] ? min_periodic : min_bounded);
    }
}

}  // namespace gran
