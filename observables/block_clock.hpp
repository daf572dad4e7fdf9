#pragma once
// Which of `n` consecutive blocks of the measurement a sample belongs to, for observables that
// keep per-block sums for their jackknife errors (profiles, local_temperature, the velocity
// distributions).
//
// A measurement of known length (SampleContext::expected_samples): sample k goes to block
// k n / expected, n blocks of (nearly) equal length.
//
// An open-ended measurement (a run with a target measures until its error bars are small
// enough, SampleContext::open_ended): the length is unknown, so the blocks have a fixed length,
// expected / n of the first look, that doubles each time all n blocks are full. The sample that
// fills the last block says so (merge_after): once it is added, the caller merges neighbouring
// pairs (merge_block_pairs on each of its per-block arrays), so the blocks stay contiguous and
// of equal length, between n / 2 and n of them, as long as the run.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "libgran/core/state_archive.hpp"

namespace gran {

class BlockClock {
  public:
    explicit BlockClock(std::size_t blocks) : n_(std::max<std::size_t>(blocks, 2)) {}

    struct Place {
        std::size_t block;
        bool merge_after;  // this sample fills the last block: merge pairs once it is added
    };

    // The block of sample `k` (0 for the first measurement sample).
    Place place(std::size_t k, std::size_t expected, bool open_ended) {
        expected = std::max<std::size_t>(expected, 1);
        if (!open_ended) return {std::min(n_ - 1, k * n_ / expected), false};
        if (length_ == 0) length_ = std::max<std::size_t>(1, expected / n_);
        const std::size_t block = k / length_;
        const bool merge = (k + 1) / length_ >= n_;
        if (merge) length_ *= 2;  // the blocks from now on
        return {block, merge};
    }

    // The block sample `k` will go to (after the merges so far), without placing it.
    std::size_t next_block(std::size_t k, std::size_t expected, bool open_ended) const {
        expected = std::max<std::size_t>(expected, 1);
        if (!open_ended) return std::min(n_ - 1, k * n_ / expected);
        return length_ == 0 ? 0 : k / length_;
    }

    void checkpoint(StateArchive& ar) { ar.io(length_); }

  private:
    std::size_t n_;
    std::size_t length_ = 0;  // samples per block of an open-ended measurement (0: not started)
};

// `v` holds `blocks` equal chunks, one per block: chunk b becomes the sum of chunks 2b and 2b + 1
// (2b alone for the last of an odd number), the rest is zeroed. With an odd number of blocks the
// last merged block holds one block's samples and goes on filling (BlockClock places the next
// samples there).
template <class T>
void merge_block_pairs(std::vector<T>& v, std::size_t blocks) {
    const std::size_t chunk = v.size() / blocks, half = (blocks + 1) / 2;
    for (std::size_t b = 0; b < half; ++b) {
        for (std::size_t i = 0; i < chunk; ++i) {
            T sum = v[2 * b * chunk + i];
            if (2 * b + 1 < blocks) sum = sum + v[(2 * b + 1) * chunk + i];
            v[b * chunk + i] = sum;
        }
    }
    std::fill(v.begin() + std::ptrdiff_t(half * chunk), v.end(), T{});
}

}  // namespace gran
