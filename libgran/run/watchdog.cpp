#include "libgran/run/watchdog.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <type_traits>

namespace gran {

double event_rate(const ProgressWindow& w) {
    const double dt = w.t_end - w.t_begin;
    if (!(dt > 0)) return std::numeric_limits<double>::infinity();
    return double(w.events) / (double(w.particles) * dt);
}

std::string check_progress(const WatchdogSettings& s, const ProgressWindow& w) {
    if (!s.enabled || w.events == 0) return "";
    const double dt = w.t_end - w.t_begin;
    // Stall: not one representable step of simulated time in a whole window.
    if (!(dt > 0)) {
        return fmt::format(
            "watchdog: simulated time stopped advancing at t = {:.10g}: the last {} events left it "
            "unchanged (inelastic collapse without a guard, or particles trapped in a zero-time "
            "loop). Keep the TC model on (engine.collapse_guard: tc) or raise engine.tc, lower the "
            "dissipation (interactions.alpha), or use engine.type: dem; the check runs every "
            "run.watchdog.window = {} events (run.watchdog.enabled: false turns it off)",
            w.t_end, w.events, s.window);
    }
    const double rate = event_rate(w);
    // TC regime: more than max_events_per_tc events per particle within one TC window.
    if (w.tc > 0 && rate * w.tc > s.max_events_per_tc) {
        return fmt::format(
            "watchdog: the TC model's micro-collisions dominate at t = {:.10g}: {:.3g} events per "
            "particle per unit time, {:.3g} per TC window engine.tc = {:g} (limit "
            "run.watchdog.max_events_per_tc = {:g}). Grains resting on each other or on a floor "
            "(a bed at rest under gravity) or a collapsing cluster are being resolved by "
            "collisions every ~tc, which the event-driven engine follows only at about 1/tc "
            "events per particle per unit time: use engine.type: dem for beds at rest, drive "
            "harder, lower the dissipation, or raise run.watchdog.max_events_per_tc to go on",
            w.t_end, rate, rate * w.tc, w.tc, s.max_events_per_tc);
    }
    // Collapse: the rate grew by more than max_rate_growth over the first window's.
    if (w.reference_rate > 0 && rate > s.max_rate_growth * w.reference_rate) {
        return fmt::format(
            "watchdog: the event rate exploded at t = {:.10g}: {:.3g} events per particle per "
            "unit time over the last {} events, {:.3g} times the {:.3g} of the run's first "
            "window (limit run.watchdog.max_rate_growth = {:g}): inelastic collapse. Keep the "
            "TC model on (engine.collapse_guard: tc) or raise engine.tc, lower the dissipation, "
            "or raise run.watchdog.max_rate_growth if this growth is physical",
            w.t_end, rate, w.events, rate / w.reference_rate, w.reference_rate, s.max_rate_growth);
    }
    return "";
}

namespace {
template <class T>
bool finite(const T& x) {
    if constexpr (std::is_floating_point_v<T>) {
        return std::isfinite(x);
    } else {
        return x.allFinite();
    }
}
}  // namespace

template <int D>
std::string check_finite(const EngineView<D>& view, const SpeciesTable& species) {
    const Particles<D>& p = view.particles();
    const auto advice =
        "the integration broke down. Check the time step (engine.dt, engine.dt_fraction) against "
        "the contact stiffness, and masses, diameters, gravity and driving for zeros or extreme "
        "values; the result holds what was measured before";
    double energy = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
        energy += species.species[p.species[k]].mass * p.v[k].squaredNorm();
        const char* what = nullptr;
        if (!finite(p.r[k])) {
            what = "position";
        } else if (!finite(p.v[k])) {
            what = "velocity";
        } else if (p.rotating() && !finite(p.w[k])) {
            what = "angular velocity";
        }
        if (!what) continue;
        return fmt::format(
            "watchdog: particle {} has a non-finite {} at t = {:.10g} ({} engine): {}", view.id(k),
            what, view.now(), view.engine_name(), advice);
    }
    if (!std::isfinite(energy)) {
        return fmt::format("watchdog: the kinetic energy overflowed at t = {:.10g} ({} engine): {}",
                           view.now(), view.engine_name(), advice);
    }
    return "";
}

template std::string check_finite<2>(const EngineView<2>&, const SpeciesTable&);
template std::string check_finite<3>(const EngineView<3>&, const SpeciesTable&);

}  // namespace gran
