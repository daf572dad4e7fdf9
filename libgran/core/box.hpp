#pragma once
// Simulation box [0, L_a) per axis; each axis periodic or bounded by hard walls.
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

}  // namespace gran
