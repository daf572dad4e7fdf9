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

// Zero angular velocity (a scalar in 2D, a 3-vector in 3D).
template <int D>
inline AngVec<D> ang_zero() {
    if constexpr (D == 2) {
        return 0.0;
    } else {
        return Eigen::Vector3d::Zero();
    }
}

template <int D>
inline double ang_squared(const AngVec<D>& w) {
    if constexpr (D == 2) {
        return w * w;
    } else {
        return w.squaredNorm();
    }
}

}  // namespace gran
