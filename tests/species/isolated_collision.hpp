#pragma once
// Isolated soft-sphere collisions for the tests of species/contact_laws.hpp: two bodies (or a body
// and a static wall) integrated with a small velocity-Verlet integrator, the kernels wrapped as
// laws, and head-on set-ups (tests/species/test_contact_laws*.cpp).
#include <cmath>
#include <limits>
#include <numbers>

#include "species/contact_laws.hpp"

namespace gran::contact_test {

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

}  // namespace gran::contact_test
