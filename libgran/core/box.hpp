#pragma once
// Simulation box [0, L_a) per axis; each axis periodic or bounded by hard walls.
#include <emmintrin.h>

#include <array>

#include "libgran/core/vec.hpp"

namespace gran {

template <int D>
struct Box {
    Vec<D> length = Vec<D>::Ones();
    std::array<bool, D> periodic{};

    double volume() const { return length.prod(); }

    // Minimum-image separation for positions inside (or within one cell of) the box.
    Vec<D> separation(const Vec<D>& a, const Vec<D>& b) const {
        Vec<D> d = a - b;
        for (int k = 0; k < D; ++k) {
            if (periodic[k]) {
                const double half = 0.5 * length[k];
                if (d[k] > half) {
                    d[k] -= length[k];
                } else if (d[k] < -half) {
                    d[k] += length[k];
                }
            }
        }
        return d;
    }
};

// Box::separation's minimum image for two pairs at once, one in each lane of an SSE2 register
// (the event-driven scan's two-lane pair test, event_times.hpp): along axis k, each lane is bit
// for bit the k-th component of separation() for its pair (the same half length, comparisons and
// one addition or subtraction). Built once per scan: the per-axis constants are broadcast here.
template <int D>
struct MinimumImageTwo {
    explicit MinimumImageTwo(const Box<D>& box) {
        for (int k = 0; k < D; ++k) {
            const double h = 0.5 * box.length[k];  // as Box::separation
            periodic[k] = box.periodic[std::size_t(k)];
            length[k] = _mm_set1_pd(box.length[k]);
            half[k] = _mm_set1_pd(h);
            minus_half[k] = _mm_set1_pd(-h);
        }
    }
    // d: the two pairs' a - b along axis k. The length, masked, is subtracted where d > L / 2
    // and added where d < -L / 2: d - L and d + L there as in separation(), and elsewhere
    // d - 0 + 0, which is d (a separation is never -0, the one value that would turn +0).
    __m128d operator()(__m128d d, int k) const {
        if (!periodic[k]) return d;
        const __m128d up = _mm_and_pd(_mm_cmpgt_pd(d, half[k]), length[k]);
        const __m128d down = _mm_and_pd(_mm_cmplt_pd(d, minus_half[k]), length[k]);
        return _mm_add_pd(_mm_sub_pd(d, up), down);
    }
    __m128d length[D], half[D], minus_half[D];
    bool periodic[D];
};

}  // namespace gran
