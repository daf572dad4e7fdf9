// Soft-sphere contact laws (species/contact_laws.hpp): the linear spring-dashpot of Bhateja, Sharma
// & Singh 2016 (Appendix, Eqs. A3-A9), the Cundall-Strack tangential spring and Hertz-Mindlin with
// Tsuji damping. Isolated collisions are integrated with a small velocity-Verlet integrator at
// dt = t_c / 50 (tests/species/isolated_collision.hpp) and compared with the closed forms. This
// file: the linear law's closed forms (restitution, contact duration), the kernels' identities,
// head-on collisions and the elastic limit; test_contact_laws_tangential.cpp: the tangential
// forces (Coulomb-capped dashpot, Cundall-Strack spring) and Hertz-Mindlin.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

#include "species/contact_laws.hpp"
#include "tests/species/isolated_collision.hpp"

namespace gran {
namespace {

using namespace contact_test;

// ----- closed forms of the linear law (Eq. A9 and the damped oscillator) -----------------------

TEST(ContactLawsLinear, EquationA9GivesTheRequestedRestitutionExactly) {
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
        for (double m : {0.25, 1.0, 7.0}) {
            const double k = 1e5;
            const double gamma = linear_damping_from_restitution(k, m, e);
            EXPECT_GT(gamma, 0.0);
            // The printed (A9) has the opposite sign: 2 ln(e) sqrt(k m) / sqrt(pi^2 + ln^2 e) < 0.
            const double printed = 2 * std::log(e) * std::sqrt(k * m) /
                                   std::sqrt(kPi * kPi + std::log(e) * std::log(e));
            EXPECT_NEAR(gamma, -printed, 1e-12 * gamma);
            EXPECT_NEAR(linear_restitution(k, m, gamma), e, 1e-13);
        }
    }
    EXPECT_EQ(linear_damping_from_restitution(4.0, 1.0, 1.0), 0.0);
    EXPECT_EQ(linear_damping_from_restitution(4.0, 1.0, 0.0), 4.0);  // critical: 2 sqrt(k m)
    EXPECT_EQ(linear_contact_duration(4.0, 1.0, 4.0), kInf);
    EXPECT_EQ(linear_restitution(4.0, 1.0, 5.0), 0.0);
}

TEST(ContactLawsLinear, StiffnessFromDurationRoundTrips) {
    for (double e : {0.3, 0.9, 1.0}) {
        const double m = 0.75, tc = 2.5e-3;
        const double k = linear_stiffness_from_duration(tc, m, e);
        const double gamma = linear_damping_from_restitution(k, m, e);
        EXPECT_NEAR(linear_contact_duration(k, m, gamma), tc, 1e-12 * tc);
        EXPECT_NEAR(linear_restitution(k, m, gamma), e, 1e-12);
        EXPECT_NEAR(gamma, -2 * m * std::log(e) / tc, 1e-9 * (gamma + 1));
    }
    // Undamped: t_c = pi sqrt(m / k).
    EXPECT_NEAR(linear_contact_duration(9.0, 4.0, 0.0), kPi * 2.0 / 3.0, 1e-15);
}

// delta(t) = (v/w) exp(-b t) sin(w t): compare the maximum overlap and the integral of |F_n| with
// a direct quadrature of the closed-form trajectory.
TEST(ContactLawsLinear, MaxOverlapAndAbsoluteNormalImpulseMatchQuadrature) {
    for (double e : {0.3, 0.6, 0.9, 1.0}) {
        const double m = 2, k = 50, v = 1.5;
        const double gamma = linear_damping_from_restitution(k, m, e);
        const double b = gamma / (2 * m), w = std::sqrt(k / m - b * b), tc = kPi / w;
        const int n = 200000;
        double max_delta = 0, impulse = 0, signed_impulse = 0;
        for (int i = 0; i < n; ++i) {
            const double t = (i + 0.5) * tc / n;
            const double d = v / w * std::exp(-b * t) * std::sin(w * t);
            const double dd = v * std::exp(-b * t) * (std::cos(w * t) - b / w * std::sin(w * t));
            const double f = k * d + gamma * dd;
            max_delta = std::max(max_delta, d);
            impulse += std::fabs(f) * tc / n;
            signed_impulse += f * tc / n;
        }
        EXPECT_NEAR(linear_max_overlap(k, m, gamma, v), max_delta, 1e-9 * max_delta);
        EXPECT_NEAR(linear_abs_normal_impulse(m, v, e), impulse, 1e-8 * impulse);
        EXPECT_NEAR(signed_impulse, m * (1 + e) * v, 1e-8 * impulse);
    }
    // e = 0.5: the tensile phase adds 6.7 % to the Coulomb budget.
    EXPECT_NEAR(linear_abs_normal_impulse(1, 1, 0.5) / 1.5, 1.0670, 1e-4);
}

// ----- kernel identities ------------------------------------------------------------------------

template <int D>
void check_kernel_identities() {
    // Pair with lever arms l = R - delta/2: torques balance the moment of the force (angular
    // momentum conservation) and the power F.(v_i - v_j) + tau.w equals F.g.
    Vec<D> ri = Vec<D>::Zero(), rj = Vec<D>::Zero(), vi, vj;
    for (int a = 0; a < D; ++a) {
        ri[a] = 0.1 * (a + 1);
        rj[a] = -0.2 * a + 0.05;
        vi[a] = 0.3 - 0.7 * a;
        vj[a] = -0.4 + 0.2 * a * a;
    }
    AngVec<D> wi, wj;
    if constexpr (D == 2) {
        wi = 1.3;
        wj = -0.6;
    } else {
        wi = Eigen::Vector3d(0.2, -1.1, 0.7);
        wj = Eigen::Vector3d(-0.5, 0.3, 0.9);
    }
    const double Ri = 0.4, Rj = 0.55;
    const Vec<D> r = ri - rj;
    const double dist = r.norm();
    const double delta = Ri + Rj - dist;
    ASSERT_GT(delta, 0.0);
    const Vec<D> n = r / dist;
    const double li = Ri - 0.5 * delta, lj = Rj - 0.5 * delta;
    const Vec<D> g = contact_velocity<D>(vi, vj, wi, wj, li, lj, n);
    // Same relative velocity as rough_collision (Barrat & Trizac 2002, Eq. A2) for l = R.
    EXPECT_LT((contact_velocity<D>(vi, vj, wi, wj, Ri, Rj, n) -
               (vi - vj - cross_w<D>(AngVec<D>(Ri * wi + Rj * wj), n)))
                  .norm(),
              1e-15);
    Vec<D> xi = 0.01 * Vec<D>::Ones();
    advance_tangential_spring<D>(xi, n, Vec<D>::Zero());
    const LinearDashpotContact lin{100, 3, 2, 0.5};
    const CundallStrackContact cs{100, 3, 40, 2, 0.5};
    const HertzMindlinContact hm{100, 3, 40, 2, 0.5};
    Vec<D> xi_cs = xi, xi_hm = xi;
    for (const ContactForce<D>& c : {linear_dashpot_force<D>(lin, delta, n, g, li, lj),
                                     cundall_strack_force<D>(cs, delta, n, g, li, lj, xi_cs),
                                     hertz_mindlin_force<D>(hm, delta, n, g, li, lj, xi_hm)}) {
        const AngVec<D> moment = cross_n<D>(r, c.force);  // r_i x F + r_j x (-F)
        if constexpr (D == 2) {
            EXPECT_NEAR(moment + c.torque_i + c.torque_j, 0.0, 1e-14);
        } else {
            EXPECT_LT((moment + c.torque_i + c.torque_j).norm(), 1e-14);
        }
        double power = c.force.dot(vi - vj);
        if constexpr (D == 2) {
            power += c.torque_i * wi + c.torque_j * wj;
        } else {
            power += c.torque_i.dot(wi) + c.torque_j.dot(wj);
        }
        EXPECT_NEAR(power, c.force.dot(g), 1e-13);
        EXPECT_NEAR(c.f_n, c.force.dot(n), 1e-14);
        // Tangential force never exceeds the Coulomb cap of Eq. (A8).
        EXPECT_LE((c.force - c.f_n * n).norm(), 0.5 * std::fabs(c.f_n) * (1 + 1e-14));
    }
    // (A5): F_n = k delta - gamma g_n.
    const ContactForce<D> c = linear_dashpot_force<D>(lin, delta, n, g, li, lj);
    EXPECT_NEAR(c.f_n, 100 * delta - 3 * g.dot(n), 1e-13);
    // (A7) below the cap: F_t = -gamma_t g_t.
    const LinearDashpotContact rough{100, 3, 2, 1e6};
    const ContactForce<D> c2 = linear_dashpot_force<D>(rough, delta, n, g, li, lj);
    EXPECT_LT((c2.force - c2.f_n * n + 2 * (g - g.dot(n) * n)).norm(), 1e-13);
    EXPECT_FALSE(c2.slipping);
}

TEST(ContactLawsKernels, DisksConserveAngularMomentumAndDissipateThroughContactVelocity) {
    check_kernel_identities<2>();
}
TEST(ContactLawsKernels, SpheresConserveAngularMomentumAndDissipateThroughContactVelocity) {
    check_kernel_identities<3>();
}

// The linear dashpot's tangential force (Eqs. A7, A8): -gamma_t g_t while gamma_t |g_t| <= mu |F_n|
// (the comparison is made squared, without the slip speed's square root); at the cap exactly
// mu |F_n| along -g_t. Both sides of the cap, 1% away, and a contact that does not slide.
template <int D>
void check_linear_dashpot_cap() {
    const Vec<D> n = unit<D>(D - 1);
    const Vec<D> g_t = 0.3 * unit<D>(0);
    const Vec<D> g = g_t - 0.2 * n;
    const double delta = 0.01, l = 0.5;
    const LinearDashpotContact base{1000, 5, 4, 0};
    const double f_n = 1000 * delta + 5 * 0.2;
    const double mu_edge = 4 * 0.3 / f_n;  // gamma_t |g_t| = mu |F_n|
    for (const double factor : {0.99, 1.01}) {
        LinearDashpotContact p = base;
        p.mu = factor * mu_edge;
        const ContactForce<D> c = linear_dashpot_force<D>(p, delta, n, g, l, l);
        const Vec<D> f_t = c.force - c.f_n * n;
        EXPECT_NEAR(c.f_n, f_n, 1e-12);
        if (factor < 1) {  // slides: capped
            EXPECT_TRUE(c.slipping);
            EXPECT_NEAR(f_t.norm(), p.mu * f_n, 1e-12);
        } else {
            EXPECT_FALSE(c.slipping);
            EXPECT_NEAR(f_t.norm(), 4 * 0.3, 1e-12);
        }
        EXPECT_NEAR(f_t.normalized().dot(g_t.normalized()), -1.0, 1e-14);
    }
    LinearDashpotContact p = base;
    p.mu = 0.5;
    const ContactForce<D> still = linear_dashpot_force<D>(p, delta, n, Vec<D>(-0.2 * n), l, l);
    EXPECT_FALSE(still.slipping);
    EXPECT_EQ((still.force - still.f_n * n).norm(), 0.0);
}

TEST(ContactLawsLinear, DisksTangentialDashpotIsCappedAtMuFnAndOnlyThere) {
    check_linear_dashpot_cap<2>();
}
TEST(ContactLawsLinear, SpheresTangentialDashpotIsCappedAtMuFnAndOnlyThere) {
    check_linear_dashpot_cap<3>();
}

TEST(ContactLawsKernels, TangentialSpringIsProjectedKeepingItsLength) {
    Vec<3> xi(0.3, -0.2, 0.5);
    const Vec<3> n = Vec<3>(1, 2, 2) / 3.0;
    const double length = xi.norm();
    advance_tangential_spring<3>(xi, n, Vec<3>::Zero());
    EXPECT_NEAR(xi.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(xi.norm(), length, 1e-15);
    advance_tangential_spring<3>(xi, n, Vec<3>(0.1, 0.1, 0.1));  // only the tangential part counts
    EXPECT_NEAR(xi.dot(n), 0.0, 1e-15);
}

template <int D>
void check_slip_rescales_spring() {
    // Slip: |F_t| = mu |F_n| and the spring is reset so that -k_t xi - gamma_t g_t = F_t.
    const Vec<D> n = unit<D>(D - 1);
    const Vec<D> g = 0.7 * unit<D>(0) - 0.2 * n;
    const CundallStrackContact p{1000, 5, 300, 4, 0.3};
    Vec<D> xi = 0.05 * unit<D>(0);
    const ContactForce<D> c = cundall_strack_force<D>(p, 0.01, n, g, 0.5, 0.5, xi);
    ASSERT_TRUE(c.slipping);
    const Vec<D> ft = c.force - c.f_n * n;
    EXPECT_NEAR(ft.norm(), 0.3 * std::fabs(c.f_n), 1e-12);
    EXPECT_LT((-300 * xi - 4 * (g - g.dot(n) * n) - ft).norm(), 1e-12);
    EXPECT_LT(ft.dot(unit<D>(0)), 0.0);  // opposes the sliding
    // Mindlin: the tangential stiffness is k_t delta^{1/2} (x4 overlap: x2 stiffness).
    const HertzMindlinContact hm{1000, 0, 300, 0, 1e9};
    Vec<D> x1 = 1e-3 * unit<D>(0), x2 = x1;
    const Vec<D> g0 = Vec<D>::Zero();
    const double f1 = hertz_mindlin_force<D>(hm, 0.01, n, g0, 0.5, 0.5, x1).force[0];
    const double f2 = hertz_mindlin_force<D>(hm, 0.04, n, g0, 0.5, 0.5, x2).force[0];
    EXPECT_NEAR(f1, -300 * std::sqrt(0.01) * 1e-3, 1e-15);
    EXPECT_NEAR(f2 / f1, 2.0, 1e-12);
    EXPECT_NEAR(hertz_mindlin_force<D>(hm, 0.04, n, g0, 0.5, 0.5, x2).f_n, 1000 * 0.008, 1e-12);
}

TEST(ContactLawsKernels, DisksCoulombCapRescalesTheStoredSpring) {
    check_slip_rescales_spring<2>();
}
TEST(ContactLawsKernels, SpheresCoulombCapRescalesTheStoredSpring) {
    check_slip_rescales_spring<3>();
}

// ----- head-on collisions, linear law -----------------------------------------------------------

struct HeadOnErrors {
    double worst_e = 0;   // max over entry phases of |e_measured / e - 1|
    double mean_e = 0;    // phase average of e_measured / e - 1
    double worst_tc = 0;  // max over entry phases of |t_c,measured / t_c - 1|
};

// Head-on collisions with the linear law at dt = t_c / steps_per_tc, the contact starting at 16
// phases of the time step. Unequal masses (1 and 3): Eq. (A9) needs the reduced mass.
template <int D>
HeadOnErrors linear_head_on(bool wall, double e, double steps_per_tc, bool predictor = true) {
    const double ma = 1.0, mb = 3.0;
    const double m_eff = wall ? ma : reduced_mass(ma, mb);
    const double tc = 1e-3, v = 1.3;
    const double k = linear_stiffness_from_duration(tc, m_eff, e);
    const LinearDashpotContact p = linear_dashpot_contact(k, m_eff, e, 0.0, 0.0);
    EXPECT_NEAR(linear_contact_duration(k, m_eff, p.gamma_n), tc, 1e-15);
    HeadOnErrors err;
    const int phases = 16;
    for (int i = 0; i < phases; ++i) {
        Setup<D> s = head_on<D>(wall, ma, mb, v, tc / steps_per_tc, (i + 0.5) / phases);
        s.predictor = predictor;
        const Outcome<D> o = collide<D>(s, linear_law<D>(p));
        EXPECT_EQ(o.contacts, 1);
        const double de = normal_relative_velocity<D>(o, wall) / v / e - 1;
        err.worst_e = std::max(err.worst_e, std::fabs(de));
        err.mean_e += de / phases;
        err.worst_tc = std::max(err.worst_tc, std::fabs((o.t_out - o.t_in) / tc - 1));
        if (!wall) {
            EXPECT_LT((ma * o.a.v + mb * o.b.v).norm(), 1e-12);  // momentum
        }
    }
    return err;
}

// With the paper's e = 0.9 (and e = 0.95) every collision is within 0.5 % of the requested e and
// 1 % of t_c at dt = t_c / 50, for pairs (reduced mass) and walls (mass m), disks and spheres. With
// t_c / dt an integer the errors at the start and at the end of the contact nearly cancel (the
// steps are in the same phase), so a generic ratio, 50.37, is tested too.
TEST(ContactLawsLinear, RestitutionAndDurationWithinHalfAPercentAtTcOver50) {
    for (bool wall : {false, true}) {
        for (double e : {0.95, 0.9}) {
            for (double steps : {50.0, 50.37}) {
                for (const HeadOnErrors& err :
                     {linear_head_on<2>(wall, e, steps), linear_head_on<3>(wall, e, steps)}) {
                    EXPECT_LT(err.worst_e, 0.005) << "wall " << wall << " e " << e;
                    EXPECT_LT(err.worst_tc, 0.01) << "wall " << wall << " e " << e;
                }
            }
        }
    }
}

// The damping force jumps at the start (gamma v) and at the end (-gamma e v) of the contact, and
// the integrator samples it at step times: one collision's e is off by up to about
// 2 |ln e| dt / t_c (first order, the sign set by where the contact starts within a step), while
// the average over entry phases is second order. Stronger damping needs smaller steps for the
// 0.5 % of every single collision: e = 0.8 at t_c/100, e = 0.5 at t_c/300, e = 0.3 at t_c/500.
TEST(ContactLawsLinear, SingleCollisionErrorIsFirstOrderAndPhaseAverageSecondOrder) {
    for (bool wall : {false, true}) {
        for (double e : {0.8, 0.5, 0.3}) {
            const HeadOnErrors coarse = linear_head_on<3>(wall, e, 50.37);
            const HeadOnErrors fine = linear_head_on<3>(wall, e, 100.37);
            const double bound = 2.5 * std::fabs(std::log(e)) / 50.37;
            EXPECT_LT(coarse.worst_e, bound) << "wall " << wall << " e " << e;
            EXPECT_GT(coarse.worst_e, 0.25 * bound) << "wall " << wall << " e " << e;
            EXPECT_LT(std::fabs(coarse.mean_e), 0.005) << "wall " << wall << " e " << e;
            EXPECT_LT(coarse.worst_tc, 0.01) << "wall " << wall << " e " << e;
            EXPECT_LT(fine.worst_e, 0.6 * coarse.worst_e) << "wall " << wall << " e " << e;
            EXPECT_LT(std::fabs(fine.mean_e), 0.35 * std::fabs(coarse.mean_e))
                << "wall " << wall << " e " << e;
        }
    }
    EXPECT_LT(linear_head_on<3>(false, 0.8, 100.37).worst_e, 0.005);
    EXPECT_LT(linear_head_on<3>(false, 0.5, 300.37).worst_e, 0.005);
    EXPECT_LT(linear_head_on<3>(true, 0.3, 500.37).worst_e, 0.005);
}

// For the integrator of the DEM engine: evaluating the damping at the half-step velocity instead of
// the predicted end-of-step velocity biases the phase-averaged restitution and the duration at
// first order (e = 0.5, t_c/50: -0.5 % and -0.7 %; with the predictor -0.16 % and +0.006 %).
TEST(ContactLawsLinear, HalfStepVelocitiesBiasRestitutionAndDurationAtFirstOrder) {
    const HeadOnErrors half50 = linear_head_on<3>(false, 0.5, 50.37, false);
    const HeadOnErrors half100 = linear_head_on<3>(false, 0.5, 100.37, false);
    const HeadOnErrors pred50 = linear_head_on<3>(false, 0.5, 50.37, true);
    EXPECT_GT(std::fabs(half50.mean_e), 2 * std::fabs(pred50.mean_e));
    EXPECT_GT(half50.worst_tc, 10 * pred50.worst_tc);
    EXPECT_NEAR(half100.worst_tc / half50.worst_tc, 0.5, 0.05);  // first order
    EXPECT_LT(half50.mean_e, -0.003);
    EXPECT_LT(half100.mean_e, -0.0015);
}

// ----- elastic limit -------------------------------------------------------------------------

// Relative energy change of oblique elastic collisions over 32 entry phases: worst and average.
template <int D, class Law>
std::pair<double, double> elastic_energy_error(bool wall, double dt, const Law& law) {
    double worst = 0, mean = 0;
    const int phases = 32;
    for (int i = 0; i < phases; ++i) {
        Setup<D> s = head_on<D>(wall, 1.0, 3.0, 1.3, dt, (i + 0.5) / phases);
        s.a.v += 0.4 * unit<D>(0);
        if constexpr (D == 2) {
            s.a.w = 3.0;
        } else {
            s.a.w = Eigen::Vector3d(1.0, -2.0, 3.0);
        }
        const double before = s.a.energy() + (wall ? 0.0 : s.b.energy());
        const Outcome<D> o = collide<D>(s, law);
        EXPECT_EQ(o.contacts, 1);
        const double de = (o.a.energy() + (wall ? 0.0 : o.b.energy())) / before - 1;
        worst = std::max(worst, std::fabs(de));
        mean += de / phases;
    }
    return {worst, mean};
}

// gamma = 0, mu = 0. Velocity Verlet conserves a shadow energy inside the contact, which differs
// from the energy by a term of order (omega dt)^2 in the elastic energy; at the step where the
// contact ends that term is left over, so one collision changes the energy by up to
// (pi dt / (2 t_c))^2 = 9.9e-4 at dt = t_c/50 for the linear spring (second order; zero on
// average over where the contact starts within a step, the average is below 1e-6). The Hertz
// force vanishes smoothly (delta^{3/2}), the error is smaller and of order dt^{5/2}.
template <int D>
void check_elastic_energy() {
    for (bool wall : {false, true}) {
        const double m_eff = wall ? 1.0 : reduced_mass(1.0, 3.0);
        const double tc = 1e-3;
        const LinearDashpotContact lin{linear_stiffness_from_duration(tc, m_eff, 1.0), 0, 0, 0};
        // dt = t_c/50 exactly: the entry and exit errors nearly cancel; generic ratios do not.
        double previous = 0;
        for (double steps : {50.0, 50.37, 100.37, 200.37}) {
            const auto [worst, mean] =
                elastic_energy_error<D>(wall, tc / steps, linear_law<D>(lin));
            const double bound = std::pow(kPi / (2 * steps), 2);
            EXPECT_LT(worst, bound) << "wall " << wall << " t_c/dt " << steps;
            EXPECT_LT(std::fabs(mean), 1e-6) << "wall " << wall << " t_c/dt " << steps;
            if (steps == 50.0) {
                EXPECT_LT(worst, 3e-5);
            } else if (previous > 0) {
                EXPECT_LT(worst, 0.3 * previous);  // second order
            }
            if (steps != 50.0) previous = worst;
        }
        // Hertz with k_n such that t_c = 1e-3 at the impact speed 1.3.
        const double tau0 = hertz_tsuji_collision(0).duration;
        const HertzMindlinContact hertz{std::pow(tau0 / tc, 2.5) * m_eff / std::sqrt(1.3), 0, 0, 0,
                                        0};
        EXPECT_NEAR(hertz_elastic_duration(hertz.k_n, m_eff, 1.3), tc, 1e-12);
        const auto [worst50, mean50] =
            elastic_energy_error<D>(wall, tc / 50, hertz_mindlin_law<D>(hertz));
        const auto [worst200, mean200] =
            elastic_energy_error<D>(wall, tc / 200, hertz_mindlin_law<D>(hertz));
        EXPECT_LT(worst50, 1e-4);
        EXPECT_LT(worst200, 3e-6);
        EXPECT_LT(std::fabs(mean50), 1e-6);
        EXPECT_LT(std::fabs(mean200), 1e-8);
    }
}

TEST(ContactLawsElastic, DisksConserveEnergyToSecondOrder) {
    check_elastic_energy<2>();
}
TEST(ContactLawsElastic, SpheresConserveEnergyToSecondOrder) {
    check_elastic_energy<3>();
}

// ----- two contacts per instruction (the DEM pair loop's path for this law) ---------------------

// Every field of each lane's ContactForce has the bits of linear_dashpot_force for that contact,
// for pairs of sticking contacts, slipping ones and one of each (the slip branch runs for both
// lanes as soon as one slips, and each lane keeps its own outcome).
TEST(ContactLawsLinear, TwoContactsAtOnceGiveTheBitsOfOneAtATime) {
    using namespace two_contacts;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-2.0, 2.0), positive(0.05, 1.0);
    auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
    auto same = [&](const ContactForce<3>& lane, const ContactForce<3>& one) {
        for (int a = 0; a < 3; ++a) {
            if (bits(lane.force[a]) != bits(one.force[a]) ||
                bits(lane.torque_i[a]) != bits(one.torque_i[a]) ||
                bits(lane.torque_j[a]) != bits(one.torque_j[a]))
                return false;
        }
        return bits(lane.f_n) == bits(one.f_n) && lane.slipping == one.slipping;
    };
    int outcomes[2][2] = {};  // [first slips][second slips]
    for (int trial = 0; trial < 4000; ++trial) {
        LinearDashpotContact p[2];
        double delta[2], l_i[2], l_j[2];
        Vec<3> n[2], g[2];
        for (int c = 0; c < 2; ++c) {
            // mu from 0.01 (almost every contact slips) to 10 (almost none does).
            p[c] =
                linear_dashpot_contact(2e5, 0.5, 0.9, std::pow(10.0, u(rng)), 20.0 * positive(rng));
            delta[c] = 1e-3 * positive(rng);
            n[c] = Vec<3>(u(rng), u(rng), u(rng)).normalized();
            g[c] = Vec<3>(u(rng), u(rng), u(rng));
            l_i[c] = 0.5 * positive(rng) + 0.25;
            l_j[c] = 0.5 * positive(rng) + 0.25;
        }
        ContactForce<3> a, b;
        linear_dashpot_force_two(p[0], p[1], lanes(delta[0], delta[1]), lanes<3>(n[0], n[1]),
                                 lanes<3>(g[0], g[1]), lanes(l_i[0], l_i[1]), lanes(l_j[0], l_j[1]),
                                 a, b);
        const ContactForce<3> one_a =
            linear_dashpot_force<3>(p[0], delta[0], n[0], g[0], l_i[0], l_j[0]);
        const ContactForce<3> one_b =
            linear_dashpot_force<3>(p[1], delta[1], n[1], g[1], l_i[1], l_j[1]);
        ASSERT_TRUE(same(a, one_a)) << "trial " << trial << ", first lane";
        ASSERT_TRUE(same(b, one_b)) << "trial " << trial << ", second lane";
        ++outcomes[one_a.slipping][one_b.slipping];
    }
    // Every combination was met often enough for the test to mean something.
    for (int x = 0; x < 2; ++x) {
        for (int y = 0; y < 2; ++y) EXPECT_GT(outcomes[x][y], 200) << x << ", " << y;
    }
}

}  // namespace
}  // namespace gran
