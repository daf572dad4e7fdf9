#include "libgran/dem_neighbour_list.hpp"

#include <algorithm>
#include <cmath>

namespace gran {

template <int D>
void DemNeighbourList<D>::configure(const Box<D>& box, std::vector<double> cutoff, std::size_t ns,
                                    std::size_t n_particles, bool history) {
    history_ = history;
    ns_ = ns;
    cutoff2_ = std::move(cutoff);
    double widest = 0;
    for (double& c : cutoff2_) {
        widest = std::max(widest, c);
        c *= c;
    }
    std::int64_t total = 1;
    for (int a = 0; a < D; ++a) {
        periodic_[std::size_t(a)] = box.periodic[std::size_t(a)];
        auto nc = static_cast<std::int64_t>(std::floor(box.length[a] / widest));
        if (nc < 1 || (box.periodic[std::size_t(a)] && nc < 3)) nc = 1;
        ncell_[std::size_t(a)] = static_cast<std::int32_t>(nc);
        total *= nc;
    }
    // Tall, dilute boxes: at most ~8 cells per particle (memory, empty-cell sweeps at builds).
    const std::int64_t cap = std::max<std::int64_t>(1 << 16, 8 * std::int64_t(n_particles));
    while (total > cap) {
        std::size_t a_max = 0;
        for (std::size_t a = 1; a < std::size_t(D); ++a) {
            if (ncell_[a] > ncell_[a_max]) a_max = a;
        }
        if (ncell_[a_max] <= 3) break;
        total /= ncell_[a_max];
        ncell_[a_max] = std::max(ncell_[a_max] / 2, 3);
        total *= ncell_[a_max];
    }
    std::int32_t stride = 1;
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        stride_[a] = stride;
        stride *= ncell_[a];
        inv_width_[int(a)] = ncell_[a] / box.length[int(a)];
    }
    cell_start_.assign(std::size_t(total) + 1, 0);
    start.assign(n_particles + 1, 0);
    partner.clear();
    touching.clear();
    spring.clear();
    old_start_.clear();
}

template <int D>
std::int32_t DemNeighbourList<D>::cell_of(const Vec<D>& x) const {
    std::int32_t id = 0;
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        double f = std::floor(x[int(a)] * inv_width_[int(a)]);
        const double top = ncell_[a] - 1;
        if (!(f >= 0)) f = 0;  // also NaN
        if (f > top) f = top;
        id += static_cast<std::int32_t>(f) * stride_[a];
    }
    return id;
}

template <int D>
void DemNeighbourList<D>::build(const Box<D>& box, const std::vector<Vec<D>>& r,
                                const std::vector<std::uint32_t>& species) {
    const std::size_t n = r.size();
    // Counting sort of the particles by cell (stable: increasing index within a cell).
    cell_.resize(n);
    std::fill(cell_start_.begin(), cell_start_.end(), 0u);
    for (std::size_t i = 0; i < n; ++i) {
        cell_[i] = cell_of(r[i]);
        ++cell_start_[std::size_t(cell_[i]) + 1];
    }
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
    cell_members_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        cell_members_[cursor_[std::size_t(cell_[i])]++] = std::uint32_t(i);
    }

    old_start_.swap(start);
    old_partner_.swap(partner);
    old_touching_.swap(touching);
    old_spring_.swap(spring);
    start.resize(n + 1);
    partner.clear();
    start[0] = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Neighbour cell coordinates per axis: up to 3, wrapped on periodic axes, clipped on
        // bounded ones, a single one on axes with one cell.
        std::array<std::array<std::int32_t, 3>, D> near{};
        std::array<int, D> count{};
        int combos = 1;
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            const std::int32_t c = (cell_[i] / stride_[a]) % ncell_[a];
            int k = 0;
            if (ncell_[a] == 1) {
                near[a][k++] = 0;
            } else {
                for (std::int32_t o = -1; o <= 1; ++o) {
                    std::int32_t cn = c + o;
                    if (periodic_[a]) {
                        cn = (cn + ncell_[a]) % ncell_[a];
                    } else if (cn < 0 || cn >= ncell_[a]) {
                        continue;
                    }
                    near[a][k++] = cn;
                }
            }
            count[a] = k;
            combos *= k;
        }
        const std::size_t row0 = partner.size();
        const Vec<D> ri = r[i];
        const double* cut2 = &cutoff2_[species[i] * ns_];
        for (int combo = 0; combo < combos; ++combo) {
            std::int32_t cell = 0;
            int rest = combo;
            for (std::size_t a = 0; a < std::size_t(D); ++a) {
                cell += near[a][std::size_t(rest % count[a])] * stride_[a];
                rest /= count[a];
            }
            const std::uint32_t end = cell_start_[std::size_t(cell) + 1];
            for (std::uint32_t m = cell_start_[std::size_t(cell)]; m < end; ++m) {
                const std::uint32_t j = cell_members_[m];
                if (j <= i) continue;
                if (box.separation(ri, r[j]).squaredNorm() < cut2[species[j]]) {
                    partner.push_back(j);
                }
            }
        }
        std::sort(partner.begin() + std::ptrdiff_t(row0), partner.end());
        start[i + 1] = std::uint32_t(partner.size());
    }
    touching.assign(partner.size(), 0);
    if (history_) spring.assign(partner.size(), Vec<D>::Zero());

    // Carry the contact state (and springs) over: merge of the sorted old and new rows.
    if (old_start_.size() != n + 1) return;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t p = old_start_[i];
        const std::uint32_t p_end = old_start_[i + 1];
        std::uint32_t q = start[i];
        const std::uint32_t q_end = start[i + 1];
        while (p < p_end && q < q_end) {
            if (old_partner_[p] < partner[q]) {
                ++p;
            } else if (partner[q] < old_partner_[p]) {
                ++q;
            } else {
                touching[q] = old_touching_[p];
                if (history_) spring[q] = old_spring_[p];
                ++p;
                ++q;
            }
        }
    }
}

template class DemNeighbourList<2>;
template class DemNeighbourList<3>;

}  // namespace gran
