// Soft-sphere contact laws (species/contact_laws.hpp), tangential forces and Hertz-Mindlin:
// isolated oblique collisions (tests/species/isolated_collision.hpp) against the impulse of the
// Coulomb-capped tangential dashpot in its sliding and viscous regimes, the Cundall-Strack
// tangential spring, and Hertz-Mindlin with Tsuji damping (restitution independent of the impact
// speed). The linear law's normal part: test_contact_laws.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "libgran/engines/event_driven/collision_rules.hpp"  // rough_collision
#include "species/contact_laws.hpp"
#include "tests/species/isolated_collision.hpp"

namespace gran {
namespace {

using namespace contact_test;

// ----- oblique collisions with the Coulomb-capped tangential dashpot (Eq. A8) -------------------
//
// Analytic result. With n fixed during the (short) contact, the normal motion is the damped
// oscillator above and the contact-point sliding speed u = |g_t| obeys
//     m_t du/dt = -min(gamma_t u, mu |F_n(t)|),   u(0) = u0,
// along a fixed direction t (the force is always antiparallel to g_t). Two bounds hold for the
// tangential impulse J_t = m_t (u0 - u(t_c)) (comparison of the two right-hand sides):
//     J_t <= m_t u0 (1 - beta_t),  beta_t = exp(-gamma_t t_c / m_t)   (pure dashpot)
//     J_t <= mu J_abs,  J_abs = integral of |F_n| dt                  (pure Coulomb sliding)
// so J_t <= min(m_t u0 (1 - beta_t), mu J_abs), with equality in the two limits:
//   - sliding (large incidence, gamma_t u(t) > mu |F_n(t)| throughout): J_t = mu J_abs, where
//     J_abs = m_eff v [1 - e + 2 e exp(2 r atan r)] > m_eff (1 + e) v because F_n turns tensile
//     at the end of the contact and Eq. (A8) caps with |F_n|;
//   - viscous (small incidence, gamma_t u(t) < mu |F_n(t)|): g_t' = beta_t g_t. There is no
//     sticking: the sliding velocity decays exponentially but neither vanishes nor reverses
//     (Walton's model has a tangential restitution beta_0 that can be positive, i.e. reversal;
//     the dashpot gives -beta_t in that convention, between -1 and 0). Strictly the cap is active
//     for a moment around t* where F_n changes sign, an effect proportional to u0.
// In between, the regimes alternate during the contact, and the 1D equation above is integrated
// directly (RK4, 20000 steps) as the reference.
// Returns J_t = m_t (u0 - u(t_c)).
inline double dashpot_tangential_reference(double k, double gamma_n, double m_eff, double v,
                                           double gamma_t, double mu, double m_t, double u0) {
    const double b = gamma_n / (2 * m_eff), w = std::sqrt(k / m_eff - b * b), tc = kPi / w;
    const auto fn = [&](double t) {
        const double d = v / w * std::exp(-b * t) * std::sin(w * t);
        const double dd = v * std::exp(-b * t) * (std::cos(w * t) - b / w * std::sin(w * t));
        return k * d + gamma_n * dd;
    };
    const auto du = [&](double t, double u) {
        return -std::min(gamma_t * u, mu * std::fabs(fn(t))) / m_t;
    };
    const int n = 20000;
    const double h = tc / n;
    double u = u0;
    for (int i = 0; i < n; ++i) {
        const double t = i * h;
        const double k1 = du(t, u), k2 = du(t + h / 2, u + h / 2 * k1);
        const double k3 = du(t + h / 2, u + h / 2 * k2), k4 = du(t + h, u + h * k3);
        u += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return m_t * (u0 - u);
}

enum class Regime { sliding, viscous, mixed };

template <int D>
constexpr double kQ = D == 2 ? 0.5 : 0.4;  // uniform disks, uniform spheres

// Oblique approach: normal relative speed v along -n (n = last axis), contact-point sliding
// velocity u0 along t = first axis. Against a wall by translation; for a pair (a: m = 1, R = 0.5;
// b: m = 2, R = 0.3) mostly by spin of both particles, which keeps the normal nearly fixed during
// the contact: -(w x n) = c t for w = -c (n x t).
template <int D>
Setup<D> oblique(bool wall, double v, double u0, double dt, double phase) {
    const Vec<D> n = unit<D>(D - 1), t_hat = unit<D>(0);
    Setup<D> s = head_on<D>(wall, 1.0, 2.0, v, dt, phase);
    s.a.q = s.b.q = kQ<D>;
    s.b.radius = 0.3;
    s.b.x = -(s.b.radius + 0.5 * v * phase * s.dt) * n;
    if (wall) {
        s.a.v += u0 * t_hat;
    } else {
        s.a.v += 0.25 * u0 * t_hat;
        const double c = 0.75 * u0 / (s.a.radius + s.b.radius);
        s.a.w = s.b.w = -c * cross_n<D>(n, t_hat);
    }
    return s;
}

// Sphere (or disk) on a wall or on another particle, oblique, e = 0.9, mu = 0.4, gamma_t set for
// beta_t = 0.2. u0 / v: 8 (sliding), 0.05 (viscous), 3 (mixed). Checks the post-collision
// velocities, angular velocities and contact-point sliding velocity against the prediction, as
// averages over 8 entry phases within 0.5 % of the tangential velocity change, and for every
// single collision within `worst_tol` (the tangential dashpot force jumps at the ends of the
// contact like the normal one: first-order error gamma_t dt / m_t).
template <int D>
void check_oblique_dashpot(bool wall, Regime regime, double steps_per_tc, double worst_tol) {
    const double e = 0.9, mu = 0.4, v = 1.0;
    const double u0 = regime == Regime::sliding ? 8.0 : regime == Regime::viscous ? 0.05 : 3.0;
    const double tc = wall ? 1e-3 : 1e-4;  // pair: stiff, so that n barely turns during contact
    const double q = kQ<D>;
    const Vec<D> n = unit<D>(D - 1), t_hat = unit<D>(0);
    const auto setup = [&](double phase) {
        return oblique<D>(wall, v, u0, tc / steps_per_tc, phase);
    };
    const Setup<D> s0 = setup(0.0);
    const double mb = wall ? kInf : s0.b.m;
    const double m_eff = reduced_mass(s0.a.m, mb);
    const double m_t = tangential_mass(s0.a.m, q, mb, q);
    const double k = linear_stiffness_from_duration(tc, m_eff, e);
    const double gamma_t = dashpot_tangential_damping(0.2, m_t, tc);
    const LinearDashpotContact p = linear_dashpot_contact(k, m_eff, e, mu, gamma_t);
    const double lb = wall ? 0.0 : s0.b.radius;
    const Vec<D> g0 = contact_velocity<D>(s0.a.v, s0.b.v, s0.a.w, s0.b.w, s0.a.radius, lb, n);
    ASSERT_LT((g0 + v * n - u0 * t_hat).norm(), 1e-12);

    const double jt_ref =
        dashpot_tangential_reference(k, p.gamma_n, m_eff, v, gamma_t, mu, m_t, u0);
    const double j_abs = linear_abs_normal_impulse(m_eff, v, e);
    const double beta_t = dashpot_tangential_restitution(gamma_t, m_t, tc);
    double jt = jt_ref;
    if (regime == Regime::sliding) {
        jt = mu * j_abs;
        EXPECT_NEAR(jt_ref / jt, 1.0, 1e-6);
    } else if (regime == Regime::viscous) {
        jt = m_t * u0 * (1 - beta_t);
        EXPECT_NEAR(jt_ref / jt, 1.0, 1e-3);  // the cap acts for a moment around t*
    } else {
        EXPECT_LT(jt, 0.95 * std::min(mu * j_abs, m_t * u0 * (1 - beta_t)));
    }
    // Impulse on a: J_n n - J_t t, J_n = m_eff (1 + e) v; I dw = -R n x P.
    const Vec<D> impulse = m_eff * (1 + e) * v * n - jt * t_hat;
    const double va = (s0.a.v + impulse / s0.a.m).dot(t_hat);
    const double vb = (s0.b.v - impulse / s0.b.m).dot(t_hat);
    const AngVec<D> wa = s0.a.w - (s0.a.radius / s0.a.inertia()) * cross_n<D>(n, impulse);
    const AngVec<D> wb = s0.b.w - (s0.b.radius / s0.b.inertia()) * cross_n<D>(n, impulse);
    const double u1 = u0 - jt / m_t;
    // Deviations in units of the velocity changes they resolve.
    const double dva = jt / s0.a.m, dvb = jt / s0.b.m,
                 dwa = dva * s0.a.radius / (q * s0.a.radius * s0.a.radius),
                 dwb = dvb * s0.b.radius / (q * s0.b.radius * s0.b.radius), du = jt / m_t;
    const int phases = 8;
    double mean[5] = {0, 0, 0, 0, 0}, worst[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < phases; ++i) {
        const Outcome<D> o = collide<D>(setup((i + 0.5) / phases), linear_law<D>(p));
        ASSERT_EQ(o.contacts, 1);
        if (regime == Regime::sliding) {
            EXPECT_EQ(o.slipping_steps, o.contact_steps);  // capped at every step
        } else if (regime == Regime::viscous) {
            EXPECT_LE(o.slipping_steps, 2);  // only around t*, where F_n changes sign
        } else {
            EXPECT_GT(o.slipping_steps, 5);
            EXPECT_LT(o.slipping_steps, o.contact_steps - 5);
        }
        const Vec<D> g1 = contact_velocity<D>(o.a.v, o.b.v, o.a.w, o.b.w, o.a.radius, lb, n);
        double dev[5] = {(o.a.v.dot(t_hat) - va) / dva, 0, 0, 0, (g1.dot(t_hat) - u1) / du};
        if constexpr (D == 2) {
            dev[1] = (o.a.w - wa) / dwa;
        } else {
            dev[1] = (o.a.w - wa).norm() / dwa;
        }
        if (!wall) {
            dev[2] = (o.b.v.dot(t_hat) - vb) / dvb;
            if constexpr (D == 2) {
                dev[3] = (o.b.w - wb) / dwb;
            } else {
                dev[3] = (o.b.w - wb).norm() / dwb;
            }
        }
        for (int c = 0; c < 5; ++c) {
            mean[c] += dev[c] / phases;
            worst[c] = std::max(worst[c], std::fabs(dev[c]));
        }
    }
    const char* names[5] = {"v_a.t", "w_a", "v_b.t", "w_b", "g_t"};
    for (int c = 0; c < 5; ++c) {
        EXPECT_LT(std::fabs(mean[c]), 0.005) << names[c] << " (phase average)";
        EXPECT_LT(worst[c], worst_tol) << names[c] << " (worst phase)";
    }
}

TEST(ContactLawsObliqueDashpot, WallSlidingRegimeImpulseIsMuTimesAbsoluteNormalImpulse) {
    check_oblique_dashpot<2>(true, Regime::sliding, 50.37, 0.01);
    check_oblique_dashpot<3>(true, Regime::sliding, 50.37, 0.01);
}
TEST(ContactLawsObliqueDashpot, WallViscousRegimeDecaysByBetaT) {
    check_oblique_dashpot<2>(true, Regime::viscous, 50.37, 0.01);
    check_oblique_dashpot<3>(true, Regime::viscous, 50.37, 0.01);
}
TEST(ContactLawsObliqueDashpot, WallMixedRegimeMatchesTheOneDimensionalReference) {
    check_oblique_dashpot<2>(true, Regime::mixed, 50.37, 0.01);
    check_oblique_dashpot<3>(true, Regime::mixed, 50.37, 0.01);
}
TEST(ContactLawsObliqueDashpot, PairRegimes) {
    for (Regime r : {Regime::sliding, Regime::viscous, Regime::mixed}) {
        check_oblique_dashpot<2>(false, r, 50.37, 0.01);
        check_oblique_dashpot<3>(false, r, 50.37, 0.01);
    }
}

// ----- Cundall-Strack tangential spring -------------------------------------------------------

// Undamped, with k_t / m_t = k_n / m_eff: the tangential and normal oscillations have the same
// frequency, F_t / F_n = (m_t / m_eff) (u0 / v) stays constant (no slip for u0 / v < mu m_eff /
// m_t) and both relative velocities are reversed at the end of the contact: the perfectly rough
// hard-sphere collision (rough_collision with alpha = 1, beta = +1), energy conserved.
template <int D>
void check_cundall_strack_rough_limit(bool wall) {
    const double v = 1.0, u0 = 1.0, mu = 0.4, tc = wall ? 1e-3 : 1e-4;
    for (double phase : {0.1, 0.4, 0.7}) {
        const Setup<D> s = oblique<D>(wall, v, u0, tc / 50.37, phase);
        const double mb = wall ? kInf : s.b.m;
        const double m_eff = reduced_mass(s.a.m, mb),
                     m_t = tangential_mass(s.a.m, kQ<D>, mb, kQ<D>);
        ASSERT_LT(m_t / m_eff * u0 / v, mu);
        const double k = linear_stiffness_from_duration(tc, m_eff, 1.0);
        const CundallStrackContact p =
            cundall_strack_contact(k, m_eff, 1.0, k * m_t / m_eff, 0, mu);
        const Outcome<D> o = collide<D>(s, cundall_strack_law<D>(p));
        ASSERT_EQ(o.contacts, 1);
        EXPECT_EQ(o.slipping_steps, 0);
        // Hard-sphere reference.
        Body<D> a = s.a, b = s.b;
        rough_collision<D>(a.v, b.v, a.w, b.w, a.m, mb, 2 * a.radius, 2 * b.radius, kQ<D>, kQ<D>,
                           unit<D>(D - 1), 1.0, 1.0);
        const double scale = std::hypot(v, u0);
        EXPECT_LT((o.a.v - a.v).norm(), 0.005 * scale) << "phase " << phase;
        if constexpr (D == 2) {
            EXPECT_NEAR(o.a.w, a.w, 0.005 * scale / a.radius);
        } else {
            EXPECT_LT((o.a.w - a.w).norm(), 0.005 * scale / a.radius);
        }
        if (!wall) {
            EXPECT_LT((o.b.v - b.v).norm(), 0.005 * scale) << "phase " << phase;
        }
        const double before = s.a.energy() + (wall ? 0.0 : s.b.energy());
        const double after = o.a.energy() + (wall ? 0.0 : o.b.energy());
        EXPECT_NEAR(after / before, 1.0, std::pow(kPi / 100, 2)) << "phase " << phase;
    }
}

TEST(ContactLawsCundallStrack, MatchedFrequencyIsThePerfectlyRoughLimit) {
    for (bool wall : {true, false}) {
        check_cundall_strack_rough_limit<2>(wall);
        check_cundall_strack_rough_limit<3>(wall);
    }
}

// Large incidence: the spring reaches the cap within the first step or two and the contact then
// slides, so the tangential impulse is mu J_abs as for the dashpot (e = 0.9).
template <int D>
void check_cundall_strack_sliding(bool wall) {
    const double v = 1.0, u0 = 8.0, mu = 0.4, e = 0.9, tc = wall ? 1e-3 : 1e-4;
    double mean = 0;
    const int phases = 8;
    for (int i = 0; i < phases; ++i) {
        const Setup<D> s = oblique<D>(wall, v, u0, tc / 50.37, (i + 0.5) / phases);
        const double mb = wall ? kInf : s.b.m;
        const double m_eff = reduced_mass(s.a.m, mb),
                     m_t = tangential_mass(s.a.m, kQ<D>, mb, kQ<D>);
        const double k = linear_stiffness_from_duration(tc, m_eff, e);
        const CundallStrackContact p = cundall_strack_contact(k, m_eff, e, 0.5 * k, 0, mu);
        const Outcome<D> o = collide<D>(s, cundall_strack_law<D>(p));
        ASSERT_EQ(o.contacts, 1);
        EXPECT_GE(o.slipping_steps, o.contact_steps - 2);
        const double lb = wall ? 0.0 : o.b.radius;
        const Vec<D> n = unit<D>(D - 1);
        const Vec<D> g1 = contact_velocity<D>(o.a.v, o.b.v, o.a.w, o.b.w, o.a.radius, lb, n);
        const double jt = m_t * (u0 - g1.dot(unit<D>(0)));
        const double dev = jt / (mu * linear_abs_normal_impulse(m_eff, v, e)) - 1;
        EXPECT_LT(std::fabs(dev), 0.01);
        mean += dev / phases;
        EXPECT_NEAR(g1.dot(n) / v, e, 0.005);  // the normal law is the linear one
    }
    EXPECT_LT(std::fabs(mean), 0.005);
}

TEST(ContactLawsCundallStrack, SlidingRegimeImpulseIsMuTimesAbsoluteNormalImpulse) {
    for (bool wall : {true, false}) {
        check_cundall_strack_sliding<2>(wall);
        check_cundall_strack_sliding<3>(wall);
    }
}

// ----- Hertz-Mindlin with Tsuji damping ---------------------------------------------------------

TEST(ContactLawsHertz, TsujiAlphaInvertsTheDimensionlessContact) {
    for (double e : {0.05, 0.3, 0.5, 0.7, 0.9, 0.99}) {
        const double alpha = hertz_tsuji_alpha(e);
        EXPECT_NEAR(hertz_tsuji_collision(alpha).restitution, e, 1e-10) << e;
        // Converged: a finer integration agrees.
        const HertzTsujiCollision coarse = hertz_tsuji_collision(alpha);
        const HertzTsujiCollision fine = hertz_tsuji_collision(alpha, 8000);
        EXPECT_NEAR(coarse.restitution, fine.restitution, 1e-10);
        EXPECT_NEAR(coarse.duration, fine.duration, 1e-9);
        EXPECT_NEAR(coarse.abs_impulse, fine.abs_impulse, 1e-6);
        EXPECT_GE(coarse.abs_impulse, 1 + e - 1e-9);
    }
    EXPECT_EQ(hertz_tsuji_alpha(1.0), 0.0);
    EXPECT_TRUE(std::isnan(hertz_tsuji_alpha(0.001)));
    EXPECT_TRUE(std::isnan(hertz_tsuji_alpha(1.1)));
    // Elastic: tau_c = 2 (5/4)^{2/5} (2/5) B(2/5, 1/2) = 3.2181, x_max = (5/4)^{2/5}.
    const HertzTsujiCollision elastic = hertz_tsuji_collision(0);
    EXPECT_NEAR(elastic.restitution, 1.0, 1e-12);
    EXPECT_NEAR(elastic.duration, hertz_elastic_duration(1, 1, 1), 1e-10);
    EXPECT_NEAR(elastic.duration, 3.218065, 1e-6);
    EXPECT_NEAR(elastic.max_overlap, std::pow(1.25, 0.4), 1e-6);
    EXPECT_NEAR(elastic.abs_impulse, 2.0, 1e-9);
}

// Head-on collisions at three impact speeds with the same parameters: the restitution is the
// requested one at every speed (Tsuji damping), the duration scales as v^{-1/5}. dt = t_c(v)/50.37,
// 8 entry phases. The damping force rises like delta^{1/4} at both ends of the contact, which
// makes the single-collision error of order dt^{1.3} (0.1 % for e = 0.9, 0.35 % for e = 0.7,
// 0.7 % for e = 0.5 at t_c/50); the phase average is second order (0.02 %, 0.08 %, 0.18 %).
template <int D>
void check_hertz_head_on(bool wall, double e, double worst_tol) {
    const double ma = 1.0, mb = 3.0;
    const double m_eff = wall ? ma : reduced_mass(ma, mb);
    const double k = 1e7;
    const HertzMindlinContact p = hertz_mindlin_contact(k, m_eff, e, 0, 0, 0);
    const double tau = hertz_tsuji_collision(hertz_tsuji_alpha(e)).duration;
    for (double v : {0.1, 1.0, 10.0}) {
        const double tc = tau * std::pow(m_eff / k, 0.4) * std::pow(v, -0.2);
        const int phases = 8;
        double mean = 0;
        for (int i = 0; i < phases; ++i) {
            const Setup<D> s = head_on<D>(wall, ma, mb, v, tc / 50.37, (i + 0.5) / phases);
            const Outcome<D> o = collide<D>(s, hertz_mindlin_law<D>(p));
            ASSERT_EQ(o.contacts, 1);
            const double de = normal_relative_velocity<D>(o, wall) / v / e - 1;
            EXPECT_LT(std::fabs(de), worst_tol) << "v " << v << " e " << e;
            EXPECT_NEAR((o.t_out - o.t_in) / tc, 1.0, 0.01) << "v " << v << " e " << e;
            mean += de / phases;
        }
        EXPECT_LT(std::fabs(mean), 0.005) << "v " << v << " e " << e;
    }
}

TEST(ContactLawsHertz, RestitutionIsIndependentOfImpactSpeed) {
    for (bool wall : {false, true}) {
        check_hertz_head_on<2>(wall, 0.9, 0.005);
        check_hertz_head_on<3>(wall, 0.9, 0.005);
        check_hertz_head_on<3>(wall, 0.7, 0.005);
        check_hertz_head_on<3>(wall, 0.5, 0.01);
    }
}

// Large incidence: the tangential impulse is mu times the integral of |F_n|, which for Hertz-Tsuji
// is m_eff v times the dimensionless abs_impulse(alpha).
template <int D>
void check_hertz_sliding(bool wall) {
    const double v = 1.0, u0 = 8.0, mu = 0.4, e = 0.7;
    const int phases = 8;
    double mean = 0;
    for (int i = 0; i < phases; ++i) {
        Setup<D> s = oblique<D>(wall, v, u0, 0, 0);
        const double mb = wall ? kInf : s.b.m;
        const double m_eff = reduced_mass(s.a.m, mb),
                     m_t = tangential_mass(s.a.m, kQ<D>, mb, kQ<D>);
        const double k = wall ? 1e7 : 1e9;
        const HertzMindlinContact p = hertz_mindlin_contact(k, m_eff, e, 0.8 * k, 0, mu);
        const HertzTsujiCollision dimensionless = hertz_tsuji_collision(hertz_tsuji_alpha(e));
        const double tc = dimensionless.duration * std::pow(m_eff / k, 0.4) * std::pow(v, -0.2);
        s = oblique<D>(wall, v, u0, tc / 50.37, (i + 0.5) / phases);
        const Outcome<D> o = collide<D>(s, hertz_mindlin_law<D>(p));
        ASSERT_EQ(o.contacts, 1);
        const double lb = wall ? 0.0 : o.b.radius;
        const Vec<D> g1 =
            contact_velocity<D>(o.a.v, o.b.v, o.a.w, o.b.w, o.a.radius, lb, unit<D>(D - 1));
        const double jt = m_t * (u0 - g1.dot(unit<D>(0)));
        const double dev = jt / (mu * m_eff * v * dimensionless.abs_impulse) - 1;
        EXPECT_LT(std::fabs(dev), 0.01);
        mean += dev / phases;
    }
    EXPECT_LT(std::fabs(mean), 0.005);
}

TEST(ContactLawsHertz, SlidingRegimeImpulseIsMuTimesAbsoluteNormalImpulse) {
    for (bool wall : {true, false}) {
        check_hertz_sliding<2>(wall);
        check_hertz_sliding<3>(wall);
    }
}

}  // namespace
}  // namespace gran
