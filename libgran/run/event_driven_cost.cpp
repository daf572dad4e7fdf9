#include "libgran/run/event_driven_cost.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "libgran/core/kinetic_theory.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/engines/cell_grid.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

namespace {

// Collisions per particle per unit time of the mixture at the initial temperature (Enskog).
double collision_frequency(const Scene& sc) {
    const SpeciesTable& t = sc.species;
    double volume = 1;
    for (double l : sc.box_length) volume *= l;
    const double n_total = double(t.total_count());
    std::vector<double> sigma, x;
    for (const auto& s : t.species) {
        sigma.push_back(s.diameter);
        x.push_back(double(s.count) / n_total);
    }
    const double phi = std::min(sc.packing_fraction, 0.5);  // a rate, not the packing's limit
    const theory::MixtureContactValues chi(sc.dimension, phi, sigma, x);
    const double T = sc.temperature;
    double omega = 0;
    for (std::size_t a = 0; a < t.size(); ++a) {
        for (std::size_t b = 0; b < t.size(); ++b) {
            // The partners of a particle of species a: the others (a lone particle has none, and
            // a schedule in collisions per particle never ends: refused as an endless run).
            const double partners = double(t.species[b].count) - (a == b ? 1.0 : 0.0);
            omega +=
                x[a] * theory::enskog_pair_collision_frequency(
                           sc.dimension, partners / volume, 0.5 * (sigma[a] + sigma[b]),
                           chi(sigma[a], sigma[b]), T, t.species[a].mass, T, t.species[b].mass);
        }
    }
    return omega;
}

// Cell crossings per particle per unit time: mean speed along each axis over the width of the
// event-driven engine's cells (cell_list.cpp: at least one largest diameter, >= 4 cells on a
// periodic axis or one, at most cell_cap(N) cells).
template <int D>
double crossing_rate(const Scene& sc) {
    std::array<std::int32_t, D> ncell{};
    std::array<bool, D> periodic{};
    const double dmax = sc.species.max_diameter();
    for (int a = 0; a < D; ++a) {
        const double cells = std::floor(sc.box_length[std::size_t(a)] / dmax);
        periodic[std::size_t(a)] = sc.periodic[std::size_t(a)];
        std::int32_t nc = cells > 1e9 ? 1000000000 : std::int32_t(std::max(cells, 1.0));
        if (periodic[std::size_t(a)] && nc < 4) nc = 1;
        ncell[std::size_t(a)] = nc;
    }
    coarsen_cells<D>(ncell, periodic, cell_cap(sc.species.total_count()), 4, 4);
    double mean_speed = 0;  // <|v_a|> = sqrt(2 T / (pi m)), number-weighted
    const double n = double(sc.species.total_count());
    for (const auto& s : sc.species.species)
        mean_speed += double(s.count) / n * std::sqrt(2 * sc.temperature / (M_PI * s.mass));
    double rate = 0;
    for (int a = 0; a < D; ++a)
        rate += mean_speed * ncell[std::size_t(a)] / sc.box_length[std::size_t(a)];
    return rate;
}

}  // namespace

EventEstimate estimate_events(const Scene& sc, const EngineDemands& demands) {
    EventEstimate e;
    const double n = double(sc.species.total_count());
    const double omega = collision_frequency(sc);
    const double length = sc.schedule.equilibration + sc.schedule.measurement;
    if (sc.schedule.unit == ScheduleUnit::Time) {
        e.simulated_time = length;
        e.collisions = 0.5 * n * omega * length;
    } else {
        e.simulated_time = length / omega;  // +inf without collisions
        e.collisions = 0.5 * n * length;
    }
    const double crossings = sc.dimension == 2 ? crossing_rate<2>(sc) : crossing_rate<3>(sc);
    e.crossings = n * crossings * e.simulated_time;
    for (double first_kick : demands.first_kicks) {
        if (first_kick > 0) e.kick_updates += n * e.simulated_time / first_kick;
    }
    return e;
}

namespace {

// A run long enough to matter (a day at 1e7 events per second) made almost only of cell crossings:
// free flights so long that the engine does bookkeeping, not physics (a Knudsen gas).
bool crossings_swamp_collisions(const EventEstimate& e) {
    return e.events() > kLongRunEvents && e.crossings > kMaxCrossingsPerCollision * e.collisions;
}

}  // namespace

void refuse_endless_run(const Scene& sc, const EventEstimate& e) {
    if (sc.schedule.unit != ScheduleUnit::Time && !(e.simulated_time < kInf)) {
        sc.run_settings.fail(
            "unit", fmt::format("kinetic theory gives no collisions ({} particles at temperature "
                                "{:g}): a schedule in collisions per particle would never end; use "
                                "run.unit: time",
                                sc.species.total_count(), sc.temperature));
    }
    const double events = e.events();
    const bool dilute = crossings_swamp_collisions(e);
    if (events <= kMaxEvents && !dilute) return;  // NaN and inf fail the first test too
    const std::string what = fmt::format(
        "this run would need about {:.2g} events ({:.2g} collisions, {:.2g} cell crossings, "
        "{:.2g} kick updates over {:.3g} time units, kinetic theory at the initial temperature), "
        "{}",
        events, e.collisions, e.crossings, e.kick_updates, e.simulated_time,
        dilute ? fmt::format("over {:g} cell crossings per collision", kMaxCrossingsPerCollision)
               : fmt::format("more than {:g}: it could not finish", kMaxEvents));
    if (dilute || !std::isfinite(e.simulated_time) ||
        e.crossings >= std::max(e.collisions, e.kick_updates)) {
        throw SceneError(fmt::format(
            "{}: {}; the gas is so dilute (packing fraction {:.3g}) that particles fly across "
            "cells for ages between collisions: raise box.packing_fraction (or shorten "
            "box.lengths), or shorten the run (run.measurement)",
            sc.box_location, what, sc.packing_fraction));
    }
    if (e.kick_updates >= e.collisions) {
        throw SceneError(
            fmt::format("{}: {}; the kicks dominate: raise the kick interval of the "
                        "thermostat (drivers[].interval)",
                        sc.box_location, what));
    }
    sc.run_settings.fail("measurement", what + ": shorten the run or use fewer particles");
}

std::string describe(const EventEstimate& e) {
    return fmt::format(
        "expected cost: about {:.2g} events ({:.2g} collisions, {:.2g} cell crossings, {:.2g} "
        "kick updates; kinetic theory at the initial temperature), {:.3g} time units",
        e.events(), e.collisions, e.crossings, e.kick_updates, e.simulated_time);
}

}  // namespace gran
