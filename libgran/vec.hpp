#pragma once
// Fixed-size vector types of the engines: the dimension is a compile-time parameter.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <limits>
#include <type_traits>

namespace gran {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

// Angular velocity: a scalar (about z) for disks, a 3-vector for spheres.
template <int D>
using AngVec = std::conditional_t<D == 2, double, Eigen::Vector3d>;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

template <int D>
inline double ang_squared(const AngVec<D>& w) {
    if constexpr (D == 2) {
        return w * w;
    } else {
        return w.squaredNorm();
    }
}

}  // namespace gran
