// Soft-sphere contact laws (species/contact_laws.hpp): the linear spring-dashpot of Bhateja, Sharma
// & Singh 2016 (Appendix, Eqs. A3-A9), the Cundall-Strack tangential spring and Hertz-Mindlin with
// Tsuji damping. Isolated collisions are integrated with a small velocity-Verlet integrator at
// dt = t_c / 50 and compared with the closed forms: restitution, contact duration, the impulse of
// the Coulomb-capped tangential dashpot in its sliding and viscous regimes, energy conservation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "libgran/engines/event_driven/collision_rules.hpp"  // rough_collision
#include "species/contact_laws.hpp"

namespace gran {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <int D>
Vec<D> unit(int axis) {
    Vec<D> e = Vec<D>::Zero();
    e[axis] = 1;
    return e;
}

template <int D>
struct Body {
    Vec<D> x = Vec<D>::Zero();
    Vec<D> v = Vec<D>::Zero();
    AngVec<D> w = ang_zero<D>();
    double m = 1;
    double radius = 0.5;
    double q = 0.4;  // I = q m R^2
    double inertia() const { return q * m * radius * radius; }
    double energy() const {
        return 0.5 * m * v.squaredNorm() + 0.5 * inertia() * ang_squared<D>(w);
    }
};

// Particle a against particle b, or against the static plane {x . wall_normal = 0} when `wall`.
template <int D>
struct Setup {
    Body<D> a, b;
    bool wall = false;
    Vec<D> wall_normal = unit<D>(D - 1);  // into the gas
    double dt = 0;
    bool predictor = true;  // dissipative forces at the predicted end-of-step velocity
};

template <int D>
struct Outcome {
    Body<D> a, b;
    double t_in = kNaN, t_out = kNaN;  // contact start and end (delta = 0, linear interpolation)
    int contact_steps = 0;
    int slipping_steps = 0;
    int contacts = 0;  // separate contact episodes
};

// Velocity Verlet: half kick, drift, force at the new positions, half kick. The force depends on
// velocities too: with `predictor` the kernel sees v + (dt/2) a_old (Groot & Warren 1997 with
// lambda = 1/2), otherwise the half-step velocity; the tangential spring always integrates the
// half-step (position-moving) contact velocity, so that xi is the sliding displacement.
// law(delta, n, g, l_i, l_j, xi) -> ContactForce<D>. Lever arms are the radii (Eq. A3).
template <int D, class Law>
Outcome<D> collide(const Setup<D>& s, const Law& law) {
    Outcome<D> out;
    Body<D>& a = out.a;
    Body<D>& b = out.b;
    a = s.a;
    b = s.b;
    const double dt = s.dt;
    const double inv_mb = s.wall ? 0.0 : 1.0 / b.m;
    const double inv_ib = s.wall ? 0.0 : 1.0 / b.inertia();
    const double lb = s.wall ? 0.0 : b.radius;
    Vec<D> f = Vec<D>::Zero();  // on a
    AngVec<D> ta = ang_zero<D>(), tb = ang_zero<D>();
    Vec<D> xi = Vec<D>::Zero();
    const auto geometry = [&](double& delta, Vec<D>& n) {
        if (s.wall) {
            n = s.wall_normal;
            delta = a.radius - a.x.dot(n);
        } else {
            const Vec<D> r = a.x - b.x;
            const double dist = r.norm();
            n = r / dist;
            delta = a.radius + b.radius - dist;
        }
    };
    double delta_prev = 0;
    Vec<D> n;
    geometry(delta_prev, n);
    double t = 0;
    bool in_contact = delta_prev > 0;
    for (int step = 0; step < 1000000; ++step) {
        a.v += (0.5 * dt / a.m) * f;
        a.w += (0.5 * dt / a.inertia()) * ta;
        b.v -= (0.5 * dt * inv_mb) * f;
        b.w += (0.5 * dt * inv_ib) * tb;
        a.x += dt * a.v;
        b.x += dt * b.v;
        t += dt;
        double delta = 0;
        geometry(delta, n);
        if (delta > 0) {
            if (!in_contact) {
                out.t_in = t - dt * delta / (delta - delta_prev);
                ++out.contacts;
                xi.setZero();
            }
            in_contact = true;
            ++out.contact_steps;
            // On the step where the contact forms, only the part of the step in contact counts.
            const double in_contact_dt = out.contact_steps == 1 ? t - out.t_in : dt;
            const Vec<D> g_half = contact_velocity<D>(a.v, b.v, a.w, b.w, a.radius, lb, n);
            advance_tangential_spring<D>(xi, n, Vec<D>(in_contact_dt * g_half));
            Vec<D> va = a.v, vb = b.v;
            AngVec<D> wa = a.w, wb = b.w;
            if (s.predictor) {
                va += (0.5 * dt / a.m) * f;
                wa += (0.5 * dt / a.inertia()) * ta;
                vb -= (0.5 * dt * inv_mb) * f;
                wb += (0.5 * dt * inv_ib) * tb;
            }
            const Vec<D> g = contact_velocity<D>(va, vb, wa, wb, a.radius, lb, n);
            const ContactForce<D> c = law(delta, n, g, a.radius, lb, xi);
            f = c.force;
            ta = c.torque_i;
            tb = c.torque_j;
            if (c.slipping) ++out.slipping_steps;
        } else {
            if (in_contact) out.t_out = t - dt * delta / (delta - delta_prev);
            in_contact = false;
            f.setZero();
            ta = ang_zero<D>();
            tb = ang_zero<D>();
            if (out.contacts > 0 && t > out.t_out + 3 * dt) break;
        }
        a.v += (0.5 * dt / a.m) * f;
        a.w += (0.5 * dt / a.inertia()) * ta;
        b.v -= (0.5 * dt * inv_mb) * f;
        b.w += (0.5 * dt * inv_ib) * tb;
        delta_prev = delta;
    }
    return out;
}

template <int D>
auto linear_law(const LinearDashpotContact& p) {
    return [p](double delta, const Vec<D>& n, const Vec<D>& g, double li, double lj, Vec<D>&) {
        return linear_dashpot_force<D>(p, delta, n, g, li, lj);
    };
}

template <int D>
auto cundall_strack_law(const CundallStrackContact& p) {
    return [p](double delta, const Vec<D>& n, const Vec<D>& g, double li, double lj, Vec<D>& xi) {
        return cundall_strack_force<D>(p, delta, n, g, li, lj, xi);
    };
}

template <int D>
auto hertz_mindlin_law(const HertzMindlinContact& p) {
    return [p](double delta, const Vec<D>& n, const Vec<D>& g, double li, double lj, Vec<D>& xi) {
        return hertz_mindlin_force<D>(p, delta, n, g, li, lj, xi);
    };
}

// Head-on approach at normal speed v (relative), contact starting a fraction `phase` of a step
// after t = 0. Pair: a at +x_n, b at -x_n along the last axis, masses ma, mb. Wall: a above it.
template <int D>
Setup<D> head_on(bool wall, double ma, double mb, double v, double dt, double phase) {
    Setup<D> s;
    s.wall = wall;
    s.dt = dt;
    s.a.m = ma;
    s.b.m = mb;
    const Vec<D> n = unit<D>(D - 1);
    const double gap = v * phase * dt;
    if (wall) {
        s.a.x = (s.a.radius + gap) * n;
        s.a.v = -v * n;
    } else {
        // Centre-of-mass frame: a moves with -v mb/(ma+mb), b with +v ma/(ma+mb).
        s.a.x = (0.5 * gap + s.a.radius) * n;
        s.b.x = -(0.5 * gap + s.b.radius) * n;
        s.a.v = -(v * mb / (ma + mb)) * n;
        s.b.v = (v * ma / (ma + mb)) * n;
    }
    return s;
}

template <int D>
double normal_relative_velocity(const Outcome<D>& o, bool wall) {
    const Vec<D> n = unit<D>(D - 1);
    return wall ? o.a.v.dot(n) : (o.a.v - o.b.v).dot(n);
}

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
