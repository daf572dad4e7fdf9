#include "libgran/engines/event_driven/neighbour_shells.hpp"

#include <algorithm>
#include <stdexcept>

#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {

template <int D>
void NeighbourShells<D>::build(const Box<D>& box, double skin, const std::vector<Vec<D>>& r,
                               CellList<D>& cells, Sizes sizes) {
    if (r.size() > kMaxParticles) {
        throw std::invalid_argument(
            "NeighbourShells: at most 65535 particles (16-bit lists); use the cell list "
            "(engine.neighbour_skin: 0)");
    }
    skin_ = skin;
    centre_ = r;
    const auto n = std::uint32_t(r.size());
    // Rows of 16 words in 2D, 32 in 3D (half a cache line and one): room for a dense fluid's
    // neighbours at the skins the engine picks; grow() doubles them otherwise.
    stride_ = D == 2 ? 16 : 32;
    rows_.assign(std::size_t(n) * stride_, 0);
    // Each pair once: i meets the particles after it in its own cell and those of the forward
    // half of its neighbour cells (as EventDrivenEngine::predict_all).
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::int32_t own = cells.cell_of(i);
        std::size_t m = cells.gather(&own, 1);
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t j = cells.candidates()[k];
            if (j > i && near(box, i, j, sizes)) {
                add(i, j);
                add(j, i);
            }
        }
        std::int32_t around[CellList<D>::kMaxNeighbours];
        m = cells.gather(around, cells.forward_neighbours(i, around));
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t j = cells.candidates()[k];
            if (near(box, i, j, sizes)) {
                add(i, j);
                add(j, i);
            }
        }
    }
}

template <int D>
void NeighbourShells<D>::rebuild(std::uint32_t i, const Vec<D>& x, const Box<D>& box,
                                 CellList<D>& cells, Sizes sizes) {
    {
        const Index* row = &rows_[i * stride_];
        for (std::uint32_t k = 1; k <= row[0]; ++k) drop(row[k], i);
        rows_[i * stride_] = 0;
    }
    centre_[i] = x;
    cells.relocate(i, x);
    std::int32_t around[CellList<D>::kMaxNeighbours];
    const std::size_t m = cells.gather(around, cells.neighbours(i, around));
    // The same pairs in the same order as a test of near() per candidate: the lists, and so the
    // scans' candidate order, are unchanged.
    const std::size_t kept = within_reach(box, i, cells.candidates(), m, sizes);
    for (std::size_t k = 0; k < kept; ++k) {
        add(i, found_[k]);
        add(found_[k], i);
    }
}

template <int D>
std::size_t NeighbourShells<D>::within_reach(const Box<D>& box, std::uint32_t i,
                                             const std::uint32_t* candidates, std::size_t m,
                                             Sizes sizes) {
    if (found_.size() < m) found_.resize(2 * m);
    std::uint32_t* found = found_.data();
    const MinimumImageTwo<D> image(box);
    __m128d ci[D];
    for (int k = 0; k < D; ++k) ci[k] = _mm_set1_pd(centre_[i][k]);
    // near()'s reach, squared, for a partner j: each lane holds the scalar products.
    const double ri = sizes.radius[sizes.species[i]];
    auto reach2 = [&](std::uint32_t j) {
        const double reach = (ri + sizes.radius[sizes.species[j]] + skin_) * (1.0 + 1e-9);
        return reach * reach;
    };
    std::size_t kept = 0, k = 0;
    for (; k + 2 <= m; k += 2) {
        const std::uint32_t j0 = candidates[k], j1 = candidates[k + 1];
        // |separation|^2 summed x, y, z in Eigen's order, each lane as near() computes it.
        __m128d d2 = _mm_setzero_pd();
        for (int a = 0; a < D; ++a) {
            const __m128d d =
                image(_mm_sub_pd(ci[a], _mm_set_pd(centre_[j1][a], centre_[j0][a])), a);
            d2 = a == 0 ? _mm_mul_pd(d, d) : _mm_add_pd(d2, _mm_mul_pd(d, d));
        }
        const int in = _mm_movemask_pd(_mm_cmplt_pd(d2, _mm_set_pd(reach2(j1), reach2(j0))));
        found[kept] = j0;
        kept += std::size_t((in & 1) & int(j0 != i));
        found[kept] = j1;
        kept += std::size_t((in >> 1) & int(j1 != i));
    }
    for (; k < m; ++k) {
        const std::uint32_t j = candidates[k];
        found[kept] = j;
        kept += std::size_t(j != i && near(box, i, j, sizes));
    }
    return kept;
}

template <int D>
void NeighbourShells<D>::grow() {
    const std::size_t old = stride_, stride = 2 * old, n = rows_.size() / old;
    decltype(rows_) grown(n * stride, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::copy_n(&rows_[i * old], 1 + rows_[i * old], &grown[i * stride]);
    }
    rows_.swap(grown);
    stride_ = stride;
}

template <int D>
void NeighbourShells<D>::reorder(const std::vector<std::uint32_t>& order,
                                 const std::vector<std::uint32_t>& inv) {
    apply_order(centre_, order);
    apply_order_rows(rows_, stride_, order);
    for (std::size_t i = 0; i < order.size(); ++i) {
        Index* row = &rows_[i * stride_];
        for (std::uint32_t k = 1; k <= row[0]; ++k) row[k] = Index(inv[row[k]]);
    }
}

template class NeighbourShells<2>;
template class NeighbourShells<3>;

}  // namespace gran
