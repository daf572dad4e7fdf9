#pragma once
// Prescribed motion of a wall along its normal, z_w(t) = wall_base + position(t), and the exact
// time at which a particle in parabolic free flight meets it (next_wall_contact).
//
// Waveforms:
//  - fixed: z = 0.
//  - sinusoid: z = A sin(omega t + phase), A the amplitude (half the peak-to-peak excursion).
//  - parabolic_piston: McNamara & Falcon 2005, Sec. II B: two parabolas joined with continuous
//    z and dz/dt, peak-to-peak amplitude A, frequency f, t0 = 1 / (4 f), maximum speed V = 4 A f:
//      z(t) = (A / 2) (t^2 / t0^2 - 1)              for -t0 <= t <= t0,
//      z(t) = -(A / 2) ((t - 2 t0)^2 / t0^2 - 1)    for  t0 <= t <= 3 t0, period 4 t0 = 1 / f.
//    The paper prints "z(t) = A/2 (t^2 - t0^2)" and "-A/2 (t^2 - t0^2)": dimensionally that needs
//    the 1/t0^2 and the second parabola centred on 2 t0; the form above is the only one with the
//    paper's stated properties (peak-to-peak A, V = 4 A f, period 1/f, smooth joins). The paper's
//    time origin is kept: at t = 0 (phase 0) the piston is at its lowest position, z = -A / 2, and
//    the waveform is close to -(A / 2) cos(omega t) (within 0.028 A). A phase shifts time:
//    position(t) = z(t + phase / omega), omega = 2 pi f.
//  - sawtooth: Barrat & Trizac 2002's virtual vibrating wall (the limit A -> 0, A f fixed): the
//    position stays 0 and every particle meets a wall moving into the gas with speed v0, so
//    velocity() reports v0 and wall_velocity() reports inward * v0, as the wall collision rule
//    (engines/event_driven/collision_rules.hpp) uses.
//  - sawtooth_ramp: the real wall of which `sawtooth` is the limit, for the soft-sphere engine
//    (which needs a wall position): z = s A (2 frac(f t + phase / 2 pi) - 1), moving at the
//    constant speed v0 = 2 A f into the gas (s = sign of v0) and jumping back once per period.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "libgran/core/free_flight.hpp"

namespace gran {

struct WallMotion {
    enum class Kind { fixed, sinusoid, parabolic_piston, sawtooth, sawtooth_ramp };

    Kind kind = Kind::fixed;
    double amplitude = 0;  // sinusoid: A of A sin(omega t + phase); piston: peak-to-peak A
    double omega = 0;      // angular frequency 2 pi f (sinusoid, piston), > 0 for a moving wall
    double phase = 0;      // [rad]
    double v0 = 0;         // sawtooth: speed of the wall into the gas

    static WallMotion fixed() { return {}; }
    static WallMotion sinusoid(double amplitude, double omega, double phase = 0) {
        return {Kind::sinusoid, amplitude, omega, phase, 0};
    }
    // The paper's parameters: peak-to-peak amplitude A and frequency f.
    static WallMotion parabolic_piston(double peak_to_peak, double frequency, double phase = 0) {
        return {Kind::parabolic_piston, peak_to_peak, 2 * std::numbers::pi * frequency, phase, 0};
    }
    static WallMotion sawtooth(double v0) { return {Kind::sawtooth, 0, 0, 0, v0}; }
    // Amplitude A (half the excursion), frequency f; direction +1 (moving to larger coordinates,
    // a lower wall) or -1.
    static WallMotion sawtooth_ramp(double amplitude, double frequency, double phase,
                                    double direction) {
        return {Kind::sawtooth_ramp, amplitude, 2 * std::numbers::pi * frequency, phase,
                (direction >= 0 ? 2.0 : -2.0) * amplitude * frequency};
    }

    // The wall does not move (its gap to a particle is a single quadratic in time).
    bool is_static() const {
        return kind == Kind::fixed || kind == Kind::sawtooth || amplitude == 0 || !(omega > 0);
    }
    double period() const {
        return is_static() ? std::numeric_limits<double>::infinity() : 2 * std::numbers::pi / omega;
    }
    // Largest |position(t)|: every position lies in [-reach, reach].
    double reach() const {
        if (kind == Kind::sinusoid || kind == Kind::sawtooth_ramp) return std::abs(amplitude);
        if (kind == Kind::parabolic_piston) return 0.5 * std::abs(amplitude);
        return 0;
    }

    // The parabolas of the piston: the n-th one (n even: around a lowest position, n odd: around
    // a highest) is centred on t_n = n T / 2 - phase / omega and holds for |t - t_n| <= t0 = T / 4:
    // z = s (A / 2) ((t - t_n)^2 / t0^2 - 1), s = +1 (n even) or -1 (n odd).
    struct Parabola {
        double z, dz, d2z;
    };
    double piston_index(double t) const {
        return std::floor((t + phase / omega) * omega / std::numbers::pi + 0.5);
    }
    // Time of the join that ends parabola n: t_n + t0.
    double piston_join(double n) const { return ((n + 0.5) * std::numbers::pi - phase) / omega; }
    Parabola piston_parabola(double n, double t) const {
        const double half = std::numbers::pi / omega, t0 = 0.5 * half;
        const double d = std::fma(-n, half, t + phase / omega);  // t - t_n
        const double s = std::fmod(n, 2.0) == 0 ? 1.0 : -1.0;
        const double curvature = s * amplitude / (t0 * t0);  // +-A / t0^2 = +-16 A f^2
        return {0.5 * curvature * (d - t0) * (d + t0), curvature * d, curvature};
    }
    Parabola piston_parabola(double t) const { return piston_parabola(piston_index(t), t); }

    double position(double t) const {
        switch (kind) {
            case Kind::sinusoid:
                return amplitude * std::sin(omega * t + phase);
            case Kind::parabolic_piston:
                return is_static() ? 0 : piston_parabola(t).z;
            case Kind::sawtooth_ramp: {
                if (is_static()) return 0;
                const double x =
                    omega * t / (2 * std::numbers::pi) + phase / (2 * std::numbers::pi);
                return (v0 >= 0 ? 1.0 : -1.0) * amplitude * (2 * (x - std::floor(x)) - 1);
            }
            default:
                return 0;
        }
    }
    double velocity(double t) const {
        switch (kind) {
            case Kind::sinusoid:
                return amplitude * omega * std::cos(omega * t + phase);
            case Kind::parabolic_piston:
                return is_static() ? 0 : piston_parabola(t).dz;
            case Kind::sawtooth:
                return v0;
            case Kind::sawtooth_ramp:
                return is_static() ? 0 : v0;
            default:
                return 0;
        }
    }
    // At a piston join (t0 + n T / 2) this is the acceleration of the parabola that starts there.
    double acceleration(double t) const {
        switch (kind) {
            case Kind::sinusoid:
                return -amplitude * omega * omega * std::sin(omega * t + phase);
            case Kind::parabolic_piston:
                return is_static() ? 0 : piston_parabola(t).d2z;
            default:
                return 0;
        }
    }
};

// Velocity u of the wall at time t along the axis, for the collision rule v_n' - u = -e (v_n - u):
// the derivative of the position, except for the sawtooth wall, which always moves into the gas
// (u = inward * v0). inward = +1 for a lower wall (the gas at larger coordinates), -1 for an upper.
inline double wall_velocity(const WallMotion& w, int inward, double t) {
    return w.kind == WallMotion::Kind::sawtooth ? (inward >= 0 ? w.v0 : -w.v0) : w.velocity(t);
}

namespace wall_motion_detail {

inline constexpr double kNever = std::numeric_limits<double>::infinity();
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

// The gap between a particle and a wall, h(t) = k (x(t) - wall_base - z_w(t)) - radius, k = inward,
// x(t) = x0 + v s + a s^2 / 2 with s = t - t0. Its particle part p(t) = k (x(t) - wall_base) - r.
struct Flight {
    double k, p0, v, a, t0;
    double p(double t) const { return p0 + k * flight_position(0.0, v, a, t - t0); }
    double dp(double t) const { return k * flight_velocity(v, a, t - t0); }
    double d2p() const { return k * a; }
};

struct Gap {
    double h, dh, d2h;
};

// A result in [t0, t_limit]: a contact strictly after t0 is never rounded down onto t0, which is
// reserved for a contact now (an overlap that closes at t0).
inline double clamp_result(double t, double t0, double t_limit, bool now) {
    if (now) return t0;
    if (t <= t0) t = std::nextafter(t0, kNever);
    return t < t_limit ? t : t_limit;
}

// The first time the particle can touch a wall whose positions never exceed `reach` towards the
// gas (h >= p - reach), from t on: t itself if it is within reach, +infinity if never before
// t_limit. Far particles (most of them, in flight) are dismissed or advanced here in O(1).
inline double enter_reach(const Flight& f, double reach, double t, double t_limit) {
    const double b = f.p(t) - reach * (1 + 64 * kEps);
    if (!(b > 0.0)) return t;
    const double s = gap_closing_time(b, f.dp(t), f.d2p(), t_limit - t);
    return s == kNever ? kNever : t + s;
}

// The piston: the gap is one quadratic per half period, solved exactly piece by piece.
inline double piston_contact(const WallMotion& w, const Flight& f, double t_limit) {
    const double reach = w.reach();
    double t = f.t0;
    for (;;) {
        t = enter_reach(f, reach, t, t_limit);
        if (t == kNever) return kNever;
        double n = w.piston_index(t);
        double end = w.piston_join(n);
        if (!(end > t)) end = w.piston_join(++n);  // t on the join, by round-off
        const bool last = end >= t_limit;
        if (last) end = t_limit;
        // On [t, end] the gap is exactly this quadratic (also if t sits on a join by round-off).
        const WallMotion::Parabola par = w.piston_parabola(n, t);
        const double s = gap_closing_time(f.p(t) - f.k * par.z, f.dp(t) - f.k * par.dz,
                                          f.d2p() - f.k * par.d2z, end - t);
        if (s != kNever) return clamp_result(t + s, f.t0, t_limit, t == f.t0 && s == 0.0);
        if (last) return kNever;
        t = end;
    }
}

// The sinusoid: the gap h = p(t) - k A sin(omega t + phase) is split at its inflection points, so
// that it is convex or concave on each piece. There the first closing contact is found without any
// chance of missing a root: Newton's method converges monotonically from the side where the tangent
// stays on one side of the curve (from the start for a convex gap, from the end for a concave one).
class SineGap {
  public:
    SineGap(const WallMotion& w, const Flight& f)
        : f_(f), kA_(f.k * w.amplitude), w_(w.omega), phase_(w.phase) {
        const double sigma = -f.a / (w.amplitude * w.omega * w.omega);  // sin at h'' = 0
        inflecting_ = std::abs(sigma) < 1;
        alpha_ = inflecting_ ? std::asin(sigma) : 0;
    }

    Gap at(double t) const {
        const double th = w_ * t + phase_, sn = std::sin(th), cs = std::cos(th);
        return {f_.p(t) - kA_ * sn, f_.dp(t) - kA_ * w_ * cs, f_.d2p() + kA_ * w_ * w_ * sn};
    }

    // The end of the piece of constant convexity that starts at t (at most half a period long).
    double piece_end(double t) const {
        constexpr double pi = std::numbers::pi, two_pi = 2 * pi;
        const double half = pi / w_;
        if (!inflecting_) return t + half;
        const double th = w_ * t + phase_;
        const double m = std::floor((th - alpha_) / two_pi);
        // inflections at theta = alpha + 2 pi m and pi - alpha + 2 pi m
        const double cand[4] = {alpha_ + two_pi * m, pi - alpha_ + two_pi * m,
                                alpha_ + two_pi * (m + 1), pi - alpha_ + two_pi * (m + 1)};
        for (double c : cand) {
            const double te = (c - phase_) / w_;
            if (te > t) return std::min(te, t + half);
        }
        return t + half;
    }

    // First closing contact in [ta, tb], or +infinity; `now` is set when it is ta with h(ta) <= 0.
    double first_contact(double ta, double tb, bool& now) const {
        const Gap ga = at(ta);
        now = false;
        if (ga.h <= 0.0 && (ga.dh < 0.0 || (ga.dh == 0.0 && ga.d2h < 0.0))) {
            now = true;
            return ta;
        }
        const double tol = 1e-14 * (tb - ta) + 4 * kEps * std::abs(tb);
        const bool convex = at(0.5 * (ta + tb)).d2h >= 0.0;
        return convex ? convex_contact(ta, tb, ga, tol) : concave_contact(ta, tb, ga, tol);
    }

  private:
    // h'' >= 0: h' increases; if h > 0, Newton from ta stays below the first root.
    double convex_contact(double ta, double tb, Gap g, double tol) const {
        if (g.h <= 0.0) return kNever;  // not closing at ta, hence receding over the whole piece
        double t = ta;
        for (int it = 0; it < 200; ++it) {
            if (!(g.dh < 0.0)) return kNever;  // past the minimum of h, still apart
            const double step = -g.h / g.dh;
            const double tn = t + step;
            if (tn > tb) return kNever;  // the tangent reaches 0 after tb: so does h
            if (!(tn > t)) return t;     // converged to the last bit
            t = tn;
            g = at(t);
            if (g.h <= 0.0 || step <= tol) return t;
        }
        return t;
    }

    // h'' <= 0: h' decreases; h rises to a maximum at tm (if h'(ta) > 0) and then falls.
    double concave_contact(double ta, double tb, const Gap& ga, double tol) const {
        double lo = ta;  // h(lo) > 0 from here on
        const Gap gb = at(tb);
        if (ga.h <= 0.0) {
            if (!(gb.dh < 0.0)) return kNever;  // still rising at tb
            const double tm = derivative_root(ta, tb, tol);
            if (at(tm).h <= 0.0) return tm;  // never clear of the wall: closing from its maximum
            lo = tm;
        }
        if (gb.h > 0.0) return kNever;  // concave and positive at both ends: positive throughout
        if (gb.h == 0.0) return tb;
        // Newton from tb stays at or after the root (the tangent lies above h).
        double t = tb;
        Gap g = gb;
        for (int it = 0; it < 200; ++it) {
            if (!(g.dh < 0.0)) break;
            const double step = -g.h / g.dh;  // <= 0
            const double tn = t + step;
            if (!(tn > lo)) break;
            if (!(tn < t)) return t;
            t = tn;
            g = at(t);
            if (g.h >= 0.0 || -step <= tol) return t;
        }
        // Round-off trouble (never seen in tests): bisection on [lo, t], h(lo) > 0 >= h(t).
        double hi = t;
        while (hi - lo > tol) {
            const double mid = 0.5 * (lo + hi);
            if (!(mid > lo && mid < hi)) break;
            (at(mid).h > 0.0 ? lo : hi) = mid;
        }
        return hi;
    }

    // The root of h' on [lo, hi] (h'(lo) >= 0 > h'(hi), h' decreasing): Newton kept inside a
    // shrinking bracket, bisection when it would leave it or converge slowly (Numerical Recipes'
    // rtsafe).
    double derivative_root(double lo, double hi, double tol) const {
        double t = 0.5 * (lo + hi), dx_old = hi - lo, dx = dx_old;
        Gap g = at(t);
        for (int it = 0; it < 200; ++it) {
            const bool bisect = ((t - hi) * g.d2h - g.dh) * ((t - lo) * g.d2h - g.dh) > 0.0 ||
                                std::abs(2.0 * g.dh) > std::abs(dx_old * g.d2h);
            dx_old = dx;
            if (bisect) {
                dx = 0.5 * (hi - lo);
                t = lo + dx;
            } else {
                dx = g.dh / g.d2h;
                t -= dx;
            }
            if (std::abs(dx) <= tol) return t;
            g = at(t);
            (g.dh >= 0.0 ? lo : hi) = t;
        }
        return t;
    }

    Flight f_;
    double kA_, w_, phase_;
    bool inflecting_ = false;
    double alpha_ = 0;
};

inline double sinusoid_contact(const WallMotion& w, const Flight& f, double t_limit) {
    const SineGap gap(w, f);
    const double reach = w.reach();
    double t = f.t0;
    for (;;) {
        t = enter_reach(f, reach, t, t_limit);
        if (t == kNever) return kNever;
        double end = gap.piece_end(t);
        if (!(end > t)) end = std::nextafter(t, kNever);
        const bool last = end >= t_limit;
        if (last) end = t_limit;
        bool now = false;
        const double tc = gap.first_contact(t, end, now);
        if (tc != kNever) return clamp_result(tc, f.t0, t_limit, now && t == f.t0);
        if (last) return kNever;
        t = end;
    }
}

}  // namespace wall_motion_detail

// Earliest time t in [t0, t_limit] at which a particle (centre x0 and velocity v along the wall
// normal at time t0, constant acceleration a along it, e.g. gravity; radius `radius`) touches the
// wall z_w(t) = wall_base + w.position(t) while closing in on it: the gap
//   h(t) = inward (x(t) - z_w(t)) - radius,  x(t) = x0 + v (t - t0) + a (t - t0)^2 / 2,
// reaches 0 going down. inward = +1 for a lower wall (floor, gas above), -1 for an upper one.
// Returns +infinity if there is none up to t_limit (or an input is not finite). Grazing (h touches
// 0 with h' = 0, h'' > 0) and receding particles never count.
//
// Contact now: t0 itself is returned only when the particle already overlaps the wall (h(t0) <= 0,
// by round-off) and closes in (h' < 0, or h' = 0 and h'' < 0: e.g. at rest on a static floor under
// gravity), like pair_collision_time's "collides now". A particle that overlaps and recedes is met
// again when its gap next closes through 0, or, if it never gets clear, at the time its overlap
// starts to grow again. Otherwise every returned time is > t0. At a contact with zero relative
// normal velocity (resting, or met at the maximum of an overlap) the caller must change the
// velocity (e.g. give it a small outward relative speed): left unchanged, the same contact is
// predicted again at the same time.
//
// Exact piece by piece for fixed, sawtooth (a wall at rest at wall_base for the contact) and
// parabolic_piston walls (quadratic gaps, libgran/free_flight.hpp); for the sinusoid a monotone
// Newton iteration on pieces of constant convexity (relative accuracy ~1e-14 of the piece length).
inline double next_wall_contact(const WallMotion& w, double wall_base, int inward, double x0,
                                double v, double a, double radius, double t0, double t_limit) {
    using namespace wall_motion_detail;
    if (!(t_limit >= t0) || !std::isfinite(wall_base + x0 + v + a + radius + t0)) return kNever;
    const double k = inward >= 0 ? 1.0 : -1.0;
    if (w.is_static()) {
        const double z = w.kind == WallMotion::Kind::sinusoid ? w.position(t0) : 0.0;
        const double s =
            gap_closing_time(k * (x0 - wall_base - z) - radius, k * v, k * a, t_limit - t0);
        return s == kNever ? kNever : clamp_result(t0 + s, t0, t_limit, s == 0.0);
    }
    const Flight f{k, k * (x0 - wall_base) - radius, v, a, t0};
    return w.kind == WallMotion::Kind::sinusoid ? sinusoid_contact(w, f, t_limit)
                                                : piston_contact(w, f, t_limit);
}

}  // namespace gran
