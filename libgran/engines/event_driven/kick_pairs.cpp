#include "libgran/engines/event_driven/kick_pairs.hpp"

namespace gran {

template <int D>
bool KickPairs<D>::build(const Box<D>& box, double skin, double width, const std::vector<Vec<D>>& r,
                         Sizes sizes) {
    built_ = false;
    grid_.build(box, width, r);
    if (!grid_.image_offsets().empty()) {
        clear();
        refused_ = true;
        return false;
    }
    const auto n = std::uint32_t(r.size());
    skin_ = skin;
    origin_ = r;
    start_.assign(std::size_t(n) + 1, 0);
    partner_.clear();
    // Within R_i + R_j + skin, widened by 1e-9 of itself against round-off (as the shells).
    auto keep = [&](std::uint32_t i, std::uint32_t j) {
        const double reach =
            (sizes.radius[sizes.species[i]] + sizes.radius[sizes.species[j]] + skin) * (1.0 + 1e-9);
        if (box.separation(r[i], r[j]).squaredNorm() < reach * reach) partner_.push_back(j);
    };
    // Each pair once: i meets the particles after it in its own cell and those of the forward
    // half of its neighbour cells, and the pair is filed under its lower index. The partners of
    // each i are collected, then sorted into place (counting sort by the lower index).
    std::vector<std::uint32_t> first;  // lower index of each pair found
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::int32_t own = grid_.cell_of(i);
        std::size_t m = grid_.gather(&own, 1);
        const std::size_t before = partner_.size();
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t j = grid_.candidates()[k];
            if (j > i) keep(i, j);
        }
        std::int32_t around[CellList<D>::kMaxNeighbours];
        m = grid_.gather(around, grid_.forward_neighbours(i, around));
        for (std::size_t k = 0; k < m; ++k) keep(i, grid_.candidates()[k]);
        first.resize(partner_.size(), i);
        for (std::size_t k = before; k < partner_.size(); ++k) {
            const std::uint32_t j = partner_[k];
            if (j < i) {
                first[k] = j;
                partner_[k] = i;
            }
        }
    }
    for (std::uint32_t lower : first) ++start_[lower + 1];
    for (std::uint32_t i = 0; i < n; ++i) start_[i + 1] += start_[i];
    std::vector<std::uint32_t> sorted(partner_.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < partner_.size(); ++k) sorted[fill[first[k]]++] = partner_[k];
    partner_.swap(sorted);
    built_ = true;
    return true;
}

template class KickPairs<2>;
template class KickPairs<3>;

}  // namespace gran
