#include "libgran/engines/dem/engine.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gran {

namespace {

[[noreturn]] void fail(const std::string& why) {
    throw std::invalid_argument("DemEngine: " + why);
}

std::string num(double x) {
    std::ostringstream s;
    s.precision(6);
    s << x;
    return s.str();
}

}  // namespace

template <int D>
DemEngine<D>::DemEngine(const Box<D>& box, const SpeciesTable& species,
                        const DemContactTable& contacts, Particles<D> particles,
                        DemSettings settings)
    : box_(box), table_(contacts), p_(std::move(particles)), settings_(settings) {
    const std::size_t ns = species.size();
    if (ns == 0 || table_.species_count() != ns) {
        fail("the contact table has " + std::to_string(table_.species_count()) +
             " species, the species table " + std::to_string(ns));
    }
    double dmax = 0;
    for (const Species& s : species.species) {
        if (!(s.mass > 0) || !(s.diameter > 0) || !(s.inertia_factor > 0)) {
            fail("species '" + s.name + "' needs mass, diameter and inertia factor > 0");
        }
        mass_.push_back(s.mass);
        radius_.push_back(0.5 * s.diameter);
        inertia_.push_back(s.inertia_factor * s.mass * s.diameter * s.diameter / 4);  // q m s^2/4
        inv_mass_.push_back(1.0 / mass_.back());
        inv_inertia_.push_back(1.0 / inertia_.back());
        dmax = std::max(dmax, s.diameter);
    }
    const std::size_t n = p_.size();
    if (p_.v.size() != n || p_.species.size() != n) fail("particle arrays of unequal sizes");
    for (std::uint32_t s : p_.species) {
        if (s >= ns) fail("a particle has species index " + std::to_string(s));
    }
    for (int a = 0; a < 3; ++a) {
        const double ga = settings_.gravity[std::size_t(a)];
        if (a < D) {
            g_[a] = ga;
        } else if (ga != 0.0) {
            fail("gravity has a component beyond the " + std::to_string(D) + " dimensions");
        }
    }

    // Time step: Verlet resolves a contact with at least a few steps; t_c / 5 is the limit.
    bool bounded = false;
    for (int a = 0; a < D; ++a) bounded = bounded || !box_.periodic[std::size_t(a)];
    const double tc = table_.shortest_duration(bounded);
    dt_ = settings_.dt > 0 ? settings_.dt : settings_.dt_fraction * tc;
    if (!(dt_ > 0) || !std::isfinite(dt_)) fail("the time step must be finite and > 0");
    if (dt_ > tc / 5) {
        fail("dt = " + num(dt_) + " exceeds t_c / 5 = " + num(tc / 5) + " (t_c = " + num(tc) +
             " is the shortest contact duration): velocity Verlet needs at least 5 steps per "
             "contact for a stable, accurate collision (restitution and duration); use dt <= "
             "t_c / 50 (the default when dt = 0)");
    }

    // Neighbour list: cutoff sigma_ij + skin, below half of every periodic length.
    if (!(settings_.skin >= 0)) fail("the skin must be >= 0");
    skin_ = settings_.skin * dmax;
    std::vector<double> cutoff(ns * ns);
    double widest = 0;
    for (std::size_t a = 0; a < ns; ++a) {
        for (std::size_t b = 0; b < ns; ++b) {
            cutoff[a * ns + b] = radius_[a] + radius_[b] + skin_;
            widest = std::max(widest, cutoff[a * ns + b]);
        }
    }
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[std::size_t(a)] && !(widest < 0.5 * box_.length[a])) {
            fail("the neighbour cutoff sigma + skin = " + num(widest) +
                 " must stay below half the periodic length " + num(box_.length[a]) +
                 " along axis " + std::to_string(a) + " (minimum image)");
        }
    }

    // Rotation: needed as soon as some contact has friction.
    if (table_.needs_rotation() && !p_.rotating()) p_.w.assign(n, ang_zero<D>());
    if (p_.rotating() && p_.w.size() != n) fail("angular velocities of the wrong size");

    t_start_ = 0;
    for (double t : p_.t) t_start_ = std::max(t_start_, t);
    p_.t.assign(n, t_start_);
    f_.assign(n, Vec<D>::Zero());
    v_pred_.assign(n, Vec<D>::Zero());
    disp_.assign(n, Vec<D>::Zero());
    if (p_.rotating()) {
        tau_.assign(n, ang_zero<D>());
        w_pred_.assign(n, ang_zero<D>());
    }
    wall_touching_.assign(n * 2 * D, 0);
    if (table_.needs_history()) wall_spring_.assign(n * 2 * D, Vec<D>::Zero());
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[std::size_t(a)]) continue;
        walls_[code(a, 0)] = {true, WallMotion::fixed(), 0.0, table_.walls()};
        walls_[code(a, 1)] = {true, WallMotion::fixed(), box_.length[a], table_.walls()};
    }
    for (auto& r : p_.r) {
        for (int a = 0; a < D; ++a) {
            if (box_.periodic[std::size_t(a)])
                r[a] -= box_.length[a] * std::floor(r[a] / box_.length[a]);
        }
    }
    list_.configure(box_, std::move(cutoff), ns, n, table_.needs_history());
    rebuild();
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::rebuild() {
    list_.build(box_, p_.r, p_.species);
    std::fill(disp_.begin(), disp_.end(), Vec<D>::Zero());
    ++counters_.rebuilds;
}

template <int D>
void DemEngine<D>::reevaluate_forces() {
    v_pred_ = p_.v;
    if (p_.rotating()) w_pred_ = p_.w;
    compute_forces(0.0);
}

template <int D>
void DemEngine<D>::step() {
    const double h = 0.5 * dt_, dt = dt_;
    const std::size_t n = p_.size();
    const bool rot = p_.rotating();
    const Vec<D> g = g_;
    // Local copies and raw pointers: the stores to positions cannot alias them, so nothing is
    // reloaded per particle.
    std::array<double, D> period{};  // 0 on bounded axes
    for (int k = 0; k < D; ++k)
        period[std::size_t(k)] = box_.periodic[std::size_t(k)] ? box_.length[k] : 0;
    const std::uint32_t* species = p_.species.data();
    const double* inv_mass = inv_mass_.data();
    const double* inv_inertia = inv_inertia_.data();
    Vec<D>* r = p_.r.data();
    Vec<D>* v = p_.v.data();
    Vec<D>* v_pred = v_pred_.data();
    Vec<D>* f = f_.data();
    Vec<D>* disp = disp_.data();
    double max_disp2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec<D> a = inv_mass[species[i]] * f[i] + g;
        f[i].setZero();            // consumed: the forces of t + dt accumulate here
        v[i] += h * a;             // 1. half kick: v(t + dt/2)
        v_pred[i] = v[i] + h * a;  //    predictor for the dampers: ~v(t + dt)
        const Vec<D> dr = dt * v[i];
        r[i] += dr;  // 2. drift: r(t + dt)
        disp[i] += dr;
        max_disp2 = std::max(max_disp2, disp[i].squaredNorm());
        for (std::size_t k = 0; k < std::size_t(D); ++k) {
            const double L = period[k];
            if (L == 0) continue;
            double& x = r[i][int(k)];
            if (x < 0) {
                x += L;
                if (x >= L) x = 0;  // -tiny + L rounded to L
            } else if (x >= L) {
                x -= L;
            }
        }
    }
    if (rot) {
        AngVec<D>* w = p_.w.data();
        AngVec<D>* w_pred = w_pred_.data();
        AngVec<D>* tau = tau_.data();
        for (std::size_t i = 0; i < n; ++i) {
            const AngVec<D> alpha = inv_inertia[species[i]] * tau[i];
            tau[i] = ang_zero<D>();
            w[i] += h * alpha;
            w_pred[i] = w[i] + h * alpha;
        }
    }
    ++steps_;
    ++counters_.steps;
    // Every pair within sigma_ij was within sigma_ij + skin at the last build unless two
    // particles moved by more than skin / 2 each.
    if (max_disp2 > 0.25 * skin_ * skin_) rebuild();
    accumulate_forces(dt);  // 3. forces at t + dt (f_, tau_ were zeroed above)
    for (std::size_t i = 0; i < n; ++i) {
        v[i] += h * (inv_mass[species[i]] * f[i] + g);  // 4. half kick: v(t + dt)
    }
    if (rot) {
        AngVec<D>* w = p_.w.data();
        const AngVec<D>* tau = tau_.data();
        for (std::size_t i = 0; i < n; ++i) w[i] += (h * inv_inertia[species[i]]) * tau[i];
    }
}

template <int D>
typename DemEngine<D>::Stop DemEngine<D>::advance(double t_limit,
                                                  const std::atomic<bool>* interrupt) {
    Stop stop = Stop::TimeLimit;
    std::uint32_t check = 0;
    while (now() < t_limit) {
        if (interrupt && (check++ & 1023u) == 0 && interrupt->load(std::memory_order_relaxed)) {
            stop = Stop::Interrupted;
            break;
        }
        step();
    }
    std::fill(p_.t.begin(), p_.t.end(), now());
    return stop;
}

template <int D>
void DemEngine<D>::compute_forces(double dt_advance) {
    std::fill(f_.begin(), f_.end(), Vec<D>::Zero());
    std::fill(tau_.begin(), tau_.end(), ang_zero<D>());
    accumulate_forces(dt_advance);
}

template <int D>
void DemEngine<D>::accumulate_forces(double dt_advance) {
    const auto run = [&]<DemLaw L>() {
        if (p_.rotating()) {
            pair_forces<L, true>(dt_advance);
            wall_forces<L, true>(dt_advance);
        } else {
            pair_forces<L, false>(dt_advance);
            wall_forces<L, false>(dt_advance);
        }
    };
    switch (table_.law()) {
        case DemLaw::linear_dashpot:
            run.template operator()<DemLaw::linear_dashpot>();
            break;
        case DemLaw::cundall_strack:
            run.template operator()<DemLaw::cundall_strack>();
            break;
        case DemLaw::hertz_mindlin:
            run.template operator()<DemLaw::hertz_mindlin>();
            break;
    }
}

// Pair contacts over the half neighbour list: force on i, its opposite on j (Newton's third law
// exactly, so the total momentum changes by round-off only). Raw pointers throughout (the byte
// stores to the contact flags may alias anything, which would reload every vector's data pointer
// per entry); nothing is written for an entry that neither touches nor touched.
template <int D>
template <DemLaw L, bool Rot>
void DemEngine<D>::pair_forces(double dt_advance) {
    constexpr bool kHistory = L != DemLaw::linear_dashpot;
    const std::size_t ns = mass_.size();
    const DemContactParams* params = table_.pairs().data();
    const AngVec<D> zero = ang_zero<D>();
    std::uint64_t formed = 0, active = 0;
    double worst = counters_.max_overlap;
    // Minimum image per component without branches on the axis kind: a bounded axis has period
    // 0 and half-period infinity. Scalars, not a vector patched in memory (store forwarding).
    std::array<double, D> period{}, half{};
    for (std::size_t k = 0; k < std::size_t(D); ++k) {
        const bool per = box_.periodic[k];
        period[k] = per ? box_.length[int(k)] : 0.0;
        half[k] = per ? 0.5 * box_.length[int(k)] : kInf;
    }
    const std::size_t entries = list_.entries();
    const std::uint32_t* owner = list_.owner.data();
    const std::uint32_t* partner = list_.partner.data();
    std::uint8_t* touching = list_.touching.data();
    Vec<D>* spring = list_.spring.data();
    const Vec<D>* r = p_.r.data();
    const Vec<D>* v = p_.v.data();
    const Vec<D>* v_pred = v_pred_.data();
    const AngVec<D>* w = p_.w.data();
    const AngVec<D>* w_pred = w_pred_.data();
    const std::uint32_t* species = p_.species.data();
    const double* radius = radius_.data();
    Vec<D>* f = f_.data();
    AngVec<D>* tau = tau_.data();
    // One flat loop over the entries (no per-row branches: most rows of a dilute gas are empty).
    for (std::size_t k = 0; k < entries; ++k) {
        const std::uint32_t i = owner[k], j = partner[k];
        const std::uint32_t si = species[i], sj = species[j];
        const DemContactParams& P = params[si * ns + sj];
        std::array<double, D> dc;
        double dist2 = 0;
        for (std::size_t a = 0; a < std::size_t(D); ++a) {
            double x = r[i][int(a)] - r[j][int(a)];
            x = x > half[a] ? x - period[a] : (x < -half[a] ? x + period[a] : x);
            dc[a] = x;
            dist2 += x * x;
        }
        if (!(dist2 < P.sigma * P.sigma)) {
            if (touching[k]) touching[k] = 0;
            continue;
        }
        Vec<D> d;
        for (std::size_t a = 0; a < std::size_t(D); ++a) d[int(a)] = dc[a];
        const double dist = std::sqrt(dist2);
        const Vec<D> nrm = (1.0 / dist) * d;  // from j to i
        const double delta = P.sigma - dist;  // (A6)
        const bool forms = touching[k] == 0;
        touching[k] = 1;
        ++active;
        if (forms) ++formed;
        if (delta > worst * P.sigma) worst = delta / P.sigma;
        const double li = radius[si], lj = radius[sj];
        AngVec<D> wpi = zero, wpj = zero, whi = zero, whj = zero;
        if constexpr (Rot) {
            wpi = w_pred[i];
            wpj = w_pred[j];
            whi = w[i];
            whj = w[j];
        }
        // (A3) at the predicted velocities: the dampers' relative velocity.
        const Vec<D> g = contact_velocity<D>(v_pred[i], v_pred[j], wpi, wpj, li, lj, nrm);
        const ContactForce<D> c = [&] {
            if constexpr (kHistory) {
                Vec<D>& xi = spring[k];
                if (forms) xi.setZero();
                // The spring integrates the half-step velocities that moved the positions; a
                // new contact only over its in-contact part delta / closing speed.
                const Vec<D> gh = contact_velocity<D>(v[i], v[j], whi, whj, li, lj, nrm);
                const double closing = -gh.dot(nrm);
                double dt_in = dt_advance;
                if (forms && closing * dt_in > delta) dt_in = delta / closing;
                advance_tangential_spring<D>(xi, nrm, Vec<D>(dt_in * gh));
                return dem_contact_force<L, D>(P, delta, nrm, g, li, lj, xi);
            } else {
                (void)whi;
                (void)whj;
                (void)spring;
                (void)v;
                Vec<D> unused;
                return dem_contact_force<L, D>(P, delta, nrm, g, li, lj, unused);
            }
        }();
        f[i] += c.force;
        f[j] -= c.force;
        if constexpr (Rot) {
            tau[i] += c.torque_i;
            tau[j] += c.torque_j;
        }
    }
    counters_.contacts += formed;
    counters_.active_contacts = active;
    counters_.max_overlap = worst;
}

// Plane walls: the particle against an infinite mass (m_eff = m_i, lever arm 0 on the wall side)
// moving along its normal with velocity u(t): v_j = u n_axis in the relative velocity (A3).
template <int D>
template <DemLaw L, bool Rot>
void DemEngine<D>::wall_forces(double dt_advance) {
    constexpr bool kHistory = L != DemLaw::linear_dashpot;
    constexpr std::size_t kWalls = 2 * D;
    const std::size_t n = p_.size();
    const AngVec<D> zero = ang_zero<D>();
    const double t = now();
    double worst = counters_.max_overlap;
    for (std::size_t c = 0; c < kWalls; ++c) {
        const Wall& w = walls_[c];
        if (!w.present) continue;
        const int a = int(c / 2);
        const double inward = c % 2 == 0 ? 1.0 : -1.0;
        const double surface = w.base + w.motion.position(t);
        Vec<D> nrm = Vec<D>::Zero();
        nrm[a] = inward;  // into the gas
        Vec<D> vw = Vec<D>::Zero();
        vw[a] = w.motion.velocity(t);
        double impulse = 0;
        std::uint64_t formed = 0;
        // Raw pointers (the byte stores to the contact flags may alias anything); a flag is
        // written only when it changes.
        const std::uint32_t* species = p_.species.data();
        const double* radius = radius_.data();
        const Vec<D>* r = p_.r.data();
        std::uint8_t* touching_of = wall_touching_.data() + c;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t s = species[i];
            const double R = radius[s];
            const double gap = inward * (r[i][a] - surface) - R;
            std::uint8_t& touching = touching_of[i * kWalls];
            if (!(gap < 0)) {
                if (touching) touching = 0;
                continue;
            }
            const double delta = -gap;
            const bool forms = touching == 0;
            touching = 1;
            if (forms) ++formed;
            const DemContactParams& P = w.params[s];
            if (delta > worst * 2 * R) worst = 0.5 * delta / R;
            AngVec<D> wpi = zero, whi = zero;
            if constexpr (Rot) {
                wpi = w_pred_[i];
                whi = p_.w[i];
            }
            const Vec<D> g = contact_velocity<D>(v_pred_[i], vw, wpi, zero, R, 0.0, nrm);
            const ContactForce<D> cf = [&] {
                if constexpr (kHistory) {
                    Vec<D>& xi = wall_spring_[i * kWalls + c];
                    if (forms) xi.setZero();
                    const Vec<D> gh = contact_velocity<D>(p_.v[i], vw, whi, zero, R, 0.0, nrm);
                    const double closing = -gh.dot(nrm);
                    double dt_in = dt_advance;
                    if (forms && closing * dt_in > delta) dt_in = delta / closing;
                    advance_tangential_spring<D>(xi, nrm, Vec<D>(dt_in * gh));
                    return dem_contact_force<L, D>(P, delta, nrm, g, R, 0.0, xi);
                } else {
                    (void)whi;
                    Vec<D> unused;
                    return dem_contact_force<L, D>(P, delta, nrm, g, R, 0.0, unused);
                }
            }();
            f_[i] += cf.force;
            if constexpr (Rot) tau_[i] += cf.torque_i;
            impulse += cf.f_n;
        }
        wall_impulse_[c] += impulse * dt_advance;
        wall_hits_[c] += formed;
        counters_.wall_contacts += formed;
    }
    counters_.max_overlap = worst;
}

template <int D>
DemEnergies DemEngine<D>::energies() const {
    DemEnergies e;
    const std::size_t n = p_.size();
    const DemLaw law = table_.law();
    const bool history = table_.needs_history();
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t s = p_.species[i];
        e.translational += 0.5 * mass_[s] * p_.v[i].squaredNorm();
        if (p_.rotating()) e.rotational += 0.5 * inertia_[s] * ang_squared<D>(p_.w[i]);
        e.gravitational -= mass_[s] * g_.dot(p_.r[i]);
        for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k) {
            const std::uint32_t j = list_.partner[k];
            const DemContactParams& P = table_.pair(s, p_.species[j]);
            const double dist = box_.separation(p_.r[i], p_.r[j]).norm();
            if (!(dist < P.sigma)) continue;
            const double xi2 = history ? list_.spring[k].squaredNorm() : 0.0;
            e.elastic += dem_contact_energy(law, P, P.sigma - dist, xi2);
        }
    }
    const double t = now();
    for (std::size_t c = 0; c < 2 * D; ++c) {
        if (!walls_[c].present) continue;
        const int a = int(c / 2);
        const double inward = c % 2 == 0 ? 1.0 : -1.0;
        const double surface = wall_position(int(c), t);
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t s = p_.species[i];
            const double gap = inward * (p_.r[i][a] - surface) - radius_[s];
            if (!(gap < 0)) continue;
            const double xi2 = history ? wall_spring_[i * 2 * D + c].squaredNorm() : 0.0;
            e.elastic += dem_contact_energy(law, walls_[c].params[s], -gap, xi2);
        }
    }
    return e;
}

template <int D>
void DemEngine<D>::set_wall(int axis, int side, const WallMotion& motion, double restitution) {
    if (axis < 0 || axis >= D || side < 0 || side > 1 || box_.periodic[std::size_t(axis)]) {
        fail("set_wall: walls need a bounded (non-periodic) axis and side 0 or 1");
    }
    if (motion.kind == WallMotion::Kind::sawtooth) {
        fail(
            "set_wall: the sawtooth limit has no position; use a sawtooth_ramp, a sinusoid or a "
            "parabolic piston");
    }
    double dmax = 0;
    for (double r : radius_) dmax = std::max(dmax, 2 * r);
    const double reach = motion.reach();
    if (2.0 * reach + dmax > box_.length[axis]) {
        fail("set_wall: the wall's excursion leaves no room for particles");
    }
    std::vector<DemContactParams> params = table_.walls();
    if (restitution >= 0) {
        for (std::size_t s = 0; s < params.size(); ++s) {
            params[s] = table_.wall_with_restitution(s, restitution);
            if (dt_ > params[s].duration / 5) {
                fail("set_wall: with restitution " + num(restitution) + " the wall contact lasts " +
                     num(params[s].duration) + " < 5 dt (dt = " + num(dt_) +
                     "): velocity Verlet needs at least 5 steps per contact");
            }
        }
    }
    Wall& w = walls_[code(axis, side)];
    w.params = std::move(params);
    w.present = true;
    w.motion = motion;
    w.base = side == 0 ? reach : box_.length[axis] - reach;  // excursion inside [0, L]
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::remove_wall(int axis, int side) {
    if (axis < 0 || axis >= D || side < 0 || side > 1) fail("remove_wall: no such wall");
    walls_[code(axis, side)].present = false;
    for (std::size_t i = 0; i < p_.size(); ++i) wall_touching_[i * 2 * D + code(axis, side)] = 0;
    reevaluate_forces();
}

template class DemEngine<2>;
template class DemEngine<3>;

}  // namespace gran
