// Free-flight root finders (libgran/free_flight.hpp) against a long-double brute force: the
// quadratic c + b s + a s^2 / 2 is monotone on either side of its vertex s = -b / a, so each root
// is bracketed there and bisected to the last bit of a long double, without any root formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "libgran/core/free_flight.hpp"

namespace gran {
namespace {

using ld = long double;
constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Quadratic {
    ld c, b, a;  // c + b s + a s^2 / 2
    ld at(ld s) const { return c + s * (b + a * s / 2); }
    ld slope(ld s) const { return b + a * s; }
    // Size of the terms at s, for error bounds.
    ld scale(ld s) const { return std::fabs(c) + std::fabs(b * s) + std::fabs(a * s * s / 2); }
};

int sign(ld x) {
    return (x > 0) - (x < 0);
}

// Root of q in the monotone piece [lo, hi] (q(lo) and q(hi) of opposite signs, or q(hi) == 0).
ld bisect(const Quadratic& q, ld lo, ld hi) {
    const int s_lo = sign(q.at(lo));
    for (int it = 0; it < 20000; ++it) {
        const ld mid = lo + (hi - lo) / 2;
        if (!(mid > lo && mid < hi)) break;
        (sign(q.at(mid)) == s_lo ? lo : hi) = mid;
    }
    return hi;
}

// Monotone pieces of q on [0, s_max]: breakpoints 0, the vertex if inside, s_max (may be inf).
std::vector<ld> pieces(const Quadratic& q, ld s_max) {
    std::vector<ld> p{0};
    if (q.a != 0) {
        const ld sc = -q.b / q.a;
        if (sc > 0 && sc < s_max) p.push_back(sc);
    }
    p.push_back(s_max);
    return p;
}

// A finite end for a monotone piece [lo, inf) on which q reaches the sign `target` (doubling).
ld finite_end(const Quadratic& q, ld lo, int target) {
    ld hi = std::max<ld>(2 * lo, 1e-30L);
    while (sign(q.at(hi)) != target && hi < 1e300L) hi *= 2;
    return hi;
}

// Earliest s in (0, s_max] where q changes sign (tangential touches excluded), or inf.
ld reference_crossing(const Quadratic& q, ld s_max) {
    const std::vector<ld> p = pieces(q, s_max);
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        const ld lo = p[i];
        ld hi = p[i + 1];
        const ld q_lo = q.at(lo);
        if (q_lo == 0) continue;  // a root at lo: s = 0 (excluded) or the vertex (a touch)
        if (std::isinf(hi)) {
            const int s_inf = q.a != 0 ? sign(q.a) : sign(q.b);
            if (s_inf == sign(q_lo) || s_inf == 0) continue;
            hi = finite_end(q, lo, s_inf);
        }
        const ld q_hi = q.at(hi);
        const bool vertex = i + 2 < p.size();
        if (q_hi == 0 && vertex) continue;  // double root: a touch
        if (sign(q_hi) != sign(q_lo)) return bisect(q, lo, hi);
    }
    return INFINITY;
}

// Earliest s in [0, s_max] with q(s) <= 0 and q decreasing, or inf (gap_closing_time's definition).
ld reference_closing(const Quadratic& q, ld s_max) {
    if (q.c <= 0 && (q.b < 0 || (q.b == 0 && q.a < 0))) return 0;
    const std::vector<ld> p = pieces(q, s_max);
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        const ld lo = p[i];
        ld hi = p[i + 1];
        const ld mid = std::isinf(hi) ? 2 * lo + 1 : (lo + hi) / 2;
        if (!(q.slope(mid) < 0)) continue;  // rising piece
        if (q.at(lo) <= 0) return lo;       // falls from a non-positive maximum
        if (std::isinf(hi)) hi = finite_end(q, lo, -1);
        if (q.at(hi) <= 0) return bisect(q, lo, hi);
    }
    return INFINITY;
}

double log_uniform(std::mt19937_64& rng, double lo_exp, double hi_exp) {
    return std::pow(10.0, std::uniform_real_distribution<double>(lo_exp, hi_exp)(rng));
}
double random_sign(std::mt19937_64& rng) {
    return (rng() & 1) ? 1.0 : -1.0;
}

struct Case {
    double x0, v, a, X, s_max;
};

Case random_case(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    Case k{};
    k.x0 = random_sign(rng) * log_uniform(rng, -3, 3);
    const double r = u(rng);
    k.X = r < 0.05 ? k.x0 : k.x0 + random_sign(rng) * log_uniform(rng, -8, 2);
    k.v = u(rng) < 0.05 ? 0.0 : random_sign(rng) * log_uniform(rng, -4, 2);
    const double ra = u(rng);
    k.a = ra < 0.1 ? 0.0
                   : random_sign(rng) *
                         (ra < 0.2 ? log_uniform(rng, -30, -10) : log_uniform(rng, -3, 3));
    k.s_max = u(rng) < 0.3 ? kNever : log_uniform(rng, -3, 3);
    return k;
}

// Agreement of a double result with the long-double reference; near a double root (the vertex
// value small against the rounding of the terms) existence itself is ill-conditioned and only
// counted as marginal.
struct Tally {
    int cases = 0, hits = 0, marginal = 0, failures = 0;
    double worst = 0;  // largest |s - s_ref| / tolerance among agreeing hits
};

void compare(const Quadratic& q, ld ref, double got, double s_max, ld scale_c, Tally& t,
             const char* what, const Case& k) {
    ++t.cases;
    const ld sc = q.a != 0 ? -q.b / q.a : INFINITY;
    const ld vertex_value = std::isfinite(sc) ? q.at(sc) : INFINITY;
    const ld vertex_scale = std::isfinite(sc) ? q.scale(sc) + scale_c : 0;
    const bool near_double_root = std::fabs(vertex_value) <= 64 * kEps * vertex_scale;
    if (std::isinf(ref) && std::isinf(got)) return;
    if (std::isfinite(ref) && std::isfinite(got)) {
        ++t.hits;
        // |ds| <= rounding of the terms / |slope|; near the vertex, sqrt(2 rounding / |a|)
        const ld err = 16 * kEps * (q.scale(ref) + scale_c);
        ld tol = err / std::max<ld>(std::fabs(q.slope(ref)), 1e-300L) + 4 * kEps * ref;
        if (q.a != 0) tol = std::min(tol, 4 * std::sqrt(2 * err / std::fabs(q.a)) + 4 * kEps * ref);
        const ld dev = std::fabs(got - ref);
        if (dev <= tol) {
            t.worst = std::max(t.worst, static_cast<double>(dev / tol));
            return;
        }
    }
    const bool at_edge =
        std::fabs((std::isfinite(ref) ? ref : static_cast<ld>(got)) - s_max) <= 1e-12L * s_max;
    if (near_double_root || at_edge) {
        ++t.marginal;
        return;
    }
    if (++t.failures <= 10) {
        ADD_FAILURE() << what << ": x0=" << k.x0 << " v=" << k.v << " a=" << k.a << " X=" << k.X
                      << " s_max=" << k.s_max << " got " << got << " reference "
                      << static_cast<double>(ref);
    }
}

TEST(FreeFlight, PositionAndVelocity) {
    EXPECT_DOUBLE_EQ(flight_position(1.0, 2.0, -9.8, 0.5), 1.0 + 1.0 - 9.8 * 0.125);
    EXPECT_DOUBLE_EQ(flight_velocity(2.0, -9.8, 0.5), 2.0 - 4.9);
    EXPECT_EQ(flight_position(1.0, 2.0, 0.0, 3.0), 7.0);
}

TEST(CrossingTime, MatchesLongDoubleBisectionOnRandomFlights) {
    std::mt19937_64 rng(20240501);
    Tally t;
    for (int i = 0; i < 100000; ++i) {
        const Case k = random_case(rng);
        const Quadratic q{static_cast<ld>(k.x0) - k.X, k.v, k.a};
        const ld ref = reference_crossing(q, k.s_max);
        const double got = crossing_time(k.x0, k.v, k.a, k.X, k.s_max);
        ASSERT_TRUE(std::isinf(got) || (got > 0 && got <= k.s_max)) << got;
        // x0 - X is rounded once before solving
        compare(q, ref, got, k.s_max, std::fabs(static_cast<ld>(k.x0)) + std::fabs(k.X), t,
                "crossing_time", k);
    }
    std::printf("crossing_time: %d cases, %d crossings, %d marginal, worst %.2f of tolerance\n",
                t.cases, t.hits, t.marginal, t.worst);
    EXPECT_EQ(t.failures, 0);
    EXPECT_GT(t.hits, 30000);
    EXPECT_LT(t.marginal, t.cases / 1000);
}

TEST(CrossingTime, IsExactlyLinearWithoutAccelerationAndContinuousForTinyOnes) {
    EXPECT_EQ(crossing_time(1.0, -0.5, 0.0, 0.0, kNever), 2.0);
    EXPECT_EQ(crossing_time(1.0, 0.5, 0.0, 0.0, kNever), kNever);  // moving away
    EXPECT_EQ(crossing_time(1.0, 0.0, 0.0, 0.0, kNever), kNever);  // at rest
    EXPECT_EQ(crossing_time(1.0, -0.5, 0.0, 0.0, 1.5), kNever);    // beyond s_max
    EXPECT_EQ(crossing_time(1.0, -0.5, 0.0, 0.0, 2.0), 2.0);       // s_max included
    for (double a : {1e-300, -1e-300, 1e-200, -1e-40}) {
        EXPECT_NEAR(crossing_time(1.0, -0.5, a, 0.0, kNever), 2.0, 4 * kEps) << a;
    }
}

TEST(CrossingTime, HasNoCatastrophicCancellation) {
    // s = (sqrt(v^2 + 2 a d) - v) / a for d = 1: the textbook formula loses ~10 digits here;
    // the exact root is 2 d / (v + sqrt(v^2 + 2 a d)).
    const double v = 1.0, a = 1e-10;
    const ld exact = 2.0L / (1.0L + std::sqrt(1.0L + 2.0L * a));
    EXPECT_NEAR(crossing_time(0.0, v, a, 1.0, kNever), static_cast<double>(exact), 2 * kEps);
    // and falling a tiny height from rest, s = sqrt(2 d / g), d = 1e-300
    const double fall = std::sqrt(2e-300 / 9.81);
    EXPECT_NEAR(crossing_time(1e-300, 0.0, -9.81, 0.0, kNever), fall, 4 * kEps * fall);
}

TEST(CrossingTime, OnTheTargetItNeverReturnsZero) {
    // just crossed upwards into a cell, falls back through the same boundary at -2 v / a
    EXPECT_EQ(crossing_time(3.0, 2.0, -4.0, 3.0, kNever), 1.0);
    EXPECT_EQ(crossing_time(3.0, 2.0, 4.0, 3.0, kNever), kNever);  // accelerating away
    EXPECT_EQ(crossing_time(3.0, 2.0, 0.0, 3.0, kNever), kNever);
    EXPECT_EQ(crossing_time(3.0, 0.0, -4.0, 3.0, kNever), kNever);  // released at rest on it
    EXPECT_EQ(crossing_time(3.0, 2.0, -4.0, 3.0, 0.5), kNever);
}

TEST(CrossingTime, TangentialTouchIsNoCrossing) {
    // apex exactly at X: x = 1 + 2 s - s^2 has a double root at s = 1 for X = 2
    EXPECT_EQ(crossing_time(1.0, 2.0, -2.0, 2.0, kNever), kNever);
    EXPECT_EQ(crossing_time(1.0, 2.0, -2.0, 2.0 - 1e-9, kNever),
              crossing_time(1.0, 2.0, -2.0, 2.0 - 1e-9, 1.0));
    EXPECT_NEAR(crossing_time(1.0, 2.0, -2.0, 2.0 - 1e-10, kNever), 1.0 - 1e-5, 1e-9);
}

TEST(GapClosingTime, MatchesLongDoubleBisectionOnRandomGaps) {
    std::mt19937_64 rng(77);
    Tally t;
    for (int i = 0; i < 100000; ++i) {
        Case k = random_case(rng);
        // gap h = x0 - X: also overlaps (h <= 0) and exact contacts (h = 0)
        const double h = k.x0 - k.X;
        const Quadratic q{h, k.v, k.a};
        const ld ref = reference_closing(q, k.s_max);
        const double got = gap_closing_time(h, k.v, k.a, k.s_max);
        ASSERT_TRUE(std::isinf(got) || (got >= 0 && got <= k.s_max)) << got;
        ASSERT_EQ(got == 0, ref == 0) << "contact now: h=" << h << " dh=" << k.v << " d2h=" << k.a;
        if (h > 0) {
            ASSERT_NE(got, 0.0);
        }
        compare(q, ref, got, k.s_max, 0, t, "gap_closing_time", k);
    }
    std::printf("gap_closing_time: %d cases, %d contacts, %d marginal, worst %.2f of tolerance\n",
                t.cases, t.hits, t.marginal, t.worst);
    EXPECT_EQ(t.failures, 0);
    EXPECT_GT(t.hits, 30000);
    EXPECT_LT(t.marginal, t.cases / 1000);
}

TEST(GapClosingTime, ContactNowOnlyWhenOverlappingAndClosing) {
    EXPECT_EQ(gap_closing_time(0.0, -1.0, 0.0, kNever), 0.0);
    EXPECT_EQ(gap_closing_time(-1e-17, -1.0, 5.0, kNever), 0.0);
    // at rest on a static floor under gravity: it would sink at once, so the contact is now
    EXPECT_EQ(gap_closing_time(0.0, 0.0, -9.81, kNever), 0.0);
    // at rest on a floor without gravity: never
    EXPECT_EQ(gap_closing_time(0.0, 0.0, 0.0, kNever), kNever);
    // just bounced off a floor: back after 2 v / g, exactly as the linear-free formula
    EXPECT_EQ(gap_closing_time(0.0, 2.0, -4.0, kNever), 1.0);
    EXPECT_EQ(gap_closing_time(0.0, 2.0, -4.0, 0.999), kNever);
    // bounced, but by round-off still overlapping: met again on its way down through h = 0
    EXPECT_NEAR(gap_closing_time(-1e-17, 2.0, -4.0, kNever), 1.0, 4 * kEps);
    // overlapping, barely receding, never clear of the wall: met at its maximum
    EXPECT_DOUBLE_EQ(gap_closing_time(-1e-10, 1e-6, -9.81, kNever), 1e-6 / 9.81);
    // receding with no force back: never
    EXPECT_EQ(gap_closing_time(-1e-17, 1.0, 0.0, kNever), kNever);
    EXPECT_EQ(gap_closing_time(-1e-17, 1.0, 3.0, kNever), kNever);
}

TEST(GapClosingTime, GrazingIsNoContact) {
    // h = 1 - 2 s + s^2 = (1 - s)^2 touches 0 at s = 1 and recedes
    EXPECT_EQ(gap_closing_time(1.0, -2.0, 2.0, kNever), kNever);
    const double d = 2e-8;  // steeper by d: roots 1 + d / 2 -+ sqrt(d + d^2 / 4)
    EXPECT_NEAR(gap_closing_time(1.0, -2.0 - d, 2.0, kNever), 1 + d / 2 - std::sqrt(d + d * d / 4),
                1e-12);
    // receding, or approaching but turned back before contact
    EXPECT_EQ(gap_closing_time(1.0, 1.0, -0.0, kNever), kNever);
    EXPECT_EQ(gap_closing_time(1.0, -1.0, 1.0, kNever), kNever);
}

TEST(GapClosingTime, LinearAndTinyCurvature) {
    EXPECT_EQ(gap_closing_time(3.0, -1.5, 0.0, kNever), 2.0);
    EXPECT_EQ(gap_closing_time(3.0, -1.5, 0.0, 2.0), 2.0);
    EXPECT_EQ(gap_closing_time(3.0, -1.5, 0.0, 1.999), kNever);
    for (double d2h : {1e-300, -1e-300, 1e-100, -1e-30}) {
        EXPECT_NEAR(gap_closing_time(3.0, -1.5, d2h, kNever), 2.0, 4 * kEps) << d2h;
    }
    // falling from rest onto a floor under gravity: sqrt(2 h / g)
    EXPECT_NEAR(gap_closing_time(0.1, 0.0, -9.81, kNever), std::sqrt(0.2 / 9.81), 4 * kEps);
}

}  // namespace
}  // namespace gran
