#pragma once
// Soft-sphere contact laws for the DEM engine (issue #5) as plain functions on plain data: given
// one contact's overlap, normal and contact-point relative velocity (and, for history-dependent
// laws, the stored tangential spring), return the force on particle i and the torques on i and j.
//
// Laws:
//   linear_dashpot  Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016), Appendix, Eqs.
//                   (A3)-(A9): linear spring-dashpot normal force, tangential dashpot capped by
//                   Coulomb friction, no tangential spring (k_t = 0, "as mentioned earlier").
//   cundall_strack  the same normal force plus a tangential spring with history (Cundall & Strack,
//                   Geotechnique 29, 47 (1979)), the spring rescaled to the Coulomb cap on slip.
//   hertz_mindlin   Hertz normal force k_n delta^{3/2} with the damping of Tsuji, Tanaka & Ishida,
//                   Powder Technol. 71, 239 (1992) (the paper's Ref. 31), which gives a restitution
//                   independent of the impact speed, and a Mindlin tangential spring of stiffness
//                   proportional to delta^{1/2}, with history and the Coulomb cap.
//
// Conventions (as in collision_rules.hpp; the paper's n_ij points the other way, see below):
//   n      unit normal from j to i at the contact, n = (r_i - r_j) / |r_i - r_j|; for a wall, the
//          wall normal pointing into the gas (j is the wall).
//   delta  overlap R_i + R_j - |r_i - r_j| > 0 (Eq. A6); for a wall R_i - distance to the plane.
//   l_i    lever arms: distances from the centres to the contact point. The paper uses l = R
//   l_j    (Eq. A3). Angular momentum of a pair is conserved exactly only if l_i + l_j =
//          |r_i - r_j|, e.g. l = R - delta/2; with l = R it changes by -delta n x F per unit time
//          (a relative error of order delta/R). A wall has l_j = 0 (it does not rotate).
//   g      relative velocity of the contact points, g = v_i - v_j - (l_i w_i + l_j w_j) x n
//          (contact_velocity()). This is Eq. (A3) rewritten for our n = -n_ij: the paper's
//          v_i - v_j + (w_i R_i + w_j R_j) x n_ij. Approaching means g_n = g.n < 0; the overlap
//          grows at the rate d(delta)/dt = -g_n.
//   result force F on i (normal + tangential); j receives -F. torque_i = -l_i n x F and
//          torque_j = -l_j n x F (the contact point is at -l_i n from i and +l_j n from j); in 2D
//          the torques are z components (AngVec<2> = double). f_n = F.n is the signed normal
//          force, positive when it pushes the particles apart.
//   The power of the contact force on the pair is F.g, so with the same lever arms in g and in the
//   torques an undamped, frictionless contact conserves energy.
//
// Masses: the damping that yields a requested restitution depends on the reduced mass
// m_eff = m_i m_j / (m_i + m_j) (Eq. A9), or m_eff = m for a wall of infinite mass; it enters
// through the parameter constructors below (one parameter struct per species pair, one per
// species-wall pair), so the kernels need no mass. The tangential (contact-point) effective mass
// of a pair with lever arms equal to the radii and I = q m R^2 is
// m_t = 1 / (1/m_i + 1/m_j + 1/(q_i m_i) + 1/(q_j m_j)) (tangential_mass()).
//
// Normal force in tension: Eq. (A5) is used as written, so the force turns attractive near the end
// of a damped contact (kdelta + gamma d(delta)/dt < 0 while delta > 0) and the contact ends when
// delta returns to 0. Only then is Eq. (A9) exact (see linear_damping_from_restitution()); clipping
// F_n at 0 would end the contact earlier and give a larger restitution than requested. The Coulomb
// cap uses |f_n| (Eq. A8), also in that tensile phase.
//
// History (cundall_strack, hertz_mindlin): the caller keeps one tangential spring xi per contact,
// zero when the contact forms, discarded when it ends; advance_tangential_spring() rotates it
// into the current tangent plane and adds g_t dt, then the force kernel reads it and rescales it
// when the contact slips. On the step where the contact forms, only the part of the step spent in
// contact should count (dt delta / (delta - delta_previous)); a full dt starts the spring up to one
// step too long, enough to trip the Coulomb cap at the first step.
//
// Time integration (measured by tests/species/test_contact_laws*.cpp with velocity Verlet):
//   - Evaluate the velocity-dependent forces at the predicted end-of-step velocity
//     v + (dt/2) a_old, not at the half-step velocity, which biases e and t_c at first order in
//     dt (e = 0.5, dt = t_c/50: -0.5 % and -0.7 %).
//   - The linear damping force jumps at both ends of a contact (gamma v, then -gamma e v): one
//     collision's e is off by up to about 2 |ln e| dt / t_c depending on where the contact starts
//     within a step (zero on average). At dt = t_c/50 every collision is within 0.5 % of e for
//     e >= 0.9; e = 0.5 needs t_c/300 for that. Durations are within 5e-4 at t_c/50.
//   - The elastic limit conserves energy on average (< 1e-6 at t_c/50), but one linear-spring
//     collision changes it by up to (pi dt / (2 t_c))^2 (1e-3 at t_c/50), the offset between
//     Verlet's shadow energy and the energy left over at the step where the contact ends; Hertz
//     contacts, whose force vanishes smoothly, by 4e-5.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "libgran/core/vec.hpp"
#include "libgran/engines/dem/contact_force.hpp"
#include "libgran/engines/dem/two_contacts.hpp"

namespace gran {

// ---------------------------------------------------------------------------------------------
// (a) Linear spring-dashpot with a Coulomb-capped tangential dashpot: Bhateja, Sharma & Singh
// 2016, Appendix.
//
//   F_n = k_n delta - gamma_n g_n                             (A5, our n: -(c_n v^n + k_n delta
//   n_ij)) F_t = -min(gamma_t |g_t|, mu |F_n|) t,  t = g_t / |g_t|   (A7, A8; the "min" of two
//   vectors
//                                                              along t is the shorter one)
//   gamma_n = -2 ln(e) sqrt(k_n m_eff) / sqrt(pi^2 + ln^2 e)  (A9 with its sign corrected: as
//                                                              printed c_n < 0 for e < 1, which in
//                                                              A5 would be an anti-damper)
//
// Closed forms of the head-on contact (m_eff delta'' = -k_n delta - gamma_n delta', delta(0) = 0,
// delta'(0) = v): with w0^2 = k_n / m_eff, b = gamma_n / (2 m_eff), w = sqrt(w0^2 - b^2),
//   delta(t) = (v / w) exp(-b t) sin(w t),   t_c = pi / w,   e = exp(-b t_c) = exp(-pi b / w).
// Inverting e = exp(-pi b / w) gives Eq. (A9) exactly: the linear law reproduces the requested
// restitution for every impact speed, provided the contact ends when delta returns to 0 (the
// force is not clipped at 0). With a contact duration t_c requested too:
//   k_n = m_eff (pi^2 + ln^2 e) / t_c^2,   gamma_n = -2 m_eff ln(e) / t_c.
struct LinearDashpotContact {
    double k_n = 0;      // normal stiffness [force/length]
    double gamma_n = 0;  // normal damping c_n >= 0 [mass/time]
    double gamma_t = 0;  // tangential damping c_t >= 0 [mass/time] (the paper does not give it)
    double mu = 0;       // Coulomb friction coefficient mu_p
};

// Eq. (A9) with the sign that makes gamma_n >= 0. e in (0, 1]; e -> 0 gives critical damping
// 2 sqrt(k_n m_eff), where the contact no longer ends.
inline double linear_damping_from_restitution(double k_n, double m_eff, double e) {
    if (e <= 0) return 2.0 * std::sqrt(k_n * m_eff);
    const double l = std::log(e);
    return -2.0 * l * std::sqrt(k_n * m_eff) /
           std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

// t_c = pi / sqrt(k/m - (gamma/2m)^2); infinity when critically damped or overdamped.
inline double linear_contact_duration(double k_n, double m_eff, double gamma_n) {
    const double b = gamma_n / (2.0 * m_eff);
    const double w2 = k_n / m_eff - b * b;
    return w2 > 0 ? std::numbers::pi / std::sqrt(w2) : kInf;
}

// e = exp(-pi b / w) (0 when critically damped or overdamped).
inline double linear_restitution(double k_n, double m_eff, double gamma_n) {
    const double b = gamma_n / (2.0 * m_eff);
    const double w2 = k_n / m_eff - b * b;
    return w2 > 0 ? std::exp(-std::numbers::pi * b / std::sqrt(w2)) : 0.0;
}

// k_n for a requested contact duration and restitution: k_n = m_eff (pi^2 + ln^2 e) / t_c^2. The
// matching damping is linear_damping_from_restitution(k_n, m_eff, e) = -2 m_eff ln(e) / t_c.
inline double linear_stiffness_from_duration(double t_c, double m_eff, double e) {
    const double l = std::log(e);
    return m_eff * (std::numbers::pi * std::numbers::pi + l * l) / (t_c * t_c);
}

// Largest overlap of a head-on contact at impact speed v: with r = b / w,
// delta_max = (v / w0) exp(-r (pi/2 - atan r)), reached at w t = pi/2 - atan r.
inline double linear_max_overlap(double k_n, double m_eff, double gamma_n, double v) {
    const double w0 = std::sqrt(k_n / m_eff);
    const double b = gamma_n / (2.0 * m_eff);
    const double r = b / std::sqrt(w0 * w0 - b * b);
    return std::fabs(v) / w0 * std::exp(-r * (0.5 * std::numbers::pi - std::atan(r)));
}

// integral of |F_n| dt over a head-on contact at normal impact speed v (the Coulomb budget of
// Eq. A8). F_n = -m_eff delta'' is repulsive until t* (delta'' = 0, w t* = pi - 2 atan r) and
// tensile after, so the integral is m_eff [(1 - e) v + 2 |delta'(t*)|] with
// |delta'(t*)| = e v exp(2 r atan r), r = b / w = -ln(e) / pi:
//   J_abs = m_eff |v| [1 - e + 2 e exp(2 r atan r)]   (>= m_eff (1 + e) |v|, equal for e = 1).
inline double linear_abs_normal_impulse(double m_eff, double v, double e) {
    const double r = -std::log(e) / std::numbers::pi;
    return m_eff * std::fabs(v) * (1.0 - e + 2.0 * e * std::exp(2.0 * r * std::atan(r)));
}

// Tangential dashpot without friction cap: m_t dg_t/dt = -gamma_t g_t during the whole contact,
// so g_t' = beta_t g_t with beta_t = exp(-gamma_t t_c / m_t) in (0, 1]: the contact-point sliding
// velocity decays but never reverses (unlike a tangential spring, Walton's beta_0 > 0 regime) and
// never reaches 0 (rolling without slip only as gamma_t -> infinity).
inline double dashpot_tangential_restitution(double gamma_t, double m_t, double t_c) {
    return std::exp(-gamma_t * t_c / m_t);
}

// gamma_t giving a requested decay beta_t in (0, 1]: gamma_t = -m_t ln(beta_t) / t_c.
inline double dashpot_tangential_damping(double beta_t, double m_t, double t_c) {
    return -m_t * std::log(beta_t) / t_c;
}

// Parameters from k_n, a requested restitution (Eq. A9 with m_eff = reduced_mass(m_i, m_j), or
// m_eff = m for a wall), mu and gamma_t.
inline LinearDashpotContact linear_dashpot_contact(double k_n, double m_eff, double e, double mu,
                                                   double gamma_t) {
    LinearDashpotContact p;
    p.k_n = k_n;
    p.gamma_n = linear_damping_from_restitution(k_n, m_eff, e);
    p.gamma_t = gamma_t;
    p.mu = mu;
    return p;
}

// Eqs. (A5), (A7), (A8). delta > 0, |n| = 1, g = contact_velocity(...).
template <int D>
[[gnu::always_inline]] inline ContactForce<D> linear_dashpot_force(const LinearDashpotContact& p,
                                                                   double delta, const Vec<D>& n,
                                                                   const Vec<D>& g, double l_i,
                                                                   double l_j) {
    const double g_n = g.dot(n);
    const double f_n = p.k_n * delta - p.gamma_n * g_n;  // (A5)
    const Vec<D> g_t = g - g_n * n;
    // (A7) unless it exceeds the cap (A8). Compared squared, so a sticking contact (the
    // common case in a bed at rest) needs neither the slip speed's square root nor a division.
    const double cap = p.mu * std::fabs(f_n);
    const double speed2 = g_t.squaredNorm();
    const bool slipping = (p.gamma_t * p.gamma_t) * speed2 > cap * cap;
    Vec<D> f_t = -p.gamma_t * g_t;                         // (A7)
    if (slipping) f_t = (-cap / std::sqrt(speed2)) * g_t;  // (A8): |F_t| = mu |F_n| along -g_t
    return contact_detail::assemble<D>(f_n, f_t, n, l_i, l_j, slipping);
}

// linear_dashpot_force for two contacts of spheres at once, lane by lane the same operations in
// the same order (two_contacts.hpp): the same bits. The slip branch is taken when either
// contact slips, and each lane keeps its own outcome.
[[gnu::always_inline]] inline void linear_dashpot_force_two(
    const LinearDashpotContact& pa, const LinearDashpotContact& pb, two_contacts::Lane delta,
    const two_contacts::Vec2<3>& n, const two_contacts::Vec2<3>& g, two_contacts::Lane l_i,
    two_contacts::Lane l_j, ContactForce<3>& a, ContactForce<3>& b) {
    using namespace two_contacts;
    const Lane k_n = lanes(pa.k_n, pb.k_n), gamma_n = lanes(pa.gamma_n, pb.gamma_n);
    const Lane gamma_t = lanes(pa.gamma_t, pb.gamma_t), mu = lanes(pa.mu, pb.mu);
    const Lane g_n = dot(g, n);
    const Lane f_n = sub(mul(k_n, delta), mul(gamma_n, g_n));  // (A5)
    const Vec2<3> g_t = sub(g, scale(g_n, n));
    const Lane cap = mul(mu, abs(f_n));
    const Lane speed2 = dot(g_t, g_t);
    const Lane slipping = _mm_cmpgt_pd(mul(mul(gamma_t, gamma_t), speed2), mul(cap, cap));
    Vec2<3> f_t = scale(neg(gamma_t), g_t);  // (A7)
    if (_mm_movemask_pd(slipping)) {         // (A8)
        const Vec2<3> capped = scale(_mm_div_pd(neg(cap), _mm_sqrt_pd(speed2)), g_t);
        for (int k = 0; k < 3; ++k) f_t.c[k] = select(slipping, capped.c[k], f_t.c[k]);
    }
    assemble(f_n, f_t, n, l_i, l_j, slipping, a, b);
}

// ---------------------------------------------------------------------------------------------
// (b) Cundall & Strack 1979: the normal force of (a) and a tangential spring with history,
//   F_t = -k_t xi - gamma_t g_t, capped at mu |F_n|; on slip xi is rescaled so that the spring
//   (plus dashpot) carries exactly the Coulomb force. With gamma_t = 0, mu large and
//   k_t / m_t = k_n / m_eff (k_t = 2/7 k_n for equal spheres) an undamped collision ends with
//   g_t' = -g_t: the tangential half-oscillation lasts exactly t_c, the perfectly rough limit
//   (beta = +1) of rough_collision().
struct CundallStrackContact {
    double k_n = 0;      // normal stiffness [force/length]
    double gamma_n = 0;  // normal damping [mass/time]
    double k_t = 0;      // tangential stiffness > 0 [force/length]
    double gamma_t = 0;  // tangential damping [mass/time]
    double mu = 0;       // Coulomb friction coefficient
};

inline CundallStrackContact cundall_strack_contact(double k_n, double m_eff, double e, double k_t,
                                                   double gamma_t, double mu) {
    CundallStrackContact p;
    p.k_n = k_n;
    p.gamma_n = linear_damping_from_restitution(k_n, m_eff, e);
    p.k_t = k_t;
    p.gamma_t = gamma_t;
    p.mu = mu;
    return p;
}

// xi: the contact's spring, already advanced to this step (advance_tangential_spring); rescaled
// on slip.
template <int D>
inline ContactForce<D> cundall_strack_force(const CundallStrackContact& p, double delta,
                                            const Vec<D>& n, const Vec<D>& g, double l_i,
                                            double l_j, Vec<D>& xi) {
    const double g_n = g.dot(n);
    const double f_n = p.k_n * delta - p.gamma_n * g_n;  // (A5)
    return contact_detail::spring_dashpot_coulomb<D>(f_n, p.k_t, p.gamma_t, p.mu, n, g - g_n * n,
                                                     xi, l_i, l_j);
}

// ---------------------------------------------------------------------------------------------
// (c) Hertz-Mindlin with Tsuji damping:
//   F_n = k_n delta^{3/2} - gamma_n delta^{1/4} g_n,   gamma_n = alpha(e) sqrt(m_eff k_n)
//                                                      (Tsuji et al. 1992, eta_n = alpha
//                                                      sqrt(m k_n) delta^{1/4})
//   F_t = -k_t delta^{1/2} xi - gamma_t delta^{1/4} g_t, capped at mu |F_n| as in (b)
//   (Mindlin's no-slip tangential stiffness 8 G* sqrt(R* delta) is proportional to delta^{1/2};
//   the force is the total-displacement form k_t(delta) xi of LAMMPS gran/hertz/history and
//   Silbert et al., Phys. Rev. E 64, 051302 (2001), not Mindlin's incremental dF_t = k_t dxi).
// For material parameters: k_n = (4/3) E* sqrt(R*), k_t = 8 G* sqrt(R*), with
// 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j, 1/G* = (2 - nu_i)/G_i + (2 - nu_j)/G_j,
// R* = R_i R_j / (R_i + R_j) (hertz_normal_stiffness, mindlin_tangential_stiffness).
//
// Velocity independence: with delta = d0 x, t = (d0 / v) tau, d0 = (m_eff v^2 / k_n)^{2/5} the
// head-on contact becomes x'' = -x^{3/2} - alpha x^{1/4} x', x(0) = 0, x'(0) = 1, free of v, so
// e depends on alpha only (Tsuji et al. give alpha(e) as a graph; hertz_tsuji_alpha() inverts
// the dimensionless problem numerically instead). The contact duration scales as v^{-1/5}:
// t_c = tau_c(alpha) (m_eff / k_n)^{2/5} v^{-1/5}, tau_c(0) = 3.2181... (hertz_elastic_duration).
struct HertzMindlinContact {
    double k_n = 0;      // F_n = k_n delta^{3/2} [force/length^{3/2}]
    double gamma_n = 0;  // normal damping coefficient: eta_n = gamma_n delta^{1/4}
    double k_t = 0;      // tangential stiffness coefficient: k_t(delta) = k_t delta^{1/2}
    double gamma_t = 0;  // tangential damping coefficient: eta_t = gamma_t delta^{1/4}
    double mu = 0;       // Coulomb friction coefficient
};

inline double hertz_normal_stiffness(double e_star, double r_star) {
    return 4.0 / 3.0 * e_star * std::sqrt(r_star);
}

inline double mindlin_tangential_stiffness(double g_star, double r_star) {
    return 8.0 * g_star * std::sqrt(r_star);
}

// Elastic Hertz contact duration at impact speed v: t_c = 2 (delta_max / v) int_0^1 dx /
// sqrt(1 - x^{5/2}) = 2 (2/5) B(2/5, 1/2) delta_max / v, delta_max = (5 m v^2 / (4 k_n))^{2/5}.
inline double hertz_elastic_duration(double k_n, double m_eff, double v) {
    const double beta_fn = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    const double delta_max = std::pow(1.25 * m_eff * v * v / k_n, 0.4);
    return 0.8 * beta_fn * delta_max / std::fabs(v);
}

// The dimensionless head-on Hertz-Tsuji contact x'' = -x^{3/2} - alpha x^{1/4} x', x(0) = 0,
// x'(0) = 1, integrated with RK4. The damping term is not smooth at x = 0 (x^{1/4}), which would
// cut a plain RK4 in tau down to order 5/4; near both ends (x < x_s = 0.01) the independent
// variable is therefore y = x^{1/4}, in which the problem is smooth:
//   du/dy = -4 y^9 / u - 4 alpha y^4,   dtau/dy = 4 y^3 / u   (u = x', never 0 there).
// Fourth order overall; the default resolution gives e and tau_c to about 1e-10, x_max and the
// impulse (sampled at the steps) to about 1e-7.
// e(alpha) falls from 1 to 0.1 at alpha = 1.32 and 0.01 at 1.85, and is below 1e-7 beyond 2.2,
// where the contact barely ends (tau_c > 100); NaN if it does not end within tau = 100.
struct HertzTsujiCollision {
    double restitution = 0;  // e = -x'(tau_c)
    double duration = 0;     // tau_c, in units (m_eff / k_n)^{2/5} v^{-1/5}
    double max_overlap = 0;  // x_max, in units d0 = (m_eff v^2 / k_n)^{2/5}
    double abs_impulse = 0;  // integral of |F_n| dt, in units m_eff v: 1 - e + 2 |min x'|
};

namespace hertz_tsuji_detail {

constexpr double kSwitch = 0.01;  // x_s
constexpr int kEndSteps = 200;    // RK4 steps in y over each end zone

// An end zone in y = x^{1/4}: RK4 for the state (u, tau) from y0 to y1, u_min the smallest u so
// far; false when u reaches 0 or is no longer finite.
inline bool end_zone(double alpha, double& u, double& tau, double& u_min, double y0, double y1) {
    const auto du = [alpha](double y, double uu) {
        const double y4 = y * y * y * y;
        return -4.0 * y4 * y4 * y / uu - 4.0 * alpha * y4;
    };
    const auto dt = [](double y, double uu) { return 4.0 * y * y * y / uu; };
    const double h = (y1 - y0) / kEndSteps;
    for (int k = 0; k < kEndSteps; ++k) {
        const double y = y0 + k * h;
        const double k1u = du(y, u), k1t = dt(y, u);
        const double k2u = du(y + 0.5 * h, u + 0.5 * h * k1u),
                     k2t = dt(y + 0.5 * h, u + 0.5 * h * k1u);
        const double k3u = du(y + 0.5 * h, u + 0.5 * h * k2u),
                     k3t = dt(y + 0.5 * h, u + 0.5 * h * k2u);
        const double k4u = du(y + h, u + h * k3u), k4t = dt(y + h, u + h * k3u);
        u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        tau += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
        u_min = std::min(u_min, u);
        if (!(std::fabs(u) > 0) || !std::isfinite(u)) return false;
    }
    return true;
}

// One RK4 step of length h in tau in the middle zone: state (x, u).
inline void middle_step(double alpha, double& x, double& u, double h) {
    const auto accel = [alpha](double xx, double uu) {
        const double s = std::sqrt(xx);
        return -xx * s - alpha * std::sqrt(s) * uu;
    };
    const double k1x = u, k1u = accel(x, u);
    const double k2x = u + 0.5 * h * k1u, k2u = accel(x + 0.5 * h * k1x, k2x);
    const double k3x = u + 0.5 * h * k2u, k3u = accel(x + 0.5 * h * k2x, k3x);
    const double k4x = u + h * k3u, k4u = accel(x + h * k3x, k4x);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
}

// The fraction s in [0, 1] of the step (x, u) -> (x1, u1) of length h where x is back at x_s:
// root of the cubic Hermite interpolant of x - x_s (bisection).
inline double return_fraction(double x, double u, double x1, double u1, double h) {
    const auto hermite = [&](double s) {
        const double s2 = s * s, s3 = s2 * s;
        return (2 * s3 - 3 * s2 + 1) * x + (s3 - 2 * s2 + s) * h * u + (-2 * s3 + 3 * s2) * x1 +
               (s3 - s2) * h * u1 - kSwitch;
    };
    double lo = 0, hi = 1;
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (hermite(mid) > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace hertz_tsuji_detail

inline HertzTsujiCollision hertz_tsuji_collision(double alpha, int steps_per_unit = 2000) {
    using namespace hertz_tsuji_detail;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    HertzTsujiCollision out;
    out.restitution = out.duration = out.max_overlap = out.abs_impulse = nan;
    double u_min = 1;
    const double y_s = std::sqrt(std::sqrt(kSwitch));
    double u = 1, tau = 0;
    if (!end_zone(alpha, u, tau, u_min, 0.0, y_s) || u <= 0) return out;
    double x = kSwitch, x_max = kSwitch;
    const double h = 1.0 / steps_per_unit;
    for (long step = 0; step < 100L * steps_per_unit; ++step) {
        double x1 = x, u1 = u;
        middle_step(alpha, x1, u1, h);
        if (x1 < kSwitch && u1 < 0) {
            // Back at x_s inside this step: one RK4 step to the crossing, then the exit zone in y.
            const double s = return_fraction(x, u, x1, u1, h);
            middle_step(alpha, x, u, s * h);
            tau += s * h;
            u_min = std::min(u_min, u);
            if (!end_zone(alpha, u, tau, u_min, std::sqrt(std::sqrt(x)), 0.0) || u >= 0) return out;
            out.restitution = -u;
            out.duration = tau;
            out.max_overlap = x_max;
            out.abs_impulse = 1.0 + u - 2.0 * u_min;  // u_min <= u
            return out;
        }
        if (x1 < 0.5 * kSwitch) return out;  // stalled near x_s
        x = x1;
        u = u1;
        tau += h;
        x_max = std::max(x_max, x);
        u_min = std::min(u_min, u);
    }
    return out;
}

// alpha(e) of the Tsuji damping: the root of hertz_tsuji_collision(alpha).restitution = e
// (bracketed in [0, 2], Illinois regula falsi), about 1e-10 accurate. e in [0.01, 1], else NaN.
inline double hertz_tsuji_alpha(double e) {
    if (!(e >= 0.01 && e <= 1)) return std::numeric_limits<double>::quiet_NaN();
    if (e == 1) return 0.0;
    const auto f = [e](double a) { return hertz_tsuji_collision(a).restitution - e; };
    double a_lo = 0, f_lo = 1 - e, a_hi = 2, f_hi = f(a_hi);  // e(2) = 0.0019
    int side = 0;
    for (int it = 0; it < 100 && a_hi - a_lo > 1e-12 * a_hi; ++it) {
        const double a = (a_lo * f_hi - a_hi * f_lo) / (f_hi - f_lo);
        const double fa = f(a);
        if (fa == 0) return a;
        if ((fa > 0) == (f_lo > 0)) {
            a_lo = a;
            f_lo = fa;
            if (side == -1) f_hi *= 0.5;
            side = -1;
        } else {
            a_hi = a;
            f_hi = fa;
            if (side == 1) f_lo *= 0.5;
            side = 1;
        }
        if (std::fabs(fa) < 1e-12) return a;
    }
    return 0.5 * (a_lo + a_hi);
}

// Parameters from the Hertz and Mindlin stiffness coefficients, a requested restitution (m_eff as
// for the linear law), mu and the tangential damping coefficient.
inline HertzMindlinContact hertz_mindlin_contact(double k_n, double m_eff, double e, double k_t,
                                                 double gamma_t, double mu) {
    HertzMindlinContact p;
    p.k_n = k_n;
    p.gamma_n = hertz_tsuji_alpha(e) * std::sqrt(m_eff * k_n);
    p.k_t = k_t;
    p.gamma_t = gamma_t;
    p.mu = mu;
    return p;
}

template <int D>
inline ContactForce<D> hertz_mindlin_force(const HertzMindlinContact& p, double delta,
                                           const Vec<D>& n, const Vec<D>& g, double l_i, double l_j,
                                           Vec<D>& xi) {
    const double root = std::sqrt(delta);
    const double quarter = std::sqrt(root);
    const double g_n = g.dot(n);
    const double f_n = p.k_n * delta * root - p.gamma_n * quarter * g_n;
    return contact_detail::spring_dashpot_coulomb<D>(f_n, p.k_t * root, p.gamma_t * quarter, p.mu,
                                                     n, g - g_n * n, xi, l_i, l_j);
}

}  // namespace gran
