#pragma once
// What every soft contact of the DEM engine shares, whatever its law: the force and torques a
// law's kernel returns (ContactForce), the relative velocity of the contact points it reads
// (contact_velocity), the assembly of normal and tangential forces with their torques, the
// Coulomb-capped tangential spring-dashpot, and the history of a tangential spring. Conventions
// (n from j to i, overlap delta, lever arms l_i, l_j, g = v_i - v_j - (l_i w_i + l_j w_j) x n) are
// those of species/contact_laws.hpp (Bhateja, Sharma & Singh 2016, Appendix, Eq. A3).
#include <cmath>

#include "libgran/core/vec.hpp"

namespace gran {

// ---------------------------------------------------------------------------------------------
// Common pieces.

template <int D>
struct ContactForce {
    Vec<D> force;           // on i; j receives -force
    AngVec<D> torque_i;     // -l_i n x force
    AngVec<D> torque_j;     // -l_j n x force
    double f_n = 0;         // force.n, positive = repulsive
    bool slipping = false;  // the Coulomb cap was active
};

// m_i m_j / (m_i + m_j); m_j = infinity (a wall) gives m_i.
inline double reduced_mass(double m_i, double m_j) {
    return 1.0 / (1.0 / m_i + 1.0 / m_j);
}

// Effective mass of the contact-point tangential motion, I = q m R^2 with lever arms R:
// dg_t = (1/m_i + 1/m_j + 1/(q_i m_i) + 1/(q_j m_j)) dP_t for a tangential impulse dP_t (the
// generalised Eq. (A12) of Barrat & Trizac 2002, as in rough_collision()). A wall: m_j = infinity.
// q = 1/2 for uniform disks, 2/5 for uniform spheres; for equal spheres m_t = (2/7) m_eff.
inline double tangential_mass(double m_i, double q_i, double m_j, double q_j) {
    return 1.0 / (1.0 / m_i + 1.0 / m_j + 1.0 / (q_i * m_i) + 1.0 / (q_j * m_j));
}

// Relative velocity of the contact points, Eq. (A3) for n from j to i (see the header comment).
template <int D>
inline Vec<D> contact_velocity(const Vec<D>& v_i, const Vec<D>& v_j, const AngVec<D>& w_i,
                               const AngVec<D>& w_j, double l_i, double l_j, const Vec<D>& n) {
    const AngVec<D> w = l_i * w_i + l_j * w_j;
    return v_i - v_j - cross_w<D>(w, n);
}

namespace contact_detail {

template <int D>
inline ContactForce<D> assemble(double f_n, const Vec<D>& f_t, const Vec<D>& n, double l_i,
                                double l_j, bool slipping) {
    ContactForce<D> c;
    c.force = f_n * n + f_t;
    const AngVec<D> nxf = cross_n<D>(n, f_t);  // n x (f_n n) = 0
    c.torque_i = -l_i * nxf;
    c.torque_j = -l_j * nxf;
    c.f_n = f_n;
    c.slipping = slipping;
    return c;
}

// Tangential spring + dashpot with the Coulomb cap and the rescaling of the stored spring on slip:
// trial F_t = -k_t xi - gamma_t g_t; if |F_t| > mu |f_n| then F_t is scaled to length mu |f_n| and
// the spring is reset so that -k_t xi - gamma_t g_t = F_t (Luding, Granular Matter 10, 235 (2008);
// LAMMPS pair gran/hooke/history), i.e. the spring stores exactly what the cap allows.
template <int D>
inline ContactForce<D> spring_dashpot_coulomb(double f_n, double k_t, double gamma_t, double mu,
                                              const Vec<D>& n, const Vec<D>& g_t, Vec<D>& xi,
                                              double l_i, double l_j) {
    Vec<D> f_t = -k_t * xi - gamma_t * g_t;
    const double cap = mu * std::fabs(f_n);
    // Compared squared: a sticking contact needs no square root.
    const double norm2 = f_t.squaredNorm();
    const bool slipping = norm2 > cap * cap;
    if (slipping) {
        f_t *= cap / std::sqrt(norm2);
        if (k_t > 0) {
            xi = -(f_t + gamma_t * g_t) / k_t;
        } else {
            xi.setZero();
        }
    }
    return assemble<D>(f_n, f_t, n, l_i, l_j, slipping);
}

}  // namespace contact_detail

// ---------------------------------------------------------------------------------------------
// Tangential spring history (cundall_strack, hertz_mindlin). Projects xi onto the plane normal to
// the current n keeping its length (the contact frame turns with the pair), then adds the
// tangential part of dxi (normally g dt, with g at the velocities that move the positions over the
// step, e.g. the half-step velocities of velocity Verlet, so that xi is the integrated sliding
// displacement).
template <int D>
inline void advance_tangential_spring(Vec<D>& xi, const Vec<D>& n, const Vec<D>& dxi) {
    const double length = xi.norm();
    xi -= xi.dot(n) * n;
    const double projected = xi.norm();
    if (projected > 0) xi *= length / projected;
    xi += dxi - dxi.dot(n) * n;
}

}  // namespace gran
