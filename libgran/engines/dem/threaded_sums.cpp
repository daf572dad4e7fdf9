// The DEM engine's pair forces on several threads (DemSettings::threads) summed into the grains
// in the order the single-threaded loop adds them: the bits of one thread for any thread count.
//
// One thread adds entry by entry, in increasing entry k; each entry (i, j) has i < j and the rows
// are ordered by i. A grain x therefore receives first its entries as partner (rows i < x), in
// increasing k, then its own row. With the rows cut into consecutive shares, one per thread, a
// grain whose entries all lie in one thread's share receives them all from that thread, in
// order: it is summed directly (law_loop.hpp, pair_forces). The others, the halo grains, are
// partners of an earlier share's rows: near a share's boundary, after the spatial sort a thin
// layer of grains. Their contacts wait in per-entry slots until every share is done.
#include <algorithm>

#include "libgran/core/parallel.hpp"
#include "libgran/engines/dem/engine.hpp"

namespace gran {

// The shares: consecutive rows holding about equal numbers of entries (cut at the first row
// starting at or after each thread's equal split of the entries). A grain is a halo grain if it is
// the partner of a row of an earlier share: an entry of share t whose partner lies beyond t's
// rows. Each halo grain's entries as partner are then listed in increasing k (halo_start_,
// halo_entries_): a counting sort over the few halo grains, not over every entry.
template <int D>
void DemEngine<D>::split_pair_rows() {
    const std::size_t n = p_.size(), parts = std::size_t(threads_);
    const std::size_t entries = list_.entries();
    const std::uint32_t* start = list_.start.data();
    const std::uint32_t* partner = list_.partner.data();
    pair_rows_.assign(parts + 1, 0);
    pair_rows_[parts] = n;
    for (std::size_t t = 1; t < parts; ++t) {
        std::size_t k0 = 0, k1 = 0;
        chunk_bounds(entries, t, parts, k0, k1);
        const std::size_t row = std::size_t(std::lower_bound(start, start + n, k0) - start);
        pair_rows_[t] = std::max(pair_rows_[t - 1], row);
    }
    halo_.assign(n, 0);
    std::uint8_t* halo = halo_.data();
    for (std::size_t t = 0; t + 1 < parts; ++t) {
        const std::size_t end = pair_rows_[t + 1];
        for (std::uint32_t k = start[pair_rows_[t]]; k < start[end]; ++k) {
            if (partner[k] >= end) halo[partner[k]] = 1;
        }
    }
    halo_list_.clear();
    halo_slot_.resize(n);
    for (std::size_t x = 0; x < n; ++x) {
        if (!halo[x]) continue;
        halo_slot_[x] = std::uint32_t(halo_list_.size());
        halo_list_.push_back(std::uint32_t(x));
    }
    const std::size_t halos = halo_list_.size();
    // Each halo grain summed by the thread whose rows hold it (the thread that drifts it and
    // adds its own row's contacts), so that its lines stay in that thread's core.
    halo_shares_.resize(parts + 1);
    for (std::size_t t = 0; t <= parts; ++t)
        halo_shares_[t] = std::size_t(
            std::lower_bound(halo_list_.begin(), halo_list_.end(), std::uint32_t(pair_rows_[t])) -
            halo_list_.begin());
    halo_start_.assign(halos + 1, 0);
    for (std::size_t k = 0; k < entries; ++k) {
        if (halo[partner[k]]) ++halo_start_[halo_slot_[partner[k]] + 1];
    }
    for (std::size_t h = 0; h < halos; ++h) halo_start_[h + 1] += halo_start_[h];
    halo_entries_.resize(halo_start_[halos]);
    halo_fill_.assign(halo_start_.begin(), halo_start_.end() - 1);
    for (std::size_t k = 0; k < entries; ++k) {
        if (halo[partner[k]])
            halo_entries_[halo_fill_[halo_slot_[partner[k]]]++] = std::uint32_t(k);
    }
    pair_split_stale_ = false;
    if (stage_clock_.enabled()) {
        ++thread_shares_.splits;
        thread_shares_.halo_grains += double(halos);
        thread_shares_.grains += double(n);
    }
}

// The last build's search seconds (any thread count) and, on several threads, its imbalance,
// max / mean work per thread, into thread_shares_.
template <int D>
void DemEngine<D>::tally_search_shares() {
    const std::vector<double>& seconds = list_.search_seconds();
    if (!seconds.empty()) {
        ++thread_shares_.timed_searches;
        for (const double s : seconds) thread_shares_.search_all += s;
        thread_shares_.search_slowest += *std::max_element(seconds.begin(), seconds.end());
    }
    if (threads_ <= 1) return;
    const std::vector<std::uint64_t>& work = list_.search_work();
    if (work.empty()) return;
    std::uint64_t total = 0, most = 0;
    for (const std::uint64_t w : work) {
        total += w;
        most = std::max(most, w);
    }
    if (total == 0) return;
    ++thread_shares_.searches;
    thread_shares_.search_imbalance += double(most) * double(work.size()) / double(total);
}

// Share `part` of `parts` of the halo grains: each one's slots, as partner (earlier rows, so
// first) then as owner (its own row), in increasing entry order, as one thread adds them.
template <int D>
void DemEngine<D>::sum_halo_pair_forces(std::size_t part, std::size_t parts) {
    const bool rot = p_.rotating();
    const std::uint32_t* start = list_.start.data();
    const std::uint32_t* halo_start = halo_start_.data();
    const std::uint32_t* halo_entries = halo_entries_.data();
    const std::uint8_t* touching = list_.touching.data();
    const Vec<D>* pf = pair_force_.data();
    const AngVec<D>* pti = pair_torque_i_.data();
    const AngVec<D>* ptj = pair_torque_j_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    std::size_t h0 = 0, h1 = 0;
    if (halo_shares_.size() == parts + 1) {
        h0 = halo_shares_[part];
        h1 = halo_shares_[part + 1];
    } else {
        chunk_bounds(halo_list_.size(), part, parts, h0, h1);
    }
    for (std::size_t h = h0; h < h1; ++h) {
        const std::uint32_t x = halo_list_[h];
        Vec<D> fx = f[x];
        for (std::uint32_t q = halo_start[h]; q < halo_start[h + 1]; ++q) {
            const std::uint32_t k = halo_entries[q];
            if (touching[k]) fx -= pf[k];
        }
        for (std::uint32_t k = start[x]; k < start[x + 1]; ++k) {
            if (touching[k]) fx += pf[k];
        }
        f[x] = fx;
        if (!rot) continue;
        AngVec<D> tx = tau[x];
        for (std::uint32_t q = halo_start[h]; q < halo_start[h + 1]; ++q) {
            const std::uint32_t k = halo_entries[q];
            if (touching[k]) tx += ptj[k];
        }
        for (std::uint32_t k = start[x]; k < start[x + 1]; ++k) {
            if (touching[k]) tx += pti[k];
        }
        tau[x] = tx;
    }
}

template void DemEngine<2>::split_pair_rows();
template void DemEngine<3>::split_pair_rows();
template void DemEngine<2>::tally_search_shares();
template void DemEngine<3>::tally_search_shares();
template void DemEngine<2>::sum_halo_pair_forces(std::size_t, std::size_t);
template void DemEngine<3>::sum_halo_pair_forces(std::size_t, std::size_t);

}  // namespace gran
