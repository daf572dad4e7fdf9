#pragma once
// Free flight under a constant acceleration: x(s) = x0 + v s + a s^2 / 2 (a: gravity along the
// axis, possibly 0). Root finders for the event-driven engine: when a particle reaches a cell
// boundary, and when the gap between a particle and a wall closes (static walls, piston pieces).
//
// Both use the cancellation-free roots of c + b s + (a/2) s^2 = 0 (Numerical Recipes, Sec. 5.6):
// q = -(b + sign(b) sqrt(b^2 - 2 a c)) / 2, roots s1 = 2 q / a and s2 = c / q. The root near 0 is
// always the stable c / q, so a tiny a behaves like the linear case (a == 0 is exactly linear), and
// the discriminant b^2 - 2 a c is evaluated with Kahan's fma correction.
#include <cmath>
#include <limits>

namespace gran {

// Position and velocity after a free flight of duration s.
inline double flight_position(double x0, double v, double a, double s) {
    return x0 + s * (v + 0.5 * a * s);
}
inline double flight_velocity(double v, double a, double s) {
    return v + a * s;
}

namespace free_flight_detail {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

// b^2 - 2 a c with one rounding for b^2 and the exact error of 2 a c added back (Kahan 2004, "On
// the cost of floating-point computation without extra-precise arithmetic").
inline double discriminant(double b, double a, double c) {
    const double w = 2.0 * a * c;               // 2 a is exact
    const double e = std::fma(-2.0 * a, c, w);  // w - 2 a c, exactly
    return std::fma(b, b, -w) + e;
}

}  // namespace free_flight_detail

// Earliest s in (0, s_max] at which x0 + v s + a s^2 / 2 crosses X, or +infinity. Only crossings
// count: a trajectory that touches X tangentially (a double root) does not cross it. s = 0 is never
// returned: a particle exactly on X is taken to have just crossed it (cell crossings: it moves on
// into its new cell); its next crossing is the return flight s = -2 v / a, if any.
inline double crossing_time(double x0, double v, double a, double X, double s_max) {
    using free_flight_detail::kNever;
    const double c = x0 - X;
    if (c == 0.0) {
        if (a == 0.0 || v == 0.0) return kNever;
        const double s = -2.0 * v / a;
        return s > 0.0 && s <= s_max ? s : kNever;
    }
    if (a == 0.0) {
        if (v == 0.0) return kNever;
        const double s = -c / v;
        return s > 0.0 && s <= s_max ? s : kNever;
    }
    const double disc = free_flight_detail::discriminant(v, a, c);
    if (!(disc > 0.0)) return kNever;
    const double q = -0.5 * (v + std::copysign(std::sqrt(disc), v));
    const double s1 = c / q;        // the stable root
    const double s2 = 2.0 * q / a;  // the far root (overflows harmlessly for tiny a)
    const double lo = s1 < s2 ? s1 : s2;
    const double hi = s1 < s2 ? s2 : s1;
    const double s = lo > 0.0 ? lo : hi;
    return s > 0.0 && s <= s_max ? s : kNever;
}

// Earliest s in [0, s_max] at which a gap h(s) = h + dh s + d2h s^2 / 2 (particle surface to wall,
// positive when apart) is non-positive and closing, or +infinity. With h > 0 this is the first
// downward zero crossing; a tangential touch (h = 0 with dh = 0, d2h > 0: grazing) and a receding
// particle never count. With h <= 0 (an overlap left by round-off) the contact is now (s = 0) if
// the gap is closing (dh < 0, or dh == 0 and d2h < 0: e.g. a particle at rest on a floor under
// gravity); a receding particle is met again either when its gap closes through 0 again or, if it
// never gets clear (the maximum of h is <= 0), at that maximum, where it starts approaching while
// still overlapping (so it can never sink through a wall).
inline double gap_closing_time(double h, double dh, double d2h, double s_max) {
    using free_flight_detail::kNever;
    double s = kNever;
    if (h <= 0.0) {
        if (dh < 0.0 || (dh == 0.0 && d2h < 0.0)) return 0.0;
        if (!(d2h < 0.0)) return kNever;  // receding for ever (linear or convex gap)
        const double disc = free_flight_detail::discriminant(dh, d2h, h);
        // dh >= 0, d2h < 0: the later root (dh + sqrt(disc)) / (-d2h), or the maximum dh / (-d2h)
        s = disc > 0.0 ? (dh + std::sqrt(disc)) / -d2h : dh / -d2h;
    } else if (d2h == 0.0) {
        if (dh < 0.0) s = h / -dh;
    } else {
        const double disc = free_flight_detail::discriminant(dh, d2h, h);
        if (!(disc > 0.0)) return kNever;  // never reaches 0, or only touches it (grazing)
        if (dh < 0.0) {
            s = 2.0 * h / (std::sqrt(disc) - dh);  // c / q: the first root, convex or concave
        } else if (d2h < 0.0) {
            s = (dh + std::sqrt(disc)) / -d2h;  // 2 q / a: the positive root of a concave gap
        }
    }
    return s <= s_max ? s : kNever;
}

}  // namespace gran
