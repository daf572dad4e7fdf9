#include "libgran/engines/dem/neighbour_list.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "libgran/core/parallel.hpp"
#include "libgran/engines/cell_grid.hpp"

namespace gran {

template <int D>
void DemNeighbourList<D>::configure(const Box<D>& box, std::vector<double> cutoff, std::size_t ns,
                                    std::size_t n_particles, bool history, bool sorted) {
    history_ = history;
    sorted_ = sorted;
    ns_ = ns;
    cutoff2_ = std::move(cutoff);
    widest_ = 0;
    for (double& c : cutoff2_) {
        widest_ = std::max(widest_, c);
        c *= c;
    }
    cap_ = cell_cap(n_particles);
    min_image_ = false;
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        periodic_[a] = box.periodic[a];
        length_[a] = box.length[int(a)];
        ncell_[a] = 1;
        if (periodic_[a]) {
            // Clamped before the conversion (a huge box must not overflow the cell count).
            const double nc = std::min(std::floor(length_[a] / widest_), double(cap_));
            if (nc >= 3) ncell_[a] = static_cast<std::int32_t>(nc);
            min_image_ = min_image_ || ncell_[a] == 1;
        }
    }
    // Half stencil: the offsets in {-1, 0, 1}^D whose last non-zero component is +1.
    int s = 0;
    for (int code = 0; code < (D == 2 ? 9 : 27); ++code) {
        std::array<std::int8_t, D> o{};
        int rest = code;
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            o[a] = static_cast<std::int8_t>(rest % 3 - 1);
            rest /= 3;
        }
        int last = 0;
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            if (o[a] != 0) last = o[a];
        }
        if (last == 1) stencil_[std::size_t(s++)] = o;
    }
    start.assign(n_particles + 1, 0);
    partner.clear();
    owner.clear();
    touching.clear();
    spring.clear();
    cell_start_.clear();
}

// The cell grid of this build: periodic axes as configured, bounded axes over the occupied range.
template <int D>
void DemNeighbourList<D>::grid(const std::vector<Vec<D>>& r, bool across_periodic) {
    std::array<double, D> hi{};
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        lo_[a] = periodic_[a] ? 0.0 : kInf;
        hi[a] = periodic_[a] ? length_[a] : -kInf;
    }
    bool bounded = false;
    for (std::size_t a = 0; a < std::size_t(D); ++a) bounded = bounded || !periodic_[a];
    if (bounded) {
        for (const Vec<D>& x : r) {
            for (std::size_t a = 0; a < std::size_t(D); ++a) {
                if (periodic_[a]) continue;
                const double xa = x[int(a)];
                lo_[a] = xa < lo_[a] ? xa : lo_[a];  // NaN ignored
                hi[a] = xa > hi[a] ? xa : hi[a];
            }
        }
    }
    std::array<double, D> span{};
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        if (!periodic_[a]) {
            if (!(hi[a] >= lo_[a]) || !std::isfinite(hi[a] - lo_[a])) {
                lo_[a] = 0;  // no finite position: one cell
                hi[a] = 0;
            }
            const double nc = std::min(std::floor((hi[a] - lo_[a]) / widest_), double(cap_));
            ncell_[a] = std::max<std::int32_t>(1, static_cast<std::int32_t>(nc));
        }
        span[a] = hi[a] - lo_[a];
    }
    // At most cap_ cells (periodic axes keep >= 3).
    coarsen_cells<D>(ncell_, periodic_, cap_, 3, 1);
    // x fastest; with across_periodic, the periodic axis of most cells slowest instead.
    std::array<std::size_t, D>& axes = axes_;
    for (std::size_t a = 0; a < std::size_t(D); ++a) axes[a] = a;
    if (across_periodic) {
        std::size_t slowest = std::size_t(D);
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            if (periodic_[a] && (slowest == std::size_t(D) || ncell_[a] > ncell_[slowest]))
                slowest = a;
        }
        if (slowest < std::size_t(D)) {
            std::rotate(axes.begin() + std::ptrdiff_t(slowest),
                        axes.begin() + std::ptrdiff_t(slowest) + 1, axes.end());
        }
    }
    std::int32_t stride = 1;
    for (const std::size_t a : axes) {
        stride_[a] = stride;
        stride *= ncell_[a];
    }
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        inv_width_[a] = span[a] > 0 ? ncell_[a] / span[a] : 0.0;
        const std::int32_t nc = ncell_[a];
        near_[a].resize(3 * std::size_t(nc));
        shift_[a].resize(3 * std::size_t(nc));
        for (std::int32_t c = 0; c < nc; ++c) {
            for (std::int32_t o = -1; o <= 1; ++o) {
                const std::size_t k = 3 * std::size_t(c) + std::size_t(o + 1);
                std::int32_t cn = c + o;
                double sh = 0;
                if (nc == 1 && o != 0) {
                    cn = -1;  // a single cell is its own and only neighbour
                } else if (cn < 0 || cn >= nc) {
                    if (periodic_[a]) {
                        // x_j seen from cell c lies one period away: x_i - x_j -/+ L.
                        sh = cn < 0 ? length_[a] : -length_[a];
                        cn = cn < 0 ? cn + nc : cn - nc;
                    } else {
                        cn = -1;
                    }
                }
                near_[a][k] = cn;
                shift_[a][k] = sh;
            }
        }
    }
    cell_start_.assign(std::size_t(stride) + 1, 0u);
}

// The cell of a point of the grid's range (clamped to the grid; NaN to its first cell).
template <int D>
std::uint32_t DemNeighbourList<D>::cell_index(const Vec<D>& x) const {
    std::uint32_t id = 0;
    for (std::size_t a = 0; a < std::size_t(D); ++a) {
        double f = std::floor((x[int(a)] - lo_[a]) * inv_width_[a]);
        const double top = ncell_[a] - 1;
        if (!(f >= 0)) f = 0;  // also NaN
        if (f > top) f = top;
        id += static_cast<std::uint32_t>(f) * std::uint32_t(stride_[a]);
    }
    return id;
}

// Counting sort of the particles by cell (stable: increasing index within a cell); positions
// and species are copied in cell order for the pair search. On several threads each counts and
// then places the particles of its share of the indices; a cell's particles of thread t go after
// those of the threads before it, which hold lower indices: the order of one thread.
template <int D>
void DemNeighbourList<D>::bin(const std::vector<Vec<D>>& r,
                              const std::vector<std::uint32_t>& species, int threads) {
    const std::size_t n = r.size();
    const std::size_t cells = cell_start_.size() - 1;
    cell_.resize(n);
    order_.resize(n);
    xs_.resize(n);
    ss_.resize(n);
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t id = cell_index(r[i]);
            cell_[i] = id;
            ++cell_start_[id];
        }
        // Inclusive prefix sums: cell_start_[c] is the end of cell c; filled from the back, it
        // ends at the beginning of cell c.
        for (std::size_t c = 1; c < cells; ++c) cell_start_[c] += cell_start_[c - 1];
        cell_start_[cells] = std::uint32_t(n);
        for (std::size_t i = n; i-- > 0;) {
            const std::uint32_t slot = --cell_start_[cell_[i]];
            order_[slot] = std::uint32_t(i);
            xs_[slot] = r[i];
            ss_[slot] = species[i];
        }
        return;
    }
    bin_count_.resize(std::size_t(threads));
    bin_total_.resize(std::size_t(threads));
    parallel_parts(threads, [&](std::size_t part, std::size_t parts) {
        std::size_t i0 = 0, i1 = 0, c0 = 0, c1 = 0;
        chunk_bounds(n, part, parts, i0, i1);
        chunk_bounds(cells, part, parts, c0, c1);
        std::vector<std::uint32_t>& count = bin_count_[part];
        count.assign(cells, 0u);
        for (std::size_t i = i0; i < i1; ++i) {
            const std::uint32_t id = cell_index(r[i]);
            cell_[i] = id;
            ++count[id];
        }
        parts_barrier();
        std::uint32_t grains = 0;  // of this share of the cells
        for (std::size_t c = c0; c < c1; ++c) {
            for (std::size_t t = 0; t < parts; ++t) grains += bin_count_[t][c];
        }
        bin_total_[part] = grains;
        parts_barrier();
        // Each thread's first slot in each cell of this share.
        std::uint32_t slot = 0;
        for (std::size_t t = 0; t < part; ++t) slot += bin_total_[t];
        for (std::size_t c = c0; c < c1; ++c) {
            cell_start_[c] = slot;
            for (std::size_t t = 0; t < parts; ++t) {
                const std::uint32_t k = bin_count_[t][c];
                bin_count_[t][c] = slot;
                slot += k;
            }
        }
        parts_barrier();
        for (std::size_t i = i0; i < i1; ++i) {
            const std::uint32_t at = count[cell_[i]]++;
            order_[at] = std::uint32_t(i);
            xs_[at] = r[i];
            ss_[at] = species[i];
        }
    });
    cell_start_[cells] = std::uint32_t(n);
}

// The pairs of the cells [c0, c1) (each cell with itself and its half stencil), appended to
// `out` in cell order: the pairs of consecutive cell ranges, concatenated, are the pairs of the
// whole grid in the order one range would find them.
template <int D>
template <bool MinImage>
std::uint64_t DemNeighbourList<D>::find_pairs(std::size_t c0, std::size_t c1,
                                              std::vector<std::uint64_t>& out) const {
    std::array<bool, D> single{};  // periodic axes of one cell: minimum image per pair
    for (std::size_t a = 0; a < std::size_t(D); ++a) single[a] = periodic_[a] && ncell_[a] == 1;
    const auto wrap = [&](Vec<D>& d) {
        if constexpr (MinImage) {
            for (std::size_t a = 0; a < std::size_t(D); ++a) {
                if (!single[a]) continue;
                const double L = length_[a];
                if (d[int(a)] > 0.5 * L) {
                    d[int(a)] -= L;
                } else if (d[int(a)] < -0.5 * L) {
                    d[int(a)] += L;
                }
            }
        }
    };
    const std::uint32_t* cs = cell_start_.data();
    const Vec<D>* xs = xs_.data();
    const std::uint32_t* ss = ss_.data();
    const std::uint32_t* order = order_.data();
    const double* cut2 = cutoff2_.data();
    const std::size_t ns = ns_;
    const auto push = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint64_t i = order[a], j = order[b];
        out.push_back(i < j ? (i << 32 | j) : (j << 32 | i));
    };
    // The pairs of the particles of slots [b0, b1) (a cell) with those of [e0, e1) (a stencil
    // cell), seen shifted by sh (the periodic image).
    const auto cell_pairs = [&](std::uint32_t b0, std::uint32_t b1, std::uint32_t e0,
                                std::uint32_t e1, const Vec<D>& sh) {
        for (std::uint32_t a = b0; a < b1; ++a) {
            const Vec<D> xa = xs[a] + sh;
            const double* cut = cut2 + ss[a] * ns;
            for (std::uint32_t b = e0; b < e1; ++b) {
                Vec<D> d = xa - xs[b];
                wrap(d);
                if (d.squaredNorm() < cut[ss[b]]) push(a, b);
            }
        }
    };
    // A cell away from the grid's edges (every coordinate but the last neither first nor last;
    // the last not last: the half stencil's last offset is 0 or +1) has every stencil cell, none
    // across a periodic boundary: each is a fixed index offset away, with no shift. The edges
    // take each offset's neighbour per axis (near_, shift_). The same cells in the same order.
    std::array<std::int64_t, kStencil> offset{};
    for (std::size_t k = 0; k < stencil_.size(); ++k) {
        for (std::size_t a = 0; a < std::size_t(D); ++a)
            offset[k] += std::int64_t(stencil_[k][a]) * stride_[a];
    }
    const Vec<D> no_shift = Vec<D>::Zero();
    std::uint64_t work = 0;  // pair tests and stencil visits (balance_search)
    // Coordinates of cell c, which advance as the cell index does: the fastest axis first.
    std::array<std::int32_t, D> q{};
    std::size_t rest = c0;
    for (const std::size_t a : axes_) {
        q[a] = std::int32_t(rest % std::size_t(ncell_[a]));
        rest /= std::size_t(ncell_[a]);
    }
    for (std::size_t c = c0; c < c1; ++c) {
        if (c != c0) {
            for (const std::size_t a : axes_) {
                if (++q[a] < ncell_[a]) break;
                q[a] = 0;
            }
        }
        const std::uint32_t b0 = cs[c], b1 = cs[c + 1];
        if (b0 == b1) continue;
        work += kStencil + std::uint64_t(b1 - b0) * (b1 - b0 - 1) / 2;
        for (std::uint32_t a = b0; a < b1; ++a) {
            const Vec<D> xa = xs[a];
            const double* cut = cut2 + ss[a] * ns;
            for (std::uint32_t b = a + 1; b < b1; ++b) {
                Vec<D> d = xa - xs[b];
                wrap(d);
                if (d.squaredNorm() < cut[ss[b]]) push(a, b);
            }
        }
        bool inside = q[D - 1] < ncell_[D - 1] - 1;
        for (std::size_t a = 0; a + 1 < std::size_t(D); ++a)
            inside = inside && q[a] > 0 && q[a] < ncell_[a] - 1;
        if (inside) {
            for (const std::int64_t off : offset) {
                const auto nc = std::size_t(std::int64_t(c) + off);
                const std::uint32_t e0 = cs[nc], e1 = cs[nc + 1];
                if (e0 == e1) continue;
                work += std::uint64_t(b1 - b0) * (e1 - e0);
                cell_pairs(b0, b1, e0, e1, no_shift);
            }
            continue;
        }
        for (const auto& o : stencil_) {
            std::int32_t nc = 0;
            Vec<D> sh;
            bool valid = true;
            for (std::size_t a = 0; a < std::size_t(D); ++a) {
                const std::size_t k = 3 * std::size_t(q[a]) + std::size_t(o[a] + 1);
                const std::int32_t cn = near_[a][k];
                if (cn < 0) {
                    valid = false;
                    break;
                }
                nc += cn * stride_[a];
                sh[int(a)] = shift_[a][k];
            }
            if (!valid) continue;
            const std::uint32_t e0 = cs[nc], e1 = cs[nc + 1];
            if (e0 == e1) continue;
            work += std::uint64_t(b1 - b0) * (e1 - e0);
            cell_pairs(b0, b1, e0, e1, sh);
        }
    }
    return work;
}

template <int D>
void DemNeighbourList<D>::build(const std::vector<Vec<D>>& r,
                                const std::vector<std::uint32_t>& species, int threads,
                                const std::uint32_t* new_index) {
    const std::size_t n = r.size();
    // The pairs in contact (and their springs), to carry over.
    carried_.clear();
    if (start.size() == n + 1) {
        for (std::size_t i = 0; i < n; ++i) {
            for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
                if (!touching[k]) continue;
                Carried c{std::uint32_t(i), partner[k],
                          history_ ? spring[k] : Vec<D>(Vec<D>::Zero())};
                if (new_index) {
                    c.i = new_index[c.i];
                    c.j = new_index[c.j];
                    // The row is the lower index. The spring is the sliding of i relative to j:
                    // seen from the other side it changes sign (as the normal and the contact
                    // velocity do).
                    if (c.i > c.j) {
                        std::swap(c.i, c.j);
                        c.spring = -c.spring;
                    }
                }
                carried_.push_back(c);
            }
        }
    }

    grid(r, sorted_);
    bin(r, species, std::max(threads, 1));
    find_rows(n, std::max(threads, 1));
    touching.assign(partner.size(), 0);
    if (history_) spring.assign(partner.size(), Vec<D>::Zero());
    for (const Carried& c : carried_) {
        for (std::uint32_t k = start[c.i]; k < start[c.i + 1]; ++k) {
            if (partner[k] != c.j) continue;
            touching[k] = 1;
            if (history_) spring[k] = c.spring;
            break;
        }
    }
}

// The slots each thread searches (search_split_): shares expected to cost about the same. A
// vibrated bed is dense at the floor and dilute above, so equal numbers of slots (cells in order,
// the floor first) gave the first of two threads 57% of the search's CPU time at N = 10^5. The
// work of the last build's shares (pair tests plus stencil visits, counted by find_pairs) is
// taken as spread evenly over each share's slots (the bed changes little between builds), and
// the new cuts are where that estimate reaches each thread's equal part. Equal slots at the
// first build or after a change of size or shares. The pairs found are the same for any split.
template <int D>
void DemNeighbourList<D>::balance_search(std::size_t n, std::size_t parts) {
    std::uint64_t total = 0;
    for (const std::uint64_t work : search_work_) total += work;
    const bool known = search_split_.size() == parts + 1 && search_split_[parts] == n &&
                       search_work_.size() == parts && total > 0;
    if (!known) {
        search_split_.resize(parts + 1);
        for (std::size_t t = 0; t < parts; ++t) {
            std::size_t end = 0;
            chunk_bounds(n, t, parts, search_split_[t], end);
        }
        search_split_[parts] = n;
        return;
    }
    std::vector<std::size_t>& cut = search_cut_;
    cut.assign(search_split_.begin(), search_split_.end());
    std::size_t u = 0;         // the old share holding the next cut
    std::uint64_t before = 0;  // work of the old shares before u
    for (std::size_t t = 1; t < parts; ++t) {
        const double target = double(total) * double(t) / double(parts);
        while (u + 1 < parts && double(before + search_work_[u]) < target)
            before += search_work_[u++];
        const double work = double(search_work_[u]);
        const double width = double(cut[u + 1] - cut[u]);
        const double into = work > 0 ? (target - double(before)) / work : 0.5;
        const auto slot = std::size_t(double(cut[u]) + std::clamp(into, 0.0, 1.0) * width);
        search_split_[t] = std::clamp(slot, search_split_[t - 1], n);
    }
}

// The pairs, then compressed rows by the lower index, on `threads` threads (one: the serial code),
// entry for entry the same rows for any count. Thread t searches the cells whose particles (slots
// in cell order) fall in its share of the slots, into its own segment; the segments in thread
// order are the one-thread sequence of pairs. Each row is filled from its end downwards in that
// sequence (so it holds its pairs in the reverse of the order found): segment t's pairs of row i
// go below those of the earlier segments.
template <int D>
void DemNeighbourList<D>::find_rows(std::size_t n, int threads) {
    const std::size_t cells = cell_start_.size() - 1;
    const std::size_t parts = std::size_t(threads);
    segments_.resize(parts);
    row_count_.resize(parts);
    for (std::vector<std::uint64_t>& seg : segments_) seg.clear();
    const std::uint32_t* cs = cell_start_.data();
    balance_search(n, parts);
    search_work_.assign(parts, 0);
    search_seconds_.assign(parts, 0.0);
    std::size_t granted = parts;
    parallel_parts(threads, [&](std::size_t part, std::size_t all) {
        const auto began = std::chrono::steady_clock::now();
        std::size_t s0 = 0, s1 = 0;
        if (all == parts) {
            s0 = search_split_[part];
            s1 = search_split_[part + 1];
        } else {
            chunk_bounds(n, part, all, s0, s1);
            if (part == 0) granted = all;
        }
        // The cells whose first slot lies in [s0, s1) (an empty cell finds nothing anywhere).
        const std::size_t c0 = std::size_t(std::lower_bound(cs, cs + cells, s0) - cs);
        const std::size_t c1 =
            s1 == n ? cells : std::size_t(std::lower_bound(cs, cs + cells, s1) - cs);
        // The segment is filled on this thread's stack: each append writes the vector's end
        // pointer, and the threads' vectors in segments_ share a cache line (false sharing
        // made the two halves of the search take 1.2-1.5x the one-thread search together).
        std::vector<std::uint64_t> seg;
        seg.swap(segments_[part]);  // its capacity, kept across builds
        search_work_[part] =
            min_image_ ? find_pairs<true>(c0, c1, seg) : find_pairs<false>(c0, c1, seg);
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - began;
        search_seconds_[part] = took.count();
        std::vector<std::uint32_t> count;
        count.swap(row_count_[part]);
        count.assign(n, 0u);
        for (std::uint64_t p : seg) ++count[std::size_t(p >> 32)];
        segments_[part].swap(seg);
        row_count_[part].swap(count);
    });
    for (std::size_t t = 0; t < parts; ++t) {  // also the parts the runtime gave no thread
        if (segments_[t].empty()) row_count_[t].assign(n, 0u);
    }
    if (granted != parts) search_split_.clear();  // the shares searched were not these
    // Row starts: exclusive prefix sums of the total counts.
    start.resize(n + 1);
    std::uint32_t total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        start[i] = total;
        for (std::size_t t = 0; t < parts; ++t) total += row_count_[t][i];
    }
    start[n] = total;
    partner.resize(total);
    owner.resize(total);
    parallel_chunks(threads, n, [&](std::size_t, std::size_t i0, std::size_t i1) {
        // Segment t fills row i downwards from its end less the earlier segments' pairs.
        for (std::size_t i = i0; i < i1; ++i) {
            std::uint32_t top = start[i + 1];
            for (std::size_t t = 0; t < parts; ++t) {
                const std::uint32_t c = row_count_[t][i];
                row_count_[t][i] = top;
                top -= c;
            }
            std::fill(owner.begin() + start[i], owner.begin() + start[i + 1], std::uint32_t(i));
        }
    });
    parallel_chunks(threads, parts, [&](std::size_t, std::size_t t0, std::size_t t1) {
        for (std::size_t t = t0; t < t1; ++t) {
            std::uint32_t* cursor = row_count_[t].data();
            for (std::uint64_t p : segments_[t])
                partner[--cursor[std::size_t(p >> 32)]] = std::uint32_t(p);
        }
    });
}

template class DemNeighbourList<2>;
template class DemNeighbourList<3>;

}  // namespace gran
