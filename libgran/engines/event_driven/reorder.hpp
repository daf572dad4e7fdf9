#pragma once
// The engine re-sorts its particles by cell now and then (memory locality): every per-particle
// array, in the particle state, the cell list and the scheduler, is permuted by the same order.
#include <cstdint>
#include <utility>
#include <vector>

namespace gran {

// v[k] becomes the old v[order[k]]; an empty array (e.g. no angular velocities) stays empty.
template <class T, class A>
void apply_order(std::vector<T, A>& v, const std::vector<std::uint32_t>& order) {
    if (v.empty()) return;
    std::vector<T, A> old(std::move(v));
    v.resize(old.size());
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
}

}  // namespace gran
