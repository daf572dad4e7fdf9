#pragma once
// The engine re-sorts its particles by cell now and then (memory locality): every per-particle
// array, in the particle state, the cell list and the scheduler, is permuted by the same order.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace gran {

// v[k] becomes the old v[order[k]]; an empty array (e.g. no angular velocities) stays empty.
// In place, one cycle of the permutation at a time: a copy of the array would raise the peak
// memory of a re-sort by the largest array's size (the scheduler's 32 bytes per particle), and
// the peak is what a run at N = 10^6 must fit in (docs/performance.md). One bit per particle
// marks the positions already written.
template <class T, class A>
void apply_order(std::vector<T, A>& v, const std::vector<std::uint32_t>& order) {
    if (v.empty()) return;
    std::vector<bool> done(order.size(), false);
    for (std::size_t start = 0; start < order.size(); ++start) {
        if (done[start]) continue;
        // The cycle start <- order[start] <- order[order[start]] ... <- start.
        T first = std::move(v[start]);
        std::size_t k = start;
        while (order[k] != start) {
            v[k] = std::move(v[order[k]]);
            done[k] = true;
            k = order[k];
        }
        v[k] = std::move(first);
        done[k] = true;
    }
}

// The same permutation of an array of rows of `stride` elements (row k becomes the old row
// order[k]), in place with one row of scratch.
template <class T, class A>
void apply_order_rows(std::vector<T, A>& v, std::size_t stride,
                      const std::vector<std::uint32_t>& order) {
    if (v.empty()) return;
    std::vector<bool> done(order.size(), false);
    std::vector<T> first(stride);
    auto row = [&](std::size_t k) { return v.begin() + std::ptrdiff_t(k * stride); };
    for (std::size_t start = 0; start < order.size(); ++start) {
        if (done[start]) continue;
        std::move(row(start), row(start + 1), first.begin());
        std::size_t k = start;
        while (order[k] != start) {
            std::move(row(order[k]), row(order[k] + 1), row(k));
            done[k] = true;
            k = order[k];
        }
        std::move(first.begin(), first.end(), row(k));
        done[k] = true;
    }
}

}  // namespace gran
