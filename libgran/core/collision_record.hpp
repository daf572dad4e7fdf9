#pragma once
// What an observable sees of one binary collision. Built only when some observable subscribes.
#include <cstdint>

#include "libgran/core/vec.hpp"

namespace gran {

template <int D>
struct CollisionRecord {
    double time = 0;
    std::uint32_t i = 0, j = 0;    // particle indices
    std::uint32_t si = 0, sj = 0;  // species
    Vec<D> ri;                     // position of i at contact (periodic axes: any image)
    Vec<D> n;                      // unit vector from j to i
    Vec<D> vi, vj, vi_after, vj_after;
    AngVec<D> wi{}, wj{}, wi_after{}, wj_after{};
    double alpha = 1, beta = -1;  // coefficients actually used (after the collapse guard)
    double impulse = 0;           // normal impulse on i (Barrat & Trizac Eq. (3))
    double contact_distance = 0;  // sigma_ij
};

template <int D>
class CollisionSink {
  public:
    virtual ~CollisionSink() = default;
    virtual void on_collision(const CollisionRecord<D>& c) = 0;
};

}  // namespace gran
