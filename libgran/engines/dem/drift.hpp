#pragma once
// The opening pass of a DEM step (velocity Verlet): the previous step's closing half kick, this
// step's opening half kick, the dampers' predicted velocities, the drift with its periodic wrap,
// the displacements since the list build, and the same kicks for the spins. Plain functions on
// plain arrays; DemEngine::kick_drift picks one and hands it its threads' ranges.
//
// Two forms with the same bits:
// - kick_drift_per_grain: one grain at a time on Eigen vectors (any dimension);
// - kick_drift_pairs_3d: spheres, two grains per block, their six components in three SSE2
//   registers (the arrays of 3-vectors read as 3N doubles). Every component gets the same
//   operations in the same order as in the per-grain form (no fused multiply-add on the
//   baseline x86-64), so the two give the same bits (DemDrift.* pins that down). It takes
//   about 70 instructions per grain against about 120: the per-grain form splits each
//   3-vector into a 2-lane and a 1-lane register and back, and passes the coordinates through
//   the stack for the wrap (docs/performance.md, "The DEM drift two grains at a time").
#include <emmintrin.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "libgran/core/vec.hpp"

namespace gran {

// What the pass reads and writes. r, v, f, disp, image per grain; w, tau only when rotating.
template <int D>
struct DriftArrays {
    Vec<D>* r;
    Vec<D>* v;
    Vec<D>* v_pred;  // the dampers' predictor, ~v(t + dt)
    Vec<D>* f;       // consumed and zeroed: the forces of t + dt accumulate here
    Vec<D>* disp;    // displacement since the last list build
    std::array<std::int32_t, D>* image;
    const std::uint32_t* species;
    const double* inv_mass;  // per species
    AngVec<D>* w = nullptr;
    AngVec<D>* w_pred = nullptr;
    AngVec<D>* tau = nullptr;  // consumed and zeroed
    const double* inv_inertia = nullptr;
};

// The constants of one step.
template <int D>
struct DriftStep {
    double dt;
    Vec<D> g;
    std::array<double, D> period;  // box length on periodic axes, 0 on bounded ones
};

// Periodic wrap of one coordinate, counting the crossing in the image.
inline void wrap_coordinate(double& x, std::int32_t& image, double period) {
    if (period == 0) return;
    if (x < 0) {
        x += period;
        if (x >= period) x = 0;  // -tiny + L rounded to L
        --image;
    } else if (x >= period) {
        x -= period;
        ++image;
    }
}

// Grains [i0, i1), one at a time. Returns the largest squared displacement since the last
// build. The velocity gets h a twice (the closing and the opening half kicks, ClosingKick),
// v_pred = v + h a, r += dt v.
template <int D, bool ClosingKick>
double kick_drift_per_grain(const DriftArrays<D>& s, const DriftStep<D>& step, bool rotating,
                            std::size_t i0, std::size_t i1) {
    const double h = 0.5 * step.dt, dt = step.dt;
    const Vec<D> g = step.g;
    const std::array<double, D> period = step.period;
    double max_disp2 = 0;
    // Each grain's vectors loaded once into registers and stored once: the stores cannot then
    // force reloads (they might alias the other arrays).
    for (std::size_t i = i0; i < i1; ++i) {
        const Vec<D> a = s.inv_mass[s.species[i]] * s.f[i] + g;
        const Vec<D> ha = h * a;
        Vec<D> vi = s.v[i];
        if constexpr (ClosingKick) vi += ha;  // 4. of the previous step, as kick() does it
        vi += ha;                             // 1. half kick: v(t + dt/2)
        s.f[i].setZero();
        s.v[i] = vi;
        s.v_pred[i] = vi + ha;
        const Vec<D> dr = dt * vi;
        Vec<D> ri = s.r[i] + dr;  // 2. drift: r(t + dt)
        const Vec<D> di = s.disp[i] + dr;
        s.disp[i] = di;
        max_disp2 = std::max(max_disp2, di.squaredNorm());
        for (std::size_t k = 0; k < std::size_t(D); ++k)
            wrap_coordinate(ri[int(k)], s.image[i][k], period[k]);
        s.r[i] = ri;
    }
    if (rotating) {
        for (std::size_t i = i0; i < i1; ++i) {
            const double ii = s.inv_inertia[s.species[i]];
            const AngVec<D> ti = s.tau[i];
            AngVec<D> wi = s.w[i];
            if constexpr (ClosingKick) wi += (h * ii) * ti;  // as kick()
            const AngVec<D> halpha = h * (ii * ti);
            s.tau[i] = ang_zero<D>();
            wi += halpha;
            s.w[i] = wi;
            s.w_pred[i] = wi + halpha;
        }
    }
    return max_disp2;
}

namespace drift_detail {

// The three registers of a block of two grains: [x0 y0], [z0 x1], [y1 z1].
struct Block {
    __m128d a, b, c;
};

inline Block load_block(const double* p) {
    return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2), _mm_loadu_pd(p + 4)};
}

inline void store_block(double* p, const Block& x) {
    _mm_storeu_pd(p, x.a);
    _mm_storeu_pd(p + 2, x.b);
    _mm_storeu_pd(p + 4, x.c);
}

// A per-grain scalar spread over the block's lanes: [s0 s0], [s0 s1], [s1 s1].
inline Block per_grain(double s0, double s1) {
    return {_mm_set1_pd(s0), _mm_set_pd(s1, s0), _mm_set1_pd(s1)};
}

// A per-axis constant spread over the block's lanes: [x y], [z x], [y z].
inline Block per_axis(double x, double y, double z) {
    return {_mm_set_pd(y, x), _mm_set_pd(x, z), _mm_set_pd(z, y)};
}

}  // namespace drift_detail

// Spheres, grains [i0, i1), two per block (an odd last grain by the per-grain form). The same
// bits as kick_drift_per_grain<3, ClosingKick>.
template <bool ClosingKick, bool Rotating>
double kick_drift_pairs_3d(const DriftArrays<3>& s, const DriftStep<3>& step, std::size_t i0,
                           std::size_t i1) {
    using drift_detail::Block;
    const double h = 0.5 * step.dt;
    const __m128d hh = _mm_set1_pd(h), dt = _mm_set1_pd(step.dt), zero = _mm_setzero_pd();
    const Block g = drift_detail::per_axis(step.g[0], step.g[1], step.g[2]);
    const Block L = drift_detail::per_axis(step.period[0], step.period[1], step.period[2]);
    const Block wraps = {_mm_cmpneq_pd(L.a, zero), _mm_cmpneq_pd(L.b, zero),
                         _mm_cmpneq_pd(L.c, zero)};
    double* r = s.r->data();
    double* v = s.v->data();
    double* v_pred = s.v_pred->data();
    double* f = s.f->data();
    double* disp = s.disp->data();
    // Local copies of every pointer: the stores through them cannot alias locals, so nothing is
    // reloaded per block.
    const std::uint32_t* species = s.species;
    const double* inv_mass = s.inv_mass;
    const double* inv_inertia = s.inv_inertia;
    double* w = Rotating ? s.w->data() : nullptr;
    double* w_pred = Rotating ? s.w_pred->data() : nullptr;
    double* tau = Rotating ? s.tau->data() : nullptr;
    std::array<std::int32_t, 3>* image = s.image;
    __m128d max_disp2 = zero;
    std::size_t i = i0;
    for (; i + 2 <= i1; i += 2) {
        const std::size_t o = 3 * i;
        const std::uint32_t s0 = species[i], s1 = species[i + 1];
        const Block m = drift_detail::per_grain(inv_mass[s0], inv_mass[s1]);
        const Block fi = drift_detail::load_block(f + o), v0 = drift_detail::load_block(v + o);
        Block ri = drift_detail::load_block(r + o), di = drift_detail::load_block(disp + o);
        Block vi, vp, sq;
        // Per register, as per grain: a = m f + g, ha = h a, v (+ ha) + ha, v_pred = v + ha,
        // dr = dt v, r + dr, disp + dr.
        const auto lanes = [&](__m128d mk, __m128d fk, __m128d gk, __m128d vk, __m128d& rk,
                               __m128d& dk, __m128d& vo, __m128d& po, __m128d& qo) {
            const __m128d ha = _mm_mul_pd(hh, _mm_add_pd(_mm_mul_pd(mk, fk), gk));
            if constexpr (ClosingKick) vk = _mm_add_pd(vk, ha);
            vk = _mm_add_pd(vk, ha);
            vo = vk;
            po = _mm_add_pd(vk, ha);
            const __m128d dr = _mm_mul_pd(dt, vk);
            rk = _mm_add_pd(rk, dr);
            dk = _mm_add_pd(dk, dr);
            qo = _mm_mul_pd(dk, dk);
        };
        lanes(m.a, fi.a, g.a, v0.a, ri.a, di.a, vi.a, vp.a, sq.a);
        lanes(m.b, fi.b, g.b, v0.b, ri.b, di.b, vi.b, vp.b, sq.b);
        lanes(m.c, fi.c, g.c, v0.c, ri.c, di.c, vi.c, vp.c, sq.c);
        drift_detail::store_block(f + o, {zero, zero, zero});
        drift_detail::store_block(v + o, vi);
        drift_detail::store_block(v_pred + o, vp);
        drift_detail::store_block(disp + o, di);
        // |disp|^2 of both grains as Eigen sums a 3-vector's squares: (x^2 + y^2) + z^2.
        const __m128d x2 = _mm_shuffle_pd(sq.a, sq.b, 2);  // [x0^2 x1^2]
        const __m128d y2 = _mm_shuffle_pd(sq.a, sq.c, 1);  // [y0^2 y1^2]
        const __m128d z2 = _mm_shuffle_pd(sq.b, sq.c, 2);  // [z0^2 z1^2]
        // max(norm, max_disp2) keeps max_disp2 when norm is NaN, as std::max(max_disp2, norm).
        max_disp2 = _mm_max_pd(_mm_add_pd(_mm_add_pd(x2, y2), z2), max_disp2);
        // The periodic wrap, rare: per component by the per-grain code.
        const __m128d out_a = _mm_or_pd(_mm_cmplt_pd(ri.a, zero), _mm_cmpge_pd(ri.a, L.a));
        const __m128d out_b = _mm_or_pd(_mm_cmplt_pd(ri.b, zero), _mm_cmpge_pd(ri.b, L.b));
        const __m128d out_c = _mm_or_pd(_mm_cmplt_pd(ri.c, zero), _mm_cmpge_pd(ri.c, L.c));
        const int out = _mm_movemask_pd(_mm_and_pd(out_a, wraps.a)) |
                        _mm_movemask_pd(_mm_and_pd(out_b, wraps.b)) |
                        _mm_movemask_pd(_mm_and_pd(out_c, wraps.c));
        drift_detail::store_block(r + o, ri);
        if (out != 0) [[unlikely]] {
            for (std::size_t c = 0; c < 6; ++c)
                wrap_coordinate(r[o + c], image[i + c / 3][c % 3], step.period[c % 3]);
        }
        if constexpr (Rotating) {
            const Block ii = drift_detail::per_grain(inv_inertia[s0], inv_inertia[s1]);
            const Block ti = drift_detail::load_block(tau + o);
            Block wi = drift_detail::load_block(w + o), wp;
            // Per register, as per grain: w (+ (h ii) tau) + h (ii tau), w_pred = w + h (ii tau).
            const auto spin = [&](__m128d iik, __m128d tk, __m128d& wk, __m128d& pk) {
                if constexpr (ClosingKick) wk = _mm_add_pd(wk, _mm_mul_pd(_mm_mul_pd(hh, iik), tk));
                const __m128d halpha = _mm_mul_pd(hh, _mm_mul_pd(iik, tk));
                wk = _mm_add_pd(wk, halpha);
                pk = _mm_add_pd(wk, halpha);
            };
            spin(ii.a, ti.a, wi.a, wp.a);
            spin(ii.b, ti.b, wi.b, wp.b);
            spin(ii.c, ti.c, wi.c, wp.c);
            drift_detail::store_block(tau + o, {zero, zero, zero});
            drift_detail::store_block(w + o, wi);
            drift_detail::store_block(w_pred + o, wp);
        }
    }
    double lanes[2];
    _mm_storeu_pd(lanes, max_disp2);
    double result = std::max(lanes[0], lanes[1]);
    if (i < i1)
        result = std::max(result, kick_drift_per_grain<3, ClosingKick>(s, step, Rotating, i, i1));
    return result;
}

}  // namespace gran
