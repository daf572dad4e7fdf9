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

// w x n for an angular velocity w: in 2D w is the z component, so w x n = w (-n_y, n_x).
template <int D>
inline Vec<D> cross_w(const AngVec<D>& w, const Vec<D>& n) {
    if constexpr (D == 2) {
        return Vec<D>(-w * n.y(), w * n.x());
    } else {
        return w.cross(n);
    }
}

// n x p, as an angular quantity (a scalar z component in 2D).
template <int D>
inline AngVec<D> cross_n(const Vec<D>& n, const Vec<D>& p) {
    if constexpr (D == 2) {
        return n.x() * p.y() - n.y() * p.x();
    } else {
        return n.cross(p);
    }
}

}  // namespace gran
