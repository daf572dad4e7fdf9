#pragma once
// When events happen: the collision time of a pair, the crossing time of a cell boundary and the
// exit time from a neighbour shell, the root finders of the event-driven engine's predictions
// (walls: next_wall_contact in libgran/core/wall_motion.hpp).
#include <emmintrin.h>

#include <algorithm>
#include <cmath>

#include "libgran/core/vec.hpp"

namespace gran {

// Collision time of two spheres at separation dr, relative velocity dv, contact distance sigma.
// Returns 0 for an approaching overlapping pair (round-off) and +inf for receding or missing pairs,
// or for pairs that cannot collide before `bound`. Stable root: dt = c / (-b + sqrt(b^2 - dv^2 c))
// avoids cancellation; since that root is >= c / (-2b), pairs beyond the bound are rejected
// before the square root (the common case in a neighbour scan). Always inlined: gcc had stopped
// inlining the 3D form into the scan, and inlined it is 4-6% faster in 3D (docs/performance.md).
template <int D>
[[gnu::always_inline]] inline double pair_collision_time(const Vec<D>& dr, const Vec<D>& dv,
                                                         double sigma, double bound = kInf) {
    const double b = dr.dot(dv);
    if (b >= 0.0) return kInf;
    const double c = dr.squaredNorm() - sigma * sigma;
    if (c <= 0.0) return 0.0;
    if (c > -2.0 * b * bound) return kInf;
    const double disc = b * b - dv.squaredNorm() * c;
    if (disc <= 0.0) return kInf;
    return c / (-b + std::sqrt(disc));
}

// pair_collision_time without a bound and without branches, bit for bit the same value: the
// scans' "receding?" and "missing?" tests are unpredictable (half the pairs of a dense fluid
// recede), and each misprediction cost more than the square root and division computed for every
// candidate here (perf annotate, 3D phi 0.4: 30% of the scan's cycles at the two branches). The
// square root of a negative discriminant is a NaN without errno (the SSE2 instruction, not the libm
// call) and is then discarded.
template <int D>
[[gnu::always_inline]] inline double pair_collision_time_branchless(const Vec<D>& dr,
                                                                    const Vec<D>& dv,
                                                                    double sigma) {
    const double b = dr.dot(dv);
    const double c = dr.squaredNorm() - sigma * sigma;
    const double disc = b * b - dv.squaredNorm() * c;
    // SSE2 on scalars: written with ?: gcc turned the "disc > 0" selection back into a branch.
    const __m128d vb = _mm_set_sd(b), vc = _mm_set_sd(c), vdisc = _mm_set_sd(disc);
    const __m128d zero = _mm_setzero_pd(), inf = _mm_set_sd(kInf);
    // sqrt(disc) - b is bit for bit -b + sqrt(disc) (negation is exact, addition commutes).
    const __m128d root = _mm_div_sd(vc, _mm_sub_sd(_mm_sqrt_sd(vdisc, vdisc), vb));
    auto select = [](__m128d mask, __m128d yes, __m128d no) {
        return _mm_or_pd(_mm_and_pd(mask, yes), _mm_andnot_pd(mask, no));
    };
    __m128d t = select(_mm_cmpgt_sd(vdisc, zero), root, inf);  // a miss: +inf
    t = _mm_andnot_pd(_mm_cmple_sd(vc, zero), t);              // overlapping: 0 (now)
    t = select(_mm_cmplt_sd(vb, zero), t, inf);                // receding: +inf
    return _mm_cvtsd_f64(t);
}

// Two pairs at once, one in each lane of an SSE2 register (dr and dv: D components, each the two
// pairs' values): the operations of pair_collision_time_branchless in the same order (a dot
// product sums the x, then the y, then the z terms, as Eigen's fixed-size reduction does), so each
// lane's time is bit for bit the one-pair time. The square root and the division, the slowest
// instructions of the test, then serve two pairs each.
template <int D>
[[gnu::always_inline]] inline __m128d pair_collision_times_two(const __m128d* dr, const __m128d* dv,
                                                               __m128d sigma) {
    auto dot = [](const __m128d* a, const __m128d* b) {
        __m128d sum = _mm_add_pd(_mm_mul_pd(a[0], b[0]), _mm_mul_pd(a[1], b[1]));
        if constexpr (D == 3) sum = _mm_add_pd(sum, _mm_mul_pd(a[2], b[2]));
        return sum;
    };
    const __m128d b = dot(dr, dv);
    const __m128d c = _mm_sub_pd(dot(dr, dr), _mm_mul_pd(sigma, sigma));
    const __m128d disc = _mm_sub_pd(_mm_mul_pd(b, b), _mm_mul_pd(dot(dv, dv), c));
    const __m128d root = _mm_div_pd(c, _mm_sub_pd(_mm_sqrt_pd(disc), b));
    auto select = [](__m128d mask, __m128d yes, __m128d no) {
        return _mm_or_pd(_mm_and_pd(mask, yes), _mm_andnot_pd(mask, no));
    };
    const __m128d zero = _mm_setzero_pd(), inf = _mm_set1_pd(kInf);
    __m128d t = select(_mm_cmpgt_pd(disc, zero), root, inf);  // a miss: +inf
    t = _mm_andnot_pd(_mm_cmple_pd(c, zero), t);              // overlapping: 0 (now)
    return select(_mm_cmplt_pd(b, zero), t, inf);             // receding: +inf
}

// Earliest s >= 0 at which x(s) = c + v s + a s^2 / 2 (c: position relative to a cell boundary)
// crosses 0 moving in direction dir (+1 up, -1 down), or +inf. Direction-aware so a particle that
// has just crossed a boundary (and sits on it, either side by round-off) is never sent back at
// once: the roots are labelled by the velocity v + a s = +-sqrt(v^2 - 2 a c) they cross with. Only
// a particle already past the boundary and moving (or, at rest, accelerating) on crosses now.
inline double directed_crossing(double c, double v, double a, int dir) {
    if (dir * c >= 0.0 && (dir * v > 0.0 || (v == 0.0 && dir * a > 0.0))) return 0.0;
    if (a == 0.0) return dir * v > 0.0 ? std::max(-c / v, 0.0) : kInf;
    const double disc = v * v - 2.0 * a * c;
    if (!(disc > 0.0)) return kInf;
    const double sq = std::sqrt(disc);
    // Root crossing upward: v + a s = +sq; downward: v + a s = -sq (cancellation-free forms).
    double s;
    if (dir > 0) {
        s = v > 0.0 ? -2.0 * c / (sq + v) : (sq - v) / a;
    } else {
        s = v < 0.0 ? 2.0 * c / (sq - v) : -(v + sq) / a;
    }
    return s >= 0.0 ? s : kInf;
}

// Time s >= 0 at which a particle at offset d from its shell's centre, moving in a straight line at
// v, reaches distance h from it (neighbour_shells.hpp), or +inf at rest. The root of
// |d + v s|^2 = h^2 with s >= 0: (-b + sqrt(b^2 - a c)) / a, with a = v.v, b = d.v,
// c = d.d - h^2 <= 0; for b > 0 the form -c / (b + sqrt(...)) avoids cancellation. A particle
// already on or past the shell (round-off) leaves now.
template <int D>
inline double shell_exit_time(const Vec<D>& d, const Vec<D>& v, double h) {
    const double a = v.squaredNorm();
    if (a == 0.0) return kInf;
    const double b = d.dot(v);
    const double c = d.squaredNorm() - h * h;
    if (c >= 0.0) return 0.0;
    const double sq = std::sqrt(b * b - a * c);
    return b > 0.0 ? -c / (b + sq) : (sq - b) / a;
}

}  // namespace gran
