#include "libgran/run/dem_cost.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "libgran/core/scene_error.hpp"
#include "libgran/engines/dem/engine.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

namespace {

// Walls (and so grain-wall contacts) on some axis.
bool bounded(const Scene& sc) {
    return std::any_of(sc.periodic.begin(), sc.periodic.end(), [](bool p) { return !p; });
}

// The smallest diameter over the fastest velocity scale: thermal speed of the lightest species at
// the initial temperature, the peak speed of a moving wall, free fall over the smallest diameter.
double grain_time(const Scene& sc) {
    double dmin = sc.species.max_diameter();
    for (const auto& s : sc.species.species) dmin = std::min(dmin, s.diameter);
    double g2 = 0;
    for (double g : sc.gravity) g2 += g * g;
    const double v = std::max({std::sqrt(sc.temperature / sc.species.min_mass()),
                               sc.info.peak_velocity, std::sqrt(std::sqrt(g2) * dmin)});
    return dmin / v;
}

// The factors of particle-steps = particles x (run / grain time) x (grain time / t_c) x (t_c / dt)
// over their usual values: 1e5 particles, runs of 1e4 grain times, contacts 1e4 times shorter
// than a grain time (stiff glass beads), 50 steps per contact (dt_fraction 0.02). Their product,
// 5e14, is about kMaxParticleSteps, so a refused run has some factor well above its usual value:
// the largest excess names the key to change.
enum class Excess { StepsPerContact, StiffContacts, LongRun, Particles };

Excess largest_excess(const DemEstimate& e) {
    const std::array<double, 4> excess{e.contact_time / e.dt / 50,
                                       e.grain_time / e.contact_time / 1e4,
                                       e.simulated_time / e.grain_time / 1e4, e.particles / 1e5};
    std::size_t k = 2;  // a run whose numbers are not finite: shorten it
    for (std::size_t i = 0; i < excess.size(); ++i) {
        if (excess[i] > excess[k] || std::isnan(excess[k])) k = i;
    }
    return Excess(k);
}

}  // namespace

DemEstimate estimate_particle_steps(const Scene& sc) {
    const Params& ep = sc.engine_settings.params;
    DemEstimate e;
    e.particles = double(sc.species.total_count());
    e.simulated_time = sc.schedule.equilibration + sc.schedule.measurement;
    e.contact_time = shortest_contact_duration(sc.contacts, bounded(sc));
    e.dt = dem_time_step(sc.contacts, bounded(sc), ep.real("dt"), ep.real("dt_fraction"));
    e.grain_time = grain_time(sc);
    return e;
}

void refuse_endless_run(const Scene& sc, const DemEstimate& e) {
    const double work = e.particle_steps();
    if (work <= kMaxParticleSteps) return;  // NaN and inf fail this test too
    const std::string what = fmt::format(
        "this run would need about {:.2g} particle-steps ({:g} particles x {:.2g} steps of dt = "
        "{:.3g} over {:.3g} time units), more than {:g}: it could not finish",
        work, e.particles, e.steps(), e.dt, e.simulated_time, kMaxParticleSteps);
    const Params& ep = sc.engine_settings.params;
    switch (largest_excess(e)) {
        case Excess::StepsPerContact:
            if (ep.real("dt") > 0) {
                ep.fail("dt", fmt::format("{}; dt is t_c / {:.3g} (t_c = {:.3g}): raise engine.dt "
                                          "(at most t_c / 5; 0: dt_fraction x t_c)",
                                          what, e.contact_time / e.dt, e.contact_time));
            }
            ep.fail("dt_fraction",
                    fmt::format("{}; dt is t_c / {:.3g}: raise engine.dt_fraction (default 0.02, "
                                "50 steps per contact)",
                                what, e.contact_time / e.dt));
        case Excess::StiffContacts:
            throw SceneError(fmt::format(
                "{}: {}; contacts last t_c = {:.3g}, {:.2g} times less than a grain takes to move "
                "its diameter ({:.3g}): soften them (lower interactions.stiffness, or raise "
                "contact_time)",
                sc.interactions_location, what, e.contact_time, e.grain_time / e.contact_time,
                e.grain_time));
        case Excess::LongRun: {
            const bool equilibration = sc.schedule.equilibration > sc.schedule.measurement;
            sc.run_settings.fail(
                equilibration ? "equilibration" : "measurement",
                fmt::format("{}; the run lasts {:.2g} times what a grain takes to move its "
                            "diameter ({:.3g}): shorten run.{}",
                            what, e.simulated_time / e.grain_time, e.grain_time,
                            equilibration ? "equilibration" : "measurement"));
        }
        case Excess::Particles:
            throw SceneError(
                fmt::format("{}: {}; use fewer particles (the species' counts, or `particles`)",
                            sc.species_location, what));
    }
}

std::string describe(const DemEstimate& e) {
    return fmt::format(
        "expected cost: about {:.2g} particle-steps ({:g} particles x {:.2g} steps of dt = {:.3g}, "
        "t_c / {:.3g}), {:.3g} time units",
        e.particle_steps(), e.particles, e.steps(), e.dt, e.contact_time / e.dt, e.simulated_time);
}

RunCost run_cost(const DemEstimate& e) {
    return RunCost{e.particle_steps(), "particle-steps", e.particles, describe(e)};
}

}  // namespace gran
