#pragma once
// Collisions per unordered species pair (a <= b), for the per-pair collision frequencies of
// `collision_statistics`. A dense ns x ns table up to kDenseSpecies species (one increment per
// collision); beyond, a hash map of the pairs that collided: a scene of 10^4 species would need
// 800 MB dense, and most of its pairs never meet. The dense view (ns x ns) is made only on request.
#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "libgran/core/state_archive.hpp"

namespace gran {

class PairCounts {
  public:
    static constexpr std::size_t kDenseSpecies = 1024;  // 8 MB of counters

    void reset(std::size_t ns) {
        ns_ = ns;
        sparse_.clear();
        dense_.assign(ns <= kDenseSpecies ? ns * ns : 0, 0);
    }
    // One collision of species a <= b.
    void add(std::uint32_t a, std::uint32_t b) {
        if (!dense_.empty()) {
            ++dense_[a * ns_ + b];
        } else {
            ++sparse_[key(a, b)];
        }
    }
    // Index min(a,b) * ns + max(a,b); many species: filled from the map at each call.
    const std::vector<std::uint64_t>& dense() const {
        if (ns_ <= kDenseSpecies) return dense_;
        view_.assign(ns_ * ns_, 0);
        for (const auto& [k, n] : sparse_) view_[(k >> 32) * ns_ + (k & 0xffffffffu)] = n;
        return view_;
    }
    // The dense table as before (same checkpoint as ever); the map as sorted keys and counts.
    void checkpoint(StateArchive& ar) {
        if (ns_ <= kDenseSpecies) {
            ar.io(dense_);
            return;
        }
        std::vector<std::uint64_t> keys, counts;
        for (const auto& kv : sparse_) keys.push_back(kv.first);
        std::sort(keys.begin(), keys.end());  // the same bytes whatever the map's order
        for (std::uint64_t k : keys) counts.push_back(sparse_.at(k));
        ar.io(keys);
        ar.io(counts);
        if (!ar.loading()) return;
        if (keys.size() != counts.size()) throw StateMismatch("pair collision counts of two sizes");
        sparse_.clear();
        for (std::size_t i = 0; i < keys.size(); ++i) sparse_[keys[i]] = counts[i];
    }

  private:
    static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
        return (std::uint64_t(a) << 32) | b;
    }
    std::size_t ns_ = 0;
    std::vector<std::uint64_t> dense_;
    std::unordered_map<std::uint64_t, std::uint64_t> sparse_;
    mutable std::vector<std::uint64_t> view_;
};

}  // namespace gran
