#include "libgran/engines/dem/probe.hpp"

#include <algorithm>
#include <stdexcept>

#include "libgran/engines/dem/engine.hpp"

namespace gran {

namespace {

// Runs an engine holding the probe particles until the contact has ended: returns the measured
// restitution (from the normal relative velocity `normal_velocity()` before and after) and the
// time with overlap.
template <int D, class Overlap, class NormalVelocity>
std::pair<double, double> collide(DemEngine<D>& engine, Overlap overlap, NormalVelocity vn) {
    const double before = vn(engine);
    std::uint64_t steps_in_contact = 0;
    bool touched = false;
    const std::uint64_t limit = 200000;
    for (std::uint64_t k = 0; k < limit; ++k) {
        engine.step();
        if (overlap(engine)) {
            touched = true;
            ++steps_in_contact;
        } else if (touched) {
            return {-vn(engine) / before, double(steps_in_contact) * engine.dt()};
        }
    }
    throw std::runtime_error("DEM probe: the isolated collision did not end in 2e5 steps");
}

template <int D>
Vec<D> unit_x() {
    Vec<D> e = Vec<D>::Zero();
    e[0] = 1;
    return e;
}

}  // namespace

// The requested restitution and closed-form duration of contact `index`.
struct Requested {
    double restitution, duration, sigma;
};
Requested requested(const ContactTable& table, std::size_t index, double sigma) {
    const auto& soft = *table.law->soft_contact;
    return {soft.restitution(*table.table, index), soft.duration(*table.table, index), sigma};
}

template <int D>
DemProbeResult probe_pair_collision(const SpeciesTable& species, const ContactTable& table,
                                    std::size_t a, std::size_t b, double speed, double dt) {
    const Requested P =
        requested(table, table.pair_index(a, b),
                  0.5 * (species.species[a].diameter + species.species[b].diameter));
    const double dmax = species.max_diameter();
    Box<D> box;
    box.length = Vec<D>::Constant(8 * dmax + 8 * P.sigma);
    for (int k = 0; k < D; ++k) box.periodic[std::size_t(k)] = true;
    const double ma = species.species[a].mass, mb = species.species[b].mass;
    Particles<D> p;
    p.resize(2, false);
    const Vec<D> centre = 0.5 * box.length;
    // Start just apart (a gap of 1% of sigma): the first contact step begins within one dt.
    const double gap = std::min(0.01 * P.sigma, 0.5 * speed * dt);
    p.r[0] = centre - 0.5 * (P.sigma + gap) * unit_x<D>();
    p.r[1] = centre + 0.5 * (P.sigma + gap) * unit_x<D>();
    p.v[0] = speed * mb / (ma + mb) * unit_x<D>();
    p.v[1] = -speed * ma / (ma + mb) * unit_x<D>();
    p.species = {std::uint32_t(a), std::uint32_t(b)};
    p.t = {0, 0};
    DemSettings s;
    s.dt = dt;
    DemEngine<D> engine(box, species, table, std::move(p), s);
    const auto [e, tc] = collide(
        engine,
        [&](const DemEngine<D>& en) {
            return en.box().separation(en.particles().r[1], en.particles().r[0]).norm() < P.sigma;
        },
        [](const DemEngine<D>& en) { return en.particles().v[1][0] - en.particles().v[0][0]; });
    return {P.restitution, e, P.duration, tc, dt / P.duration};
}

template <int D>
DemProbeResult probe_wall_collision(const SpeciesTable& species, const ContactTable& table,
                                    std::size_t s, std::size_t wall, double speed, double dt) {
    const Requested P =
        requested(table, table.wall_index(wall, s), 0.5 * species.species[s].diameter);
    const double dmax = species.max_diameter();
    Box<D> box;
    box.length = Vec<D>::Constant(8 * dmax);
    for (int k = 1; k < D; ++k) box.periodic[std::size_t(k)] = true;
    Particles<D> p;
    p.resize(1, false);
    p.r[0] = 0.5 * box.length;
    const double gap = std::min(0.01 * P.sigma, 0.5 * speed * dt);
    p.r[0][0] = P.sigma + gap;
    p.v[0] = -speed * unit_x<D>();
    p.species = {std::uint32_t(s)};
    p.t = {0};
    DemSettings st;
    st.dt = dt;
    DemEngine<D> engine(box, species, table, std::move(p), st);
    engine.set_wall(0, 0, WallMotion::fixed(), wall);
    const auto [e, tc] = collide(
        engine, [&](const DemEngine<D>& en) { return en.particles().r[0][0] < P.sigma; },
        [](const DemEngine<D>& en) { return en.particles().v[0][0]; });
    return {P.restitution, e, P.duration, tc, dt / P.duration};
}

template DemProbeResult probe_pair_collision<2>(const SpeciesTable&, const ContactTable&,
                                                std::size_t, std::size_t, double, double);
template DemProbeResult probe_pair_collision<3>(const SpeciesTable&, const ContactTable&,
                                                std::size_t, std::size_t, double, double);
template DemProbeResult probe_wall_collision<2>(const SpeciesTable&, const ContactTable&,
                                                std::size_t, std::size_t, double, double);
template DemProbeResult probe_wall_collision<3>(const SpeciesTable&, const ContactTable&,
                                                std::size_t, std::size_t, double, double);

}  // namespace gran
