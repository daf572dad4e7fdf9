#include "libgran/engines/dem/engine.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "libgran/core/parallel.hpp"
#include "libgran/engines/dem/drift.hpp"

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

double shortest_contact_duration(const ContactTable& contacts, bool walls) {
    const auto& soft = contacts.law->soft_contact;
    if (!soft) fail("law '" + contacts.law->name + "' has no soft-contact form");
    double tc = kInf;
    const std::size_t ns = contacts.species;
    for (std::size_t k = 0; k < contacts.pair_contacts(); ++k)
        tc = std::min(tc, soft->duration(*contacts.table, k));
    if (walls) {
        for (std::size_t w = 0; w < contacts.walls.size(); ++w) {
            for (std::size_t s = 0; s < ns; ++s)
                tc = std::min(tc, soft->duration(*contacts.table, contacts.wall_index(w, s)));
        }
    }
    return tc;
}

double dem_time_step(const ContactTable& contacts, bool walls, double dt, double dt_fraction) {
    // Verlet resolves a contact with at least a few steps; t_c / 5 is the limit.
    const double tc = shortest_contact_duration(contacts, walls);
    const double step = dt > 0 ? dt : dt_fraction * tc;
    if (!(step > 0) || !std::isfinite(step)) fail("the time step must be finite and > 0");
    if (step > tc / 5) {
        fail("dt = " + num(step) + " exceeds t_c / 5 = " + num(tc / 5) + " (t_c = " + num(tc) +
             " is the shortest contact duration): velocity Verlet needs at least 5 steps per "
             "contact for a stable, accurate collision (restitution and duration); use dt <= "
             "t_c / 50 (the default when dt = 0)");
    }
    return step;
}

template <int D>
DemEngine<D>::DemEngine(const Box<D>& box, const SpeciesTable& species,
                        const ContactTable& contacts, Particles<D> particles, DemSettings settings)
    : box_(box), contacts_(contacts), p_(std::move(particles)), settings_(settings) {
    p_.image.resize(p_.size());  // particles built by hand (tests) may leave it empty
    const std::size_t ns = species.size();
    if (ns == 0 || contacts_.species != ns) {
        fail("the contact table has " + std::to_string(contacts_.species) +
             " species, the species table " + std::to_string(ns));
    }
    const auto* loops = Registry<DemLawLoops<D>>::instance().find(contacts_.law->name);
    if (!loops || !contacts_.law->soft_contact) {
        fail("law '" + contacts_.law->name + "' has no soft-contact form (the dem engine takes " +
             Registry<DemLawLoops<D>>::instance().names() + ")");
    }
    loops_ = *loops;
    history_ = contacts_.law->soft_contact->history;
    set_species(species);
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
    bool bounded = false;
    for (int a = 0; a < D; ++a) bounded = bounded || !box_.periodic[std::size_t(a)];
    dt_ = dem_time_step(contacts_, bounded, settings_.dt, settings_.dt_fraction);
    if (settings_.threads < 1 || settings_.threads > kMaxThreads) {
        fail("threads must be 1 to " + std::to_string(kMaxThreads) + ", not " +
             std::to_string(settings_.threads));
    }
    const std::size_t per_thread = std::max<std::size_t>(1, settings_.min_particles_per_thread);
    threads_ = int(std::min<std::size_t>(std::size_t(settings_.threads),
                                         std::max<std::size_t>(1, p_.size() / per_thread)));
    configure_neighbours();
    allocate_state();
    place_walls();
    list_.configure(box_, neighbour_cutoffs(), ns, n, history_, sorts());
    rebuild();
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::set_species(const SpeciesTable& species) {
    for (const Species& s : species.species) {
        if (!(s.mass > 0) || !(s.diameter > 0) || !(s.inertia_factor > 0)) {
            fail("species '" + s.name + "' needs mass, diameter and inertia factor > 0");
        }
        mass_.push_back(s.mass);
        radius_.push_back(0.5 * s.diameter);
        inertia_.push_back(s.inertia_factor * s.mass * s.diameter * s.diameter / 4);  // q m s^2/4
        inv_mass_.push_back(1.0 / mass_.back());
        inv_inertia_.push_back(1.0 / inertia_.back());
        dmax_ = std::max(dmax_, s.diameter);
    }
    const std::size_t ns = species.size();
    sigma_.resize(ns * ns);
    for (std::size_t a = 0; a < ns; ++a) {
        for (std::size_t b = 0; b < ns; ++b) {
            sigma_[a * ns + b] = 0.5 * (species.species[a].diameter + species.species[b].diameter);
        }
    }
}

// Neighbour list: cutoff sigma_ij + skin, below half of every periodic length.
template <int D>
void DemEngine<D>::configure_neighbours() {
    if (!(settings_.skin >= 0)) fail("the skin must be >= 0");
    skin_ = settings_.skin * dmax_;
    const double widest = [&] {
        double w = 0;
        for (double c : neighbour_cutoffs()) w = std::max(w, c);
        return w;
    }();
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[std::size_t(a)] && !(widest < 0.5 * box_.length[a])) {
            fail("the neighbour cutoff sigma + skin = " + num(widest) +
                 " must stay below half the periodic length " + num(box_.length[a]) +
                 " along axis " + std::to_string(a) + " (minimum image)");
        }
    }
}

template <int D>
std::vector<double> DemEngine<D>::neighbour_cutoffs() const {
    const std::size_t ns = mass_.size();
    std::vector<double> cutoff(ns * ns);
    for (std::size_t a = 0; a < ns; ++a) {
        for (std::size_t b = 0; b < ns; ++b) cutoff[a * ns + b] = radius_[a] + radius_[b] + skin_;
    }
    return cutoff;
}

// Per-particle state; angular velocities as soon as some contact has friction.
template <int D>
void DemEngine<D>::allocate_state() {
    const std::size_t n = p_.size();
    if (contacts_.rotating && !p_.rotating()) p_.w.assign(n, ang_zero<D>());
    if (p_.rotating() && p_.w.size() != n) fail("angular velocities of the wrong size");
    t_start_ = 0;
    for (double t : p_.t) t_start_ = std::max(t_start_, t);
    p_.t.assign(n, t_start_);
    id_.resize(n);
    for (std::size_t i = 0; i < n; ++i) id_[i] = std::uint32_t(i);
    f_.assign(n, Vec<D>::Zero());
    v_pred_.assign(n, Vec<D>::Zero());
    disp_.assign(n, Vec<D>::Zero());
    if (p_.rotating()) {
        tau_.assign(n, ang_zero<D>());
        w_pred_.assign(n, ang_zero<D>());
    }
    wall_touching_.assign(n * 2 * D, 0);
    if (history_) wall_spring_.assign(n * 2 * D, Vec<D>::Zero());
    for (auto& r : p_.r) {
        for (int a = 0; a < D; ++a) {
            if (box_.periodic[std::size_t(a)])
                r[a] -= box_.length[a] * std::floor(r[a] / box_.length[a]);
        }
    }
}

// Static walls at 0 and L of every bounded axis, with the contacts of the wall partner `box`.
template <int D>
void DemEngine<D>::place_walls() {
    const std::size_t box_partner = contacts_.wall_named("box");
    for (int a = 0; a < D; ++a) {
        if (box_.periodic[std::size_t(a)]) continue;
        if (box_partner == contacts_.walls.size()) {
            fail("the box has a bounded axis but the contacts have no wall partner 'box'");
        }
        walls_[code(a, 0)] = {true, WallMotion::fixed(), 0.0, box_partner, -1, WallMotion::fixed()};
        walls_[code(a, 1)] = {true, WallMotion::fixed(), box_.length[a], box_partner,
                              -1,   WallMotion::fixed()};
    }
}

template <int D>
void DemEngine<D>::rebuild() {
    const bool sort = sort_due();
    if (sort) sort_particles();
    list_.build(p_.r, p_.species, threads_, sort ? new_index_.data() : nullptr);
    if (stage_clock_.enabled()) tally_search_shares();
    std::fill(disp_.begin(), disp_.end(), Vec<D>::Zero());
    wall_candidates_stale_ = true;
    pair_split_stale_ = true;
    ++counters_.rebuilds;
}

template <int D>
bool DemEngine<D>::sort_due() const {
    if (!sorts()) return false;
    return counters_.sorts == 0 || steps_ - steps_at_sort_ >= settings_.sort_interval;
}

template <int D>
void DemEngine<D>::sort_particles() {
    const std::vector<std::uint32_t>& order = list_.spatial_order(p_.r, p_.species);
    const std::size_t n = p_.size();
    new_index_.resize(n);
    for (std::size_t k = 0; k < n; ++k) new_index_[order[k]] = std::uint32_t(k);
    // Every per-particle array, `per` values per particle: the value of slot k is the one of
    // particle order[k]. (The forces were consumed by the drift, or are about to be evaluated,
    // but they move along all the same.)
    const auto gather = [&order, n](auto& a, std::size_t per) {
        if (a.empty()) return;
        std::remove_reference_t<decltype(a)> out(a.size());
        for (std::size_t k = 0; k < n; ++k) {
            for (std::size_t c = 0; c < per; ++c) out[k * per + c] = a[order[k] * per + c];
        }
        a.swap(out);
    };
    gather(p_.r, 1);
    gather(p_.v, 1);
    gather(p_.t, 1);
    gather(p_.species, 1);
    gather(p_.w, 1);
    gather(p_.image, 1);
    gather(id_, 1);
    gather(f_, 1);
    gather(v_pred_, 1);
    gather(disp_, 1);
    gather(tau_, 1);
    gather(w_pred_, 1);
    gather(wall_touching_, 2 * D);
    gather(wall_spring_, 2 * D);
    steps_at_sort_ = steps_;
    ++counters_.sorts;
}

// A particle touches a wall only within R of its surface, which stays within `reach` of the
// wall's base. Until the next list build a particle moves less than skin / 2 from where it was
// at the last one, so less than skin from where it is now: the particles within reach + R + skin
// of the base are all that can touch the wall meanwhile (1e-9 L more for the rounding of the
// wall's position). Those still flagged as touching are kept, so the wall pass clears their
// flags. In increasing index, so the wall pass adds the forces in the order a pass over all
// particles does.
template <int D>
void DemEngine<D>::find_wall_candidates() {
    const std::size_t n = p_.size();
    for (std::size_t c = 0; c < 2 * D; ++c) {
        std::vector<std::uint32_t>& near = wall_candidates_[c];
        near.clear();
        const Wall& w = walls_[c];
        if (!w.present) continue;
        const int a = int(c / 2);
        const double margin = skin_ + 1e-9 * box_.length[a] + w.motion.reach();
        const double lowest = w.base - margin, highest = w.base + margin;
        for (std::size_t i = 0; i < n; ++i) {
            const double R = radius_[p_.species[i]];
            const double x = p_.r[i][a];
            const bool reaches = c % 2 == 0 ? x - R < highest : x + R > lowest;
            if (reaches || wall_touching_[i * 2 * D + c]) near.push_back(std::uint32_t(i));
        }
    }
    wall_candidates_stale_ = false;
}

template <int D>
void DemEngine<D>::reevaluate_forces() {
    v_pred_ = p_.v;
    if (p_.rotating()) w_pred_ = p_.w;
    compute_forces(0.0);
}

template <int D>
template <bool ClosingKick>
void DemEngine<D>::open_step() {
    const std::size_t n = p_.size();
    // Largest displacement since the last build, per thread (a maximum: the same for any split).
    std::array<double, kMaxThreads> moved2{};
    stage_clock_.start();
    const auto drift = [this, &moved2](std::size_t part, std::size_t i0, std::size_t i1) {
        moved2[part] = kick_drift<ClosingKick>(i0, i1);
    };
    // On several threads each thread drifts the grains whose rows it takes in the pair stage
    // (pair_rows_, of the last list): the lines it writes here are those it reads there, and do
    // not move between the cores (docs/performance.md, "The drift on the pair stage's rows").
    if (rows_split())
        parallel_ranges(threads_, pair_rows_, drift);
    else
        parallel_chunks(threads_, n, drift);
    stage_clock_.lap(stage_times_.kicks_and_drift);
    ++steps_;
    ++counters_.steps;
    // Every pair within sigma_ij was within sigma_ij + skin at the last build unless two
    // particles moved by more than skin / 2 each.
    if (*std::max_element(moved2.begin(), moved2.end()) > 0.25 * skin_ * skin_) rebuild();
    stage_clock_.lap(stage_times_.neighbour_list);
    accumulate_forces(dt_);  // 3. forces at t + dt (f_, tau_ were zeroed by kick_drift)
}

template <int D>
void DemEngine<D>::step() {
    steps(1);
}

template <int D>
void DemEngine<D>::steps(std::uint64_t k) {
    if (k == 0) return;
    open_step<false>();
    for (std::uint64_t s = 1; s < k; ++s) open_step<true>();
    stage_clock_.start();
    parallel_chunks(threads_, p_.size(),
                    [this](std::size_t, std::size_t i0, std::size_t i1) { kick(i0, i1); });
    stage_clock_.lap(stage_times_.kicks_and_drift);
}

template <int D>
template <bool ClosingKick>
double DemEngine<D>::kick_drift(std::size_t i0, std::size_t i1) {
    DriftStep<D> step{dt_, g_, {}};
    for (int k = 0; k < D; ++k)
        step.period[std::size_t(k)] = box_.periodic[std::size_t(k)] ? box_.length[k] : 0;
    const bool rotating = p_.rotating();
    const DriftArrays<D> s{p_.r.data(),
                           p_.v.data(),
                           v_pred_.data(),
                           f_.data(),
                           disp_.data(),
                           p_.image.data(),
                           p_.species.data(),
                           inv_mass_.data(),
                           rotating ? p_.w.data() : nullptr,
                           rotating ? w_pred_.data() : nullptr,
                           rotating ? tau_.data() : nullptr,
                           inv_inertia_.data()};
    // Spheres: two grains per block in SSE2 registers (drift.hpp), the same bits as one at a
    // time in about 70 instructions per grain instead of 120.
    if constexpr (D == 3) {
        return rotating ? kick_drift_pairs_3d<ClosingKick, true>(s, step, i0, i1)
                        : kick_drift_pairs_3d<ClosingKick, false>(s, step, i0, i1);
    } else {
        return kick_drift_per_grain<D, ClosingKick>(s, step, rotating, i0, i1);
    }
}

template <int D>
void DemEngine<D>::kick(std::size_t i0, std::size_t i1) {
    const double h = 0.5 * dt_;
    const Vec<D> g = g_;
    const std::uint32_t* species = p_.species.data();
    const double* inv_mass = inv_mass_.data();
    Vec<D>* v = p_.v.data();
    const Vec<D>* f = f_.data();
    for (std::size_t i = i0; i < i1; ++i) {
        v[i] += h * (inv_mass[species[i]] * f[i] + g);  // 4. half kick: v(t + dt)
    }
    if (p_.rotating()) {
        const double* inv_inertia = inv_inertia_.data();
        AngVec<D>* w = p_.w.data();
        const AngVec<D>* tau = tau_.data();
        for (std::size_t i = i0; i < i1; ++i) w[i] += (h * inv_inertia[species[i]]) * tau[i];
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
        // The steps up to the limit or the next interrupt check, fused (steps()): as many as
        // the loop of single steps would make, by the same test of now().
        std::uint64_t k = 1;
        const std::uint64_t room = interrupt ? 1024 - ((check - 1) & 1023u) : 1024;
        while (k < room && t_start_ + double(steps_ + k) * dt_ < t_limit) ++k;
        steps(k);
        if (interrupt) check += std::uint32_t(k - 1);
    }
    std::fill(p_.t.begin(), p_.t.end(), now());
    return stop;
}

template <int D>
void DemEngine<D>::compute_forces(double dt_advance) {
    std::fill(f_.begin(), f_.end(), Vec<D>::Zero());
    std::fill(tau_.begin(), tau_.end(), ang_zero<D>());
    stage_clock_.start();  // outside a step: the forces' laps start here
    accumulate_forces(dt_advance);
}

template <int D>
DemEnergies DemEngine<D>::energies() const {
    DemEnergies e;
    for (std::size_t i = 0; i < p_.size(); ++i) {
        const std::uint32_t s = p_.species[i];
        e.translational += 0.5 * mass_[s] * p_.v[i].squaredNorm();
        if (p_.rotating()) e.rotational += 0.5 * inertia_[s] * ang_squared<D>(p_.w[i]);
        e.gravitational -= mass_[s] * g_.dot(p_.r[i]);
    }
    e.elastic = (this->*loops_.elastic_energy)();
    return e;
}

template <int D>
void DemEngine<D>::set_wall_slide(int wall_axis, int side, int axis, const WallMotion& motion) {
    if (wall_axis < 0 || wall_axis >= D || side < 0 || side > 1 || axis < 0 || axis >= D ||
        axis == wall_axis || !walls_[code(wall_axis, side)].present) {
        fail("set_wall_slide: needs a present wall and an in-plane axis");
    }
    if (motion.kind == WallMotion::Kind::sawtooth) fail("set_wall_slide: no sawtooth limit");
    Wall& w = walls_[code(wall_axis, side)];
    w.slide_axis = axis;
    w.slide = motion;
    wall_candidates_stale_ = true;
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::set_wall(int axis, int side, const WallMotion& motion, std::size_t partner) {
    if (axis < 0 || axis >= D || side < 0 || side > 1 || box_.periodic[std::size_t(axis)]) {
        fail("set_wall: walls need a bounded (non-periodic) axis and side 0 or 1");
    }
    if (motion.kind == WallMotion::Kind::sawtooth) {
        fail(
            "set_wall: the sawtooth limit has no position; use a sawtooth_ramp, a sinusoid or a "
            "parabolic piston");
    }
    if (partner >= contacts_.walls.size()) fail("set_wall: no such wall partner");
    const double reach = motion.reach();
    if (2.0 * reach + dmax_ > box_.length[axis]) {
        fail("set_wall: the wall's excursion leaves no room for particles");
    }
    const auto& soft = *contacts_.law->soft_contact;
    for (std::size_t s = 0; s < mass_.size(); ++s) {
        const double duration = soft.duration(*contacts_.table, contacts_.wall_index(partner, s));
        if (dt_ > duration / 5) {
            fail("set_wall: the contact of wall '" + contacts_.walls[partner] + "' lasts " +
                 num(duration) + " < 5 dt (dt = " + num(dt_) +
                 "): velocity Verlet needs at least 5 steps per contact");
        }
    }
    Wall& w = walls_[code(axis, side)];
    w.present = true;
    w.slide_axis = -1;
    w.motion = motion;
    w.partner = partner;
    w.base = side == 0 ? reach : box_.length[axis] - reach;  // excursion inside [0, L]
    wall_candidates_stale_ = true;
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::remove_wall(int axis, int side) {
    if (axis < 0 || axis >= D || side < 0 || side > 1) fail("remove_wall: no such wall");
    walls_[code(axis, side)].present = false;
    walls_[code(axis, side)].slide_axis = -1;
    for (std::size_t i = 0; i < p_.size(); ++i) wall_touching_[i * 2 * D + code(axis, side)] = 0;
    wall_candidates_stale_ = true;
    reevaluate_forces();
}

template <int D>
void DemEngine<D>::checkpoint(StateArchive& ar) {
    ar.section("dem engine");
    ar.io(p_);
    ar.io(counters_);
    ar.io(t_start_);
    ar.io(steps_);
    ar.io(id_);
    ar.io(steps_at_sort_);
    ar.io(f_);
    ar.io(v_pred_);
    ar.io(disp_);
    ar.io(tau_);
    ar.io(w_pred_);
    ar.io(wall_touching_);
    ar.io(wall_spring_);
    ar.io(list_);
    ar.io(wall_impulse_);
    ar.io(wall_hits_);
    wall_candidates_stale_ = true;  // derived from the state: found again after a restore
    pair_split_stale_ = true;
}

template class DemEngine<2>;
template class DemEngine<3>;

}  // namespace gran
