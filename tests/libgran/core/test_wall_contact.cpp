// next_wall_contact (libgran/core/wall_motion.hpp) against a long-double brute force that samples
// the gap finely in time, locates every local minimum between samples and bisects the first
// closing zero, for the sinusoid, the parabolic piston (McNamara & Falcon 2005, Sec. II B), the
// sawtooth (Barrat & Trizac 2002) and fixed walls. The waveforms themselves: test_wall_motion.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <numbers>
#include <random>

#include "libgran/core/wall_motion.hpp"
#include "tests/support/wall_reference.hpp"

namespace gran {
namespace {

using namespace testing::wall;  // ld, kNever, kEps, kPi, PaperPiston

// ---------------------------------------------------------------------------------------------
// Contacts against the brute force

struct Particle {
    int inward;
    double base, x0, v, a, radius, t0, t_limit;
};

// The gap h(t) = k (x(t) - base - z_w(t)) - radius + shift in long double; `Wall` gives z_w and
// its derivative.
template <class Wall>
struct GapLD {
    const Wall& wall;
    Particle p;
    ld shift = 0;
    ld flight(ld t) const {
        const ld s = t - p.t0;
        return p.inward * (p.x0 - static_cast<ld>(p.base) + s * (p.v + p.a * s / 2)) - p.radius +
               shift;
    }
    ld h(ld t) const { return flight(t) - p.inward * wall.z(t); }
    ld dh(ld t) const { return p.inward * (p.v + p.a * (t - p.t0) - wall.dz(t)); }
};

struct FixedLD {
    ld z(ld) const { return 0; }
    ld dz(ld) const { return 0; }
    ld d2z(ld) const { return 0; }
    // samples of (z, dz, d2z) on a grid
    struct Grid {
        void next() {}
        ld z = 0, dz = 0, d2z = 0;
    };
    Grid grid(ld, ld) const { return {}; }
};

struct SineLD {
    ld A, w, phase;
    ld z(ld t) const { return A * sinl(w * t + phase); }
    ld dz(ld t) const { return A * w * cosl(w * t + phase); }
    ld d2z(ld t) const { return -A * w * w * sinl(w * t + phase); }
    // sin and cos on the grid t0 + i dt by rotation (error ~1e-19 per step)
    struct Grid {
        ld A, w, c, s, cd, sd;
        ld z, dz, d2z;
        void next() {
            const ld c2 = c * cd - s * sd;
            s = s * cd + c * sd;
            c = c2;
            z = A * s;
            dz = A * w * c;
            d2z = -A * w * w * s;
        }
    };
    Grid grid(ld t0, ld dt) const {
        const ld th = w * t0 + phase;
        return {A, w, cosl(th), sinl(th), cosl(w * dt), sinl(w * dt), z(t0), dz(t0), d2z(t0)};
    }
};

struct PistonLD {
    PaperPiston paper;
    ld shift;  // phase / omega
    ld z(ld t) const { return paper.z(t + shift); }
    ld dz(ld t) const { return paper.dz(t + shift); }
    ld d2z(ld t) const { return paper.d2z(t + shift); }
    struct Grid {
        const PistonLD* p;
        ld t, dt, z, dz, d2z;
        void next() {
            t += dt;
            z = p->z(t);
            dz = p->dz(t);
            d2z = p->d2z(t);
        }
    };
    Grid grid(ld t0, ld dt) const { return {this, t0, dt, z(t0), dz(t0), d2z(t0)}; }
};

// Bisection of a sign change of fn on [lo, hi] (fn(lo) on the `positive` side), to the last bit.
template <class F>
ld bisect(F fn, ld lo, ld hi, bool lo_positive) {
    for (int it = 0; it < 200; ++it) {
        const ld mid = lo + (hi - lo) / 2;
        if (!(mid > lo && mid < hi)) break;
        ((fn(mid) > 0) == lo_positive ? lo : hi) = mid;
    }
    return hi;
}

// The first closing zero of h on [ta, tb], where h' is monotone (h'' of one sign), h(ta) > 0 (or
// h(ta) = 0 and rising): a sign change of h, or a local minimum (h' from - to +) at or below 0.
template <class Wall>
ld closing_zero(const GapLD<Wall>& g, ld ta, ld tb, ld da, ld hb, ld db) {
    auto h = [&](ld t) { return g.h(t); };
    if (hb <= 0) return bisect(h, ta, tb, true);
    if (da < 0 && db > 0) {
        const ld tm = bisect([&](ld t) { return -g.dh(t); }, ta, tb, true);
        if (g.h(tm) <= 0) return bisect(h, ta, tm, true);
    }
    return INFINITY;
}

// Brute force: 500 samples per period (and in the whole window at least); a sample interval where
// h'' changes sign (an inflection of the sinusoid, a join of the piston) is split there by
// bisection of h'', so that h' is monotone on each part and closing_zero can miss nothing (h''
// changes sign at most twice per period: at two inflections or two joins).
template <class Wall>
ld reference_contact(const GapLD<Wall>& g, ld period) {
    constexpr long per_period = 500;
    const ld t0 = g.p.t0, window = static_cast<ld>(g.p.t_limit) - t0;
    if (!(window > 0)) return INFINITY;
    const long n = std::max(per_period, static_cast<long>(std::ceil(window / period * per_period)));
    const ld dt = window / n;
    const int k = g.p.inward;
    auto grid = g.wall.grid(t0, dt);
    auto d2h = [&](ld t) { return k * (g.p.a - g.wall.d2z(t)); };
    ld ta = t0, da = g.dh(t0), ca = k * (g.p.a - grid.d2z);
    for (long i = 1; i <= n; ++i) {
        grid.next();
        const ld tb = t0 + i * dt;
        const ld hb = g.flight(tb) - k * grid.z;
        const ld db = k * (g.p.v + g.p.a * (tb - t0) - grid.dz);
        const ld cb = k * (g.p.a - grid.d2z);
        if ((ca > 0) != (cb > 0)) {
            const ld tc = bisect(d2h, ta, tb, ca > 0);
            const ld root = closing_zero(g, ta, tc, da, g.h(tc), g.dh(tc));
            if (std::isfinite(root)) return root;
            ta = tc;
            da = g.dh(tc);
        }
        const ld root = closing_zero(g, ta, tb, da, hb, db);
        if (std::isfinite(root)) return root;
        ta = tb;
        da = db;
        ca = cb;
    }
    return INFINITY;
}

struct Stats {
    int cases = 0, contacts = 0, marginal = 0, failures = 0;
    double worst = 0;           // max |t - t_ref| / period over agreeing contacts
    double worst_residual = 0;  // max |h(t)| at the returned times / round-off
};

// Round-off of the gap evaluated in double: its terms, and the wall's position at a time (or phase
// omega t + phase) known to eps |t| only, times the wall's top speed.
double gap_roundoff(const WallMotion& w, const Particle& p) {
    const double window = p.t_limit - p.t0;
    const double top_speed = w.kind == WallMotion::Kind::sinusoid ? std::abs(w.amplitude) * w.omega
                             : w.kind == WallMotion::Kind::parabolic_piston
                                 ? 2 * std::abs(w.amplitude) * w.omega / kPi
                                 : 0.0;
    return 64 * kEps *
               (std::abs(p.x0) + std::abs(p.base) + p.radius + 2 * w.reach() +
                std::abs(p.v) * window + std::abs(p.a) * window * window) +
           (top_speed > 0
                ? 8 * kEps * (std::abs(p.t_limit) + std::abs(w.phase / w.omega)) * top_speed
                : 0.0);
}

// Compares next_wall_contact with the brute force. A disagreement beyond `tol` is accepted only as
// round-off at a graze: the result must lie between the references for the gap shifted by -+delta
// (the first closing time of h - delta <= that of h <= that of h + delta).
template <class Wall>
void check_case(const WallMotion& w, const Wall& ref_wall, const Particle& p, ld period,
                double curvature, Stats& st) {
    const double delta = gap_roundoff(w, p);
    GapLD<Wall> g{ref_wall, p};
    // the brute force needs h(t0) > 0, clear of round-off (else a contact now is legitimate)
    if (!(g.h(p.t0) > 2 * delta)) return;
    ++st.cases;
    const double got =
        next_wall_contact(w, p.base, p.inward, p.x0, p.v, p.a, p.radius, p.t0, p.t_limit);
    const ld ref = reference_contact(g, period);
    if (std::isfinite(got)) {
        // backward error: the result is an exact contact for a gap off by |h(got)|, in units of
        // the round-off of the gap, eps (|x0| + |base| + ...), and of the time, eps |t| |h'|
        const ld unit = delta / 64 + kEps * std::fabs(got * g.dh(got));
        const double residual = static_cast<double>(std::fabs(g.h(got)) / unit);
        st.worst_residual = std::max(st.worst_residual, residual);
    }
    const ld tol = 1e-12L * period + 8 * kEps * std::abs(p.t0);
    auto describe = [&] {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "kind %d A=%.17g omega=%.17g phase=%.17g | inward=%d base=%.17g x0=%.17g "
                      "v=%.17g a=%.17g r=%.17g t0=%.17g t_limit=%.17g: got %.17g, reference %.17Lg",
                      static_cast<int>(w.kind), w.amplitude, w.omega, w.phase, p.inward, p.base,
                      p.x0, p.v, p.a, p.radius, p.t0, p.t_limit, got, ref);
        return std::string(buf);
    };
    if (!(std::isinf(got) || (got > p.t0 && got <= p.t_limit))) {
        ++st.failures;
        ADD_FAILURE() << "outside (t0, t_limit]: " << describe();
        return;
    }
    if (std::isfinite(got)) {
        ++st.contacts;
        // closing in on the wall, up to round-off at a graze
        const ld closing = g.dh(got);
        if (closing > std::sqrt(2 * curvature * delta) + curvature * tol) {
            ++st.failures;
            ADD_FAILURE() << "receding contact (h' = " << static_cast<double>(closing)
                          << "): " << describe();
            return;
        }
    }
    if (std::isinf(ref) && std::isinf(got)) return;
    if (std::isfinite(ref) && std::isfinite(got) && std::fabs(got - ref) <= tol) {
        st.worst = std::max(st.worst, static_cast<double>(std::fabs(got - ref) / period));
        return;
    }
    GapLD<Wall> lower{ref_wall, p, -delta}, upper{ref_wall, p, delta};
    const ld early = reference_contact(lower, period);
    const ld late = reference_contact(upper, period);
    if (early - tol <= got && got <= late + tol) {
        ++st.marginal;
        return;
    }
    if (++st.failures <= 10) ADD_FAILURE() << describe();
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A random particle near (or far from) a wall: gap, velocity relative to the wall, gravity towards
// or away from it, any curvature, windows up to 3 periods, times up to 10^4 periods.
Particle random_particle(std::mt19937_64& rng, const WallMotion& w, double period, double speed,
                         double wall_acc) {
    Particle p{};
    p.inward = (rng() & 1) ? 1 : -1;
    p.base = uniform(rng, -0.5, 0.5);
    p.radius = uniform(rng, 5e-4, 5e-3);
    const double rt = uniform(rng, 0, 1);
    p.t0 = period * (rt < 0.1 ? uniform(rng, 1e3, 1e4) : rt < 0.15 ? 0.0 : uniform(rng, 0, 50));
    const double rw = uniform(rng, 0, 1);
    p.t_limit = p.t0 + (rw < 0.03 ? 0.0 : period * uniform(rng, 0, 3));
    const double ra = uniform(rng, 0, 1);
    p.a = ra < 0.25   ? 0.0
          : ra < 0.5  ? -p.inward * 9.81  // gravity towards the wall (a floor)
          : ra < 0.65 ? p.inward * 9.81   // away from it (a ceiling)
                      : uniform(rng, -3, 3) * wall_acc;
    const double reach = std::max(w.reach(), 1e-3);
    const double rg = uniform(rng, 0, 1);
    const double gap = rg < 0.5    ? uniform(rng, 0, 2) * reach
                       : rg < 0.65 ? uniform(rng, 0, 1e-6) * reach
                       : rg < 0.75 ? uniform(rng, 0, 1e-12) * reach
                                   : uniform(rng, 2, 10) * reach;
    p.v = wall_velocity(w, p.inward, p.t0) + uniform(rng, -2, 2) * speed;
    if (w.kind == WallMotion::Kind::sawtooth) p.v = uniform(rng, -2, 2) * speed;
    p.x0 = p.base + w.position(p.t0) + p.inward * (p.radius + gap);
    return p;
}

// Prints a brute-force comparison's tallies (worst time error in `unit`s, after scaling by
// `time_scale`) and holds every comparison to the same bounds: no failure, at least 3000
// contacts, fewer than 20 graze-marginal cases, residual gaps within 100 round-offs.
void expect_agreement(const char* name, const Stats& st, double time_scale, const char* unit) {
    std::printf(
        "%s: %d cases, %d contacts, %d graze-marginal, |t - t_ref| <= %.2g %s, "
        "|h(t)| <= %.2g round-off\n",
        name, st.cases, st.contacts, st.marginal, time_scale * st.worst, unit, st.worst_residual);
    EXPECT_EQ(st.failures, 0);
    EXPECT_GT(st.contacts, 3000);
    EXPECT_LT(st.marginal, 20);
    EXPECT_LT(st.worst_residual, 100);
}

TEST(WallContact, SinusoidMatchesBruteForce) {
    std::mt19937_64 rng(2005);
    Stats st;
    while (st.cases < 10000) {
        const double f = uniform(rng, 5, 50), A = uniform(rng, 5e-4, 2e-2);
        const WallMotion w = WallMotion::sinusoid(A, 2 * kPi * f, uniform(rng, 0, 2 * kPi));
        const Particle p = random_particle(rng, w, 1 / f, A * w.omega, A * w.omega * w.omega);
        const SineLD ref{A, w.omega, w.phase};
        check_case(w, ref, p, 1 / f, std::abs(p.a) + A * w.omega * w.omega, st);
    }
    expect_agreement("sinusoid", st, 1.0, "T");
}

TEST(WallContact, ParabolicPistonMatchesBruteForce) {
    std::mt19937_64 rng(1955);
    Stats st;
    while (st.cases < 10000) {
        const double f = uniform(rng, 5, 50), A = uniform(rng, 1e-3, 5e-2);
        const WallMotion w = WallMotion::parabolic_piston(A, f, uniform(rng, 0, 2 * kPi));
        const Particle p = random_particle(rng, w, 1 / f, 4 * A * f, 16 * A * f * f);
        const PistonLD ref{{A, f}, static_cast<ld>(w.phase) / w.omega};
        check_case(w, ref, p, 1 / f, std::abs(p.a) + 16 * A * f * f, st);
    }
    expect_agreement("piston", st, 1.0, "T");
}

TEST(WallContact, FixedAndSawtoothWallsMatchBruteForce) {
    std::mt19937_64 rng(2002);
    Stats st;
    while (st.cases < 10000) {
        const WallMotion w = (rng() & 1) ? WallMotion::fixed() : WallMotion::sawtooth(0.3);
        const double scale = 0.1;  // time scale of the windows [s]
        const Particle p = random_particle(rng, w, scale, 0.05, 20);
        const FixedLD ref;
        check_case(w, ref, p, scale, std::abs(p.a), st);
    }
    expect_agreement("fixed/sawtooth", st, 0.1, "s");
}

// A particle that has just bounced off a moving wall (gap 0, receding from it) is met again when
// the wall catches up, never at t0 itself: the chattering of a bed resting on a vibrated floor.
template <class Wall>
void check_bounce(const WallMotion& w, const Wall& ref_wall, double period, double speed,
                  double wall_acc, std::mt19937_64& rng, Stats& st) {
    Particle p{};
    p.inward = (rng() & 1) ? 1 : -1;
    p.base = uniform(rng, -0.5, 0.5);
    p.radius = uniform(rng, 5e-4, 5e-3);
    p.t0 = period * uniform(rng, 0, 50);
    p.t_limit = p.t0 + period * uniform(rng, 0.1, 2);
    const double ra = uniform(rng, 0, 1);
    p.a = ra < 0.5 ? -p.inward * 9.81 : ra < 0.75 ? 0.0 : uniform(rng, -3, 3) * wall_acc;
    // below round-off (slow) only "never at t0" and "not after the long-double re-hit" are defined:
    // the relative velocity itself is uncertain to eps |t| |wall acceleration|
    const bool slow = uniform(rng, 0, 1) < 0.2;
    const double recession =
        speed * std::pow(10.0, slow ? uniform(rng, -14, -8) : uniform(rng, -4, 0));
    p.v = wall_velocity(w, p.inward, p.t0) + p.inward * recession;
    p.x0 = p.base + w.position(p.t0) + p.inward * p.radius;
    ++st.cases;
    const double got =
        next_wall_contact(w, p.base, p.inward, p.x0, p.v, p.a, p.radius, p.t0, p.t_limit);
    GapLD<Wall> g{ref_wall, p};
    g.shift = -g.h(p.t0);  // exactly in contact at t0
    const ld ref = reference_contact(g, period);
    const double delta = gap_roundoff(w, p);
    const ld tol =
        1e-12L * period + 8 * kEps * p.t0 + 4 * delta / std::max<ld>(std::fabs(g.dh(ref)), 1e-300L);
    const bool ok = got > p.t0 && (std::isinf(got) || got <= p.t_limit) &&
                    (slow ? ref <= p.t0 + tol || !(got > ref + tol)  // long double may disagree
                          : (std::isinf(ref) ? std::isinf(got) : std::fabs(got - ref) <= tol));
    if (std::isfinite(got)) ++st.contacts;
    if (!ok && ++st.failures <= 10) {
        ADD_FAILURE() << std::setprecision(17) << "bounce: kind " << static_cast<int>(w.kind)
                      << " A=" << w.amplitude << " omega=" << w.omega << " phase=" << w.phase
                      << " slow=" << slow << " inward=" << p.inward << " x0=" << p.x0
                      << " v=" << p.v << " a=" << p.a << " r=" << p.radius << " base=" << p.base
                      << " t0=" << p.t0 << " t_limit=" << p.t_limit << " got " << got
                      << " reference " << static_cast<double>(ref);
    }
}

TEST(WallContact, JustBouncedParticleIsMetAgainNeverAtOnce) {
    std::mt19937_64 rng(42);
    Stats sine, piston;
    for (int i = 0; i < 2000; ++i) {
        const double f = uniform(rng, 5, 50), A = uniform(rng, 1e-3, 2e-2);
        const WallMotion ws = WallMotion::sinusoid(A, 2 * kPi * f, uniform(rng, 0, 2 * kPi));
        check_bounce(ws, SineLD{A, ws.omega, ws.phase}, 1 / f, A * ws.omega,
                     A * ws.omega * ws.omega, rng, sine);
        const WallMotion wp = WallMotion::parabolic_piston(2 * A, f, uniform(rng, 0, 2 * kPi));
        check_bounce(wp, PistonLD{{2 * A, f}, static_cast<ld>(wp.phase) / wp.omega}, 1 / f,
                     8 * A * f, 32 * A * f * f, rng, piston);
    }
    std::printf("bounces: sinusoid %d re-hits of %d, piston %d of %d\n", sine.contacts, sine.cases,
                piston.contacts, piston.cases);
    EXPECT_EQ(sine.failures, 0);
    EXPECT_EQ(piston.failures, 0);
    EXPECT_GT(sine.contacts, 500);
    EXPECT_GT(piston.contacts, 500);
}

TEST(WallContact, RestingOnAFloorUnderGravityIsAContactNow) {
    // gap exactly 0 (x0 - base = radius), at rest, pushed into the wall: it would sink at once, so
    // the contact is now (t0). Without gravity it never happens.
    const double g = 9.81, t0 = 2.5;
    for (const WallMotion& w : {WallMotion::fixed(), WallMotion::sawtooth(0.2)}) {
        EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 0.0, -g, 0.5, t0, 10.0), t0);  // floor
        EXPECT_EQ(next_wall_contact(w, 1.0, -1, 0.5, 0.0, +g, 0.5, t0, 10.0), t0);  // ceiling
        EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 0.0, 0.0, 0.5, t0, 10.0), kNever);
        EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 0.0, +g, 0.5, t0, 10.0), kNever);
    }
    // on the piston at its lowest position (at rest, accelerating upwards): also now
    const WallMotion piston = WallMotion::parabolic_piston(0.025, 20);
    EXPECT_EQ(next_wall_contact(piston, 0.0125, +1, 0.5, 0.0, -g, 0.5, 0.0, 1.0), 0.0);
    EXPECT_EQ(next_wall_contact(piston, 0.0125, +1, 0.5, 0.0, 0.0, 0.5, 0.0, 1.0), 0.0);
    // an overlap by round-off, closing in: now, for every waveform
    const WallMotion sine = WallMotion::sinusoid(0.01, 60, 0.2);
    const double z = sine.position(t0), u = sine.velocity(t0);
    EXPECT_EQ(next_wall_contact(sine, 0.0, +1, z + 0.5 - 1e-15, u - 1e-3, -g, 0.5, t0, 9.0), t0);
    EXPECT_EQ(next_wall_contact(sine, 0.0, -1, z - 0.5 + 1e-15, u + 1e-3, -g, 0.5, t0, 9.0), t0);
}

TEST(WallContact, FallingAndBouncingOnAStaticFloorAreExact) {
    const double g = 9.81, t0 = 3.0;
    const WallMotion w = WallMotion::fixed();
    // from rest 0.1 above the floor: sqrt(2 h / g)
    EXPECT_NEAR(next_wall_contact(w, 0.0, +1, 0.6, 0.0, -g, 0.5, t0, 10.0), t0 + std::sqrt(0.2 / g),
                8 * kEps * t0);
    // a = 0 is exactly linear
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 1.5, -2.0, 0.0, 0.5, t0, 10.0), t0 + 0.5);
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 1.5, +2.0, 0.0, 0.5, t0, kNever), kNever);
    // just bounced (gap 0, receding): back after 2 v / g, not now
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 2.0, -4.0, 0.5, t0, 10.0), t0 + 1.0);
    EXPECT_EQ(next_wall_contact(w, 1.0, -1, 0.5, -2.0, 4.0, 0.5, t0, 10.0), t0 + 1.0);
    // bounced, but by round-off still overlapping: the same, not now
    EXPECT_NEAR(next_wall_contact(w, 0.0, +1, 0.5 - 1e-16, 2.0, -4.0, 0.5, t0, 10.0), t0 + 1.0,
                8 * kEps * t0);
    // the window: the contact at t0 + 1 is inside [t0, t0 + 1] but not [t0, t0 + 0.999]
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 2.0, -4.0, 0.5, t0, t0 + 1.0), t0 + 1.0);
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 2.0, -4.0, 0.5, t0, t0 + 0.999), kNever);
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.6, -1.0, 0.0, 0.5, t0, t0), kNever);
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.6, -1.0, 0.0, 0.5, t0, t0 - 1), kNever);
}

TEST(WallContact, GrazingIsNoContact) {
    // pushed away from a static floor, turning exactly at contact: h = (1 - s)^2
    EXPECT_EQ(next_wall_contact(WallMotion::fixed(), 0.0, +1, 1.5, -2.0, 2.0, 0.5, 0.0, 9.0),
              kNever);
    // a particle at rest at the highest point the wall reaches (+- 1e-9 A): untouched above it, hit
    // just before the wall's maximum below it
    const double A = 0.01, f = 10, omega = 2 * kPi * f, r = 0.001;
    const WallMotion sine = WallMotion::sinusoid(A, omega);
    EXPECT_EQ(next_wall_contact(sine, 0.0, +1, r + A * (1 + 1e-9), 0, 0, r, 0.0, 10 / f), kNever);
    const double hit = next_wall_contact(sine, 0.0, +1, r + A * (1 - 1e-9), 0, 0, r, 0.0, 10 / f);
    const double theta = static_cast<double>(asinl((r + A * (1 - 1e-9) - r) / A));
    EXPECT_NEAR(hit, theta / omega, 1e-12 / f);
    EXPECT_LT(hit, 0.25 / f);  // before the top, closing in
    EXPECT_GT(sine.velocity(hit), 0);
    // the same against the piston's top, A / 2 at t = 2 t0 = 1 / (2 f)
    const WallMotion piston = WallMotion::parabolic_piston(2 * A, f);
    const double top = r + A;
    EXPECT_EQ(next_wall_contact(piston, 0.0, +1, top + 1e-12, 0, 0, r, 0.0, 10 / f), kNever);
    const double hp = next_wall_contact(piston, 0.0, +1, top - 1e-11, 0, 0, r, 0.0, 10 / f);
    // z = A (1 - d^2 / t0^2) = A - 1e-11 at d = -t0 sqrt(1e-11 / A)
    const double t0p = 1 / (4 * f);
    EXPECT_NEAR(hp, 2 * t0p - t0p * std::sqrt(1e-11 / A), 1e-9 * t0p);
}

TEST(WallContact, ParticleAtRestIsMetByTheRisingPiston) {
    // piston lowest at t = 0; a particle at rest with its bottom at z* = 4 mm is hit on the second
    // parabola, z = (A / 2) (1 - (t - 2 t0)^2 / t0^2): t = 2 t0 - t0 sqrt(1 - 2 z* / A)
    const double A = 0.025, f = 20, t0 = 1 / (4 * f), base = 0.3, r = 0.001, zs = 0.004;
    const WallMotion w = WallMotion::parabolic_piston(A, f);
    const double t = next_wall_contact(w, base, +1, base + zs + r, 0, 0, r, 0.0, 1.0);
    const double expected = 2 * t0 - t0 * std::sqrt(1 - 2 * zs / A);
    EXPECT_NEAR(t, expected, 4 * kEps);
    // wall velocity at contact: dz/dt = -A (t - 2 t0) / t0^2 > 0, for v_n' - u = -e (v_n - u)
    EXPECT_NEAR(wall_velocity(w, +1, t), -A * (expected - 2 * t0) / (t0 * t0), 1e-12);
    EXPECT_GT(wall_velocity(w, +1, t), 0);
    // one period later, the same
    const double t1 = next_wall_contact(w, base, +1, base + zs + r, 0, 0, r, 1 / f, 2.0);
    EXPECT_NEAR(t1, expected + 1 / f, 8 * kEps);
    // a ceiling piston (inward -1) moving down onto a particle below it
    const double tc = next_wall_contact(w, base, -1, base + zs - r, 0, 0, r, 0.0, 1.0);
    EXPECT_NEAR(tc, 4 * t0 - expected, 8 * kEps);  // z falls back through z* in the second half
}

TEST(WallContact, OverlapThatNeverClearsIsMetWhenItStartsClosing) {
    // gap -1e-15, receding at 1e-9 relative to a wall accelerating towards the particle: it never
    // gets clear, and is met at its maximum gap (s = h' / |h''|), not at t0 and not never
    const double A = 0.01, omega = 300, g = 9.81;
    const WallMotion w = WallMotion::sinusoid(A, omega, -kPi / 2);  // lowest at t = 0
    const double t0 = 0.0, r = 0.5;
    const double x0 = w.position(t0) + r - 1e-15, v = w.velocity(t0) + 1e-9;
    const double t = next_wall_contact(w, 0.0, +1, x0, v, -g, r, t0, 1.0);
    const double curvature = g + A * omega * omega;  // |h''|
    EXPECT_GT(t, t0);
    EXPECT_NEAR(t, 1e-9 / curvature, 1e-3 * 1e-9 / curvature);
    // the piston at its lowest (accelerating upwards at 16 A f^2): the same
    const WallMotion p = WallMotion::parabolic_piston(0.025, 20);
    const double tp = next_wall_contact(p, 0.0, +1, -0.0125 + r - 1e-15, 1e-9, -g, r, 0.0, 1.0);
    EXPECT_NEAR(tp, 1e-9 / (g + 16 * 0.025 * 400), 1e-12 * 1e-9);
}

TEST(WallContact, FarParticlesAndLongWindows) {
    const double A = 0.01, f = 25, g = 9.81;
    for (const WallMotion& w :
         {WallMotion::sinusoid(A, 2 * kPi * f, 1.0), WallMotion::parabolic_piston(2 * A, f, 1.0)}) {
        // flying away with nothing to bring it back: never, even with an infinite window
        EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 1.0, 0.0, 0.001, 0.0, kNever), kNever);
        EXPECT_EQ(next_wall_contact(w, 0.0, -1, -0.5, -1.0, 0.0, 0.001, 0.0, kNever), kNever);
        // thrown up 1 m/s from 0.5 m, back under gravity after ~0.5 s: a closing contact
        const double t = next_wall_contact(w, 0.0, +1, 0.5, 1.0, -g, 0.001, 0.0, kNever);
        ASSERT_TRUE(std::isfinite(t));
        const double x = 0.5 + t * (1.0 - 0.5 * g * t);
        EXPECT_NEAR(x - 0.001, w.position(t), 1e-12);
        EXPECT_LT(1.0 - g * t, w.velocity(t));  // approaching the wall
        // with a window ending just before it, nothing
        EXPECT_EQ(next_wall_contact(w, 0.0, +1, 0.5, 1.0, -g, 0.001, 0.0, t * (1 - 1e-9)), kNever);
    }
}

TEST(WallContact, SawtoothMeetsParticlesAtItsRestPosition) {
    // the virtual wall never moves; the collision rule uses u = inward * v0
    const WallMotion w = WallMotion::sawtooth(0.3);
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 1.5, -2.0, 0.0, 0.5, 0.0, 10.0), 0.5);
    EXPECT_EQ(next_wall_contact(w, 2.0, -1, 1.0, 2.0, 0.0, 0.5, 0.0, 10.0), 0.25);
    EXPECT_EQ(wall_velocity(w, -1, 0.25), -0.3);
    // moving towards the wall slower than v0 still hits it (the wall is virtual)
    EXPECT_EQ(next_wall_contact(w, 0.0, +1, 1.5, -0.1, 0.0, 0.5, 0.0, 20.0), 10.0);
}

}  // namespace
}  // namespace gran
