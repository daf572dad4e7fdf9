#include "libgran/engines/event_driven/neighbour_shells.hpp"

#include <algorithm>

#include "libgran/engines/event_driven/reorder.hpp"

namespace gran {

template <int D>
void NeighbourShells<D>::build(const Box<D>& box, double skin, const std::vector<Vec<D>>& r,
                               CellList<D>& cells, Sizes sizes) {
    skin_ = skin;
    centre_ = r;
    const auto n = std::uint32_t(r.size());
    // Rows of 16 words in 2D, 32 in 3D (one and two cache lines): room for a dense fluid's
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
        const std::uint32_t* row = &rows_[i * stride_];
        for (std::uint32_t k = 1; k <= row[0]; ++k) drop(row[k], i);
        rows_[i * stride_] = 0;
    }
    centre_[i] = x;
    cells.relocate(i, x);
    std::int32_t around[CellList<D>::kMaxNeighbours];
    const std::size_t m = cells.gather(around, cells.neighbours(i, around));
    const std::uint32_t* candidates = cells.candidates();
    for (std::size_t k = 0; k < m; ++k) {
        const std::uint32_t j = candidates[k];
        if (j != i && near(box, i, j, sizes)) {
            add(i, j);
            add(j, i);
        }
    }
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
        std::uint32_t* row = &rows_[i * stride_];
        for (std::uint32_t k = 1; k <= row[0]; ++k) row[k] = inv[row[k]];
    }
}

template class NeighbourShells<2>;
template class NeighbourShells<3>;

}  // namespace gran
