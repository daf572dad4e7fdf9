#pragma once
// Two contacts per SSE2 instruction (issue 15, the settled bed): lane 0 holds one contact's
// value, lane 1 the next one's. A settled bed spends most of its time in the contacts'
// arithmetic, one scalar operation after another (docs/performance.md, "Two contacts per
// instruction"); here each operation serves two contacts. Every helper performs, per lane, the
// scalar operations of the one-contact code in the same order (Eigen's fixed-size dot sums x, y,
// then z; its cross product is (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0)), and the build has
// no fused multiply-add, so each lane's result is bit for bit the one-contact result.
#include <emmintrin.h>

#include "libgran/core/vec.hpp"
#include "libgran/engines/dem/contact_force.hpp"

namespace gran::two_contacts {

using Lane = __m128d;

// A vector of D components, each holding both contacts' values.
template <int D>
struct Vec2 {
    Lane c[D];
};

inline Lane lanes(double first, double second) {
    return _mm_set_pd(second, first);
}
inline double first(Lane x) {
    return _mm_cvtsd_f64(x);
}
inline double second(Lane x) {
    return _mm_cvtsd_f64(_mm_unpackhi_pd(x, x));
}
template <int D>
inline Vec2<D> lanes(const Vec<D>& first, const Vec<D>& second) {
    Vec2<D> v;
    for (int a = 0; a < D; ++a) v.c[a] = _mm_set_pd(second[a], first[a]);
    return v;
}
template <int D>
inline Vec<D> first(const Vec2<D>& v) {
    Vec<D> out;
    for (int a = 0; a < D; ++a) out[a] = first(v.c[a]);
    return out;
}
template <int D>
inline Vec<D> second(const Vec2<D>& v) {
    Vec<D> out;
    for (int a = 0; a < D; ++a) out[a] = second(v.c[a]);
    return out;
}

inline Lane add(Lane a, Lane b) {
    return _mm_add_pd(a, b);
}
inline Lane sub(Lane a, Lane b) {
    return _mm_sub_pd(a, b);
}
inline Lane mul(Lane a, Lane b) {
    return _mm_mul_pd(a, b);
}
inline Lane neg(Lane a) {
    return _mm_xor_pd(a, _mm_set1_pd(-0.0));
}
inline Lane abs(Lane a) {
    return _mm_andnot_pd(_mm_set1_pd(-0.0), a);
}
// Per lane: yes where mask is set, no elsewhere.
inline Lane select(Lane mask, Lane yes, Lane no) {
    return _mm_or_pd(_mm_and_pd(mask, yes), _mm_andnot_pd(mask, no));
}

template <int D>
inline Vec2<D> scale(Lane s, const Vec2<D>& v) {
    Vec2<D> out;
    for (int a = 0; a < D; ++a) out.c[a] = mul(s, v.c[a]);
    return out;
}
template <int D>
inline Vec2<D> add(const Vec2<D>& x, const Vec2<D>& y) {
    Vec2<D> out;
    for (int a = 0; a < D; ++a) out.c[a] = add(x.c[a], y.c[a]);
    return out;
}
template <int D>
inline Vec2<D> sub(const Vec2<D>& x, const Vec2<D>& y) {
    Vec2<D> out;
    for (int a = 0; a < D; ++a) out.c[a] = sub(x.c[a], y.c[a]);
    return out;
}
template <int D>
inline Lane dot(const Vec2<D>& x, const Vec2<D>& y) {
    Lane s = mul(x.c[0], y.c[0]);
    for (int a = 1; a < D; ++a) s = add(s, mul(x.c[a], y.c[a]));
    return s;
}
inline Vec2<3> cross(const Vec2<3>& x, const Vec2<3>& y) {
    return {{sub(mul(x.c[1], y.c[2]), mul(x.c[2], y.c[1])),
             sub(mul(x.c[2], y.c[0]), mul(x.c[0], y.c[2])),
             sub(mul(x.c[0], y.c[1]), mul(x.c[1], y.c[0]))}};
}

// contact_velocity (Eq. A3) for two contacts, spheres: v_i - v_j - (l_i w_i + l_j w_j) x n.
inline Vec2<3> contact_velocity(const Vec2<3>& v_i, const Vec2<3>& v_j, const Vec2<3>& w_i,
                                const Vec2<3>& w_j, Lane l_i, Lane l_j, const Vec2<3>& n) {
    const Vec2<3> w = add(scale(l_i, w_i), scale(l_j, w_j));
    return sub(sub(v_i, v_j), cross(w, n));
}

// contact_detail::assemble for two contacts: the force on i, f_n n + f_t, and the torques
// -l n x f_t, unpacked into each contact's ContactForce.
inline void assemble(Lane f_n, const Vec2<3>& f_t, const Vec2<3>& n, Lane l_i, Lane l_j,
                     Lane slipping, ContactForce<3>& a, ContactForce<3>& b) {
    const Vec2<3> force = add(scale(f_n, n), f_t);
    const Vec2<3> nxf = cross(n, f_t);
    const Vec2<3> torque_i = scale(neg(l_i), nxf);
    const Vec2<3> torque_j = scale(neg(l_j), nxf);
    a.force = first(force);
    b.force = second(force);
    a.torque_i = first(torque_i);
    b.torque_i = second(torque_i);
    a.torque_j = first(torque_j);
    b.torque_j = second(torque_j);
    a.f_n = first(f_n);
    b.f_n = second(f_n);
    const int slip = _mm_movemask_pd(slipping);
    a.slipping = (slip & 1) != 0;
    b.slipping = (slip & 2) != 0;
}

}  // namespace gran::two_contacts
