#pragma once
// Binary collision rules of inelastic hard disks/spheres as plain functions on plain data: the
// event-driven engine applies them with the normal and tangential restitution a law gives.
// n is the unit vector from particle 2 to particle 1 at contact; approaching means (v1 - v2).n < 0.
#include "libgran/core/vec.hpp"  // cross_w, cross_n

namespace gran {

// Smooth particles, Barrat & Trizac 2002 Eqs. (1)-(2): the normal relative velocity is reversed and
// scaled by alpha; tangential components are untouched. Returns the normal impulse on particle 1
// (P.n of Eq. (3), positive when it pushes 1 away from 2), used by virial pressure estimates.
template <int D>
inline double smooth_collision(Vec<D>& v1, Vec<D>& v2, double m1, double m2, const Vec<D>& n,
                               double alpha) {
    const double gn = (v1 - v2).dot(n);
    const double impulse = -(1.0 + alpha) * gn * (m1 * m2 / (m1 + m2));
    v1 += (impulse / m1) * n;
    v2 -= (impulse / m2) * n;
    return impulse;
}

// Rough particles with normal restitution alpha and tangential restitution beta, Barrat & Trizac
// 2002 Appendix A (Eqs. A2-A12), written for unequal inertia factors q_i (I_i = q_i m_i s_i^2 / 4;
// q = 1/2 for uniform disks, 2/5 for uniform spheres). With g the relative velocity of the contact
// points (A2), g_n' = -alpha g_n (A8) and g_t' = -beta g_t (A9); beta = -1 is the smooth limit.
// Returns the normal impulse on particle 1 as smooth_collision does.
template <int D>
inline double rough_collision(Vec<D>& v1, Vec<D>& v2, AngVec<D>& w1, AngVec<D>& w2, double m1,
                              double m2, double s1, double s2, double q1, double q2,
                              const Vec<D>& n, double alpha, double beta) {
    const AngVec<D> wsum = 0.5 * s1 * w1 + 0.5 * s2 * w2;
    const Vec<D> g = v1 - v2 - cross_w<D>(wsum, n);
    const double gn = g.dot(n);
    const Vec<D> gt = g - gn * n;
    const double inv_mu = 1.0 / m1 + 1.0 / m2;
    // Eq. (A12) generalised: the tangential effective mass includes both moments of inertia.
    const double inv_mu_t = inv_mu + 1.0 / (q1 * m1) + 1.0 / (q2 * m2);
    const double impulse_n = -(1.0 + alpha) * gn / inv_mu;
    const Vec<D> p_t = -((1.0 + beta) / inv_mu_t) * gt;
    const Vec<D> p = impulse_n * n + p_t;
    v1 += p / m1;
    v2 -= p / m2;
    // Eq. (A4)/(A7): I_i dw_i = -(s_i/2) n x P for both particles (P is the impulse on particle 1).
    // Only the tangential part has a torque (n x n = 0): taking it alone keeps a smooth collision
    // (beta = -1, p_t = 0) from changing w by the round-off of n x (impulse_n n).
    const AngVec<D> torque = cross_n<D>(n, p_t);
    w1 -= (2.0 / (q1 * m1 * s1)) * torque;
    w2 -= (2.0 / (q2 * m2 * s2)) * torque;
    return impulse_n;
}

// A wall of infinite mass moving with velocity u along its normal (u = 0: a static wall; a
// sawtooth wall reports u = inward v0, Barrat & Trizac 2002, Sec. III A; a piston its waveform's
// velocity, McNamara & Falcon 2005, Sec. II B): the relative normal velocity is reversed and
// scaled, v_n' - u = -e (v_n - u). Returns v_n'; exactly 2 u - v_n for e = 1 (the sawtooth rule).
inline double wall_collision(double v_n, double u, double e) {
    return (1.0 + e) * u - e * v_n;
}

// Closed-form kinetic energy change of a collision (translational + rotational), for tests and
// bookkeeping: dE = -(mu/2)(1 - alpha^2) g_n^2 - (mu_t/2)(1 - beta^2) |g_t|^2.
inline double collision_energy_change(double mu, double mu_t, double gn2, double gt2, double alpha,
                                      double beta) {
    return -0.5 * mu * (1.0 - alpha * alpha) * gn2 - 0.5 * mu_t * (1.0 - beta * beta) * gt2;
}

}  // namespace gran
