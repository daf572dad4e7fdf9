// The event-driven engine as an engine plugin (`engine.type: event_driven`, the default): its
// numerical settings (the collapse guard), its check at load (a hard-particle form for every
// contact), and its runner: stops at the drivers' kicks and at collision counts (schedules in
// collisions per particle), watchdog windows of events.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "libgran/engines/event_driven/engine.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/run/event_driven_cost.hpp"
#include "libgran/run/initial_state.hpp"
#include "libgran/run/watchdog.hpp"

namespace gran {

namespace {

template <int D>
class EventDrivenView final : public EngineView<D> {
  public:
    explicit EventDrivenView(const EventDrivenEngine<D>& e) : e_(e) {}
    const char* engine_name() const override { return "event_driven"; }
    const Particles<D>& particles() const override { return e_.particles(); }
    std::uint32_t id(std::size_t k) const override { return e_.ids()[k]; }
    double now() const override { return e_.now(); }
    double species_inertia(std::uint32_t s) const override { return e_.species_inertia(s); }
    const Vec<D>& gravity() const override { return e_.gravity(); }
    std::uint64_t collisions() const override { return e_.counters().collisions; }
    const std::vector<std::uint64_t>& pair_collisions() const override {
        return e_.pair_collisions();
    }
    const std::array<std::uint64_t, 2 * D>& wall_hits() const override { return e_.wall_hits(); }
    const std::array<double, 2 * D>& wall_impulse() const override { return e_.wall_impulse(); }
    double wall_position(int code, double t) const override { return e_.wall_position(code, t); }

  private:
    const EventDrivenEngine<D>& e_;
};

// Forwards collisions to several subscribers.
template <int D>
class CollisionFanout final : public CollisionSink<D> {
  public:
    std::vector<CollisionSink<D>*> sinks;
    void on_collision(const CollisionRecord<D>& c) override {
        for (auto* s : sinks) s->on_collision(c);
    }
};

EngineSettings engine_settings(const Scene& sc) {
    EngineSettings s;
    s.tc_guard = sc.engine_settings.params.str("collapse_guard") == "tc";
    s.tc = sc.engine_settings.params.real("tc");
    s.gravity = sc.gravity;
    return s;
}

// A wall description on this engine: a sawtooth ramp is taken in its limit A -> 0 (every particle
// meets the wall moving into the gas at v0 = 2 A f, Barrat & Trizac 2002), the wall this engine
// was built for.
inline WallMotion event_driven_motion(const WallMotion& m) {
    if (m.kind == WallMotion::Kind::sawtooth_ramp) return WallMotion::sawtooth(std::abs(m.v0));
    return m;
}

template <int D>
class EventDrivenRunner final : public EngineRunner<D> {
  public:
    EventDrivenRunner(const Scene& sc, DriverList<D>& drivers, ObservableList<D>& observables)
        : drivers_(drivers),
          engine_(make_box<D>(sc), sc.species, sc.contacts, initial_particles<D>(sc),
                  engine_settings(sc)),
          view_(engine_),
          watchdog_(sc.watchdog),
          tc_(engine_settings(sc).tc_guard ? engine_settings(sc).tc : 0.0),
          species_(&sc.species) {
        for (const auto& d : sc.drivers) driver_names_.push_back(d.name);
        for (auto& d : drivers) {
            for (const WallSpec<D>& w : d->walls()) {
                engine_.set_wall(w.axis, w.side, event_driven_motion(w.motion),
                                 sc.contacts.wall_named(w.partner), w.reflection);
            }
        }
        for (auto& d : drivers) d->observe(view_);
        for (auto& o : observables) {
            if (auto* s = o->collision_sink()) fanout_.sinks.push_back(s);
        }
        if (fanout_.sinks.size() == 1) engine_.set_collision_sink(fanout_.sinks[0]);
        if (fanout_.sinks.size() > 1) engine_.set_collision_sink(&fanout_);
    }

    const char* work_unit() const override { return "events"; }
    const EngineView<D>& view() const override { return view_; }
    double now() const override { return engine_.now(); }
    std::uint64_t collisions() const override { return engine_.counters().collisions; }
    // Events, and particle updates of the drivers' kicks (a kick touches every particle): a scene
    // whose only events are kicks (one particle and a thermostat) still does work, so chunks of
    // work end (the kicks are counted as the cost estimate counts them).
    std::uint64_t work() const override { return engine_.counters().events + kick_updates_; }
    // Observables read positions and velocities at now() (under gravity velocities change in free
    // flight too).
    void synchronize() override { engine_.synchronize(); }
    const std::string& failure() const override { return failure_; }

    Advance advance(double t_target, std::uint64_t c_target, std::uint64_t w_target,
                    const std::atomic<bool>* interrupt) override {
        while (true) {
            double t_kick = kInf;
            for (auto& d : drivers_) t_kick = std::min(t_kick, d->next_kick());
            const double t_stop = std::min(t_target, t_kick);
            if (work() >= w_target) return Advance::Reached;
            const std::uint64_t window = next_check();
            const auto stop = engine_.advance(t_stop, c_target, interrupt,
                                              std::min(window, w_target - kick_updates_));
            using Stop = typename EventDrivenEngine<D>::Stop;
            if (stop == Stop::Interrupted) return Advance::Interrupted;
            if (stop == Stop::EventLimit) {
                if (work() >= w_target) return Advance::Reached;
                if (!check_window()) return Advance::Watchdog;
                continue;
            }
            if (stop == Stop::NoEvents) {
                spdlog::warn("no more events (all particles at rest?): stopping the run early");
                return Advance::Stalled;
            }
            if (stop == Stop::CollisionLimit) return Advance::Reached;
            // Time limit: the kicks that are due; stop when the sample time is reached.
            for (std::size_t k = 0; k < drivers_.size(); ++k) {
                Driver<D>& d = *drivers_[k];
                if (d.next_kick() > engine_.now()) continue;
                const double at = engine_.now();
                engine_.synchronize();
                d.kick(engine_.particles_for_update(), *species_);
                // Every event is predicted again at the next kick: none later is looked for.
                double next = kInf;
                for (auto& other : drivers_) next = std::min(next, other->next_kick());
                engine_.velocities_changed(next);
                kick_updates_ += engine_.particles().size();
                if (!(d.next_kick() > at)) {  // the time would never advance again
                    failure_ = fmt::format(
                        "driver '{}': its next kick is not after t = {:.17g} (an interval below "
                        "the resolution of the time there): increase drivers[{}].interval",
                        driver_names_[k], at, k);
                    return Advance::Watchdog;
                }
            }
            if (engine_.now() >= t_target) return Advance::Reached;
        }
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("event_driven runner");
        ar.io(engine_);
        ar.io(kick_updates_);
        ar.io(window_start_events_);
        ar.io(window_start_time_);
        ar.io(reference_rate_);
        ar.io(failure_);
    }

    void write_performance(ResultGroup& perf, double cpu) const override {
        const auto& c = engine_.counters();
        const double n = double(engine_.particles().size());
        perf.text("engine", "event_driven");
        perf.value("events", c.events);
        perf.value("collisions", c.collisions);
        perf.value("events_per_second", double(c.events) / std::max(cpu, 1e-9));
        perf.value("collisions_per_second", double(c.collisions) / std::max(cpu, 1e-9));
        perf.value("collisions_per_particle", 2.0 * double(c.collisions) / n);
        perf.value("tc_guard_collisions", c.tc_collisions);
        perf.value("overlap_collisions", c.overlap_collisions);
        perf.value("full_reschedules", c.full_reschedules);
        if (c.full_reschedules > 0 && c.collisions > 0) {
            perf.value("reschedules_per_collision_per_particle",
                       double(c.full_reschedules) * n / (2.0 * double(c.collisions)));
        }
        ResultGroup detail = perf.file_only();
        detail.value("cell_crossings", c.cell_crossings);
        detail.value("wall_hits", c.wall_hits);
        detail.value("stale_events", c.stale_events);
        if (engine_.neighbour_skin() > 0.0) {
            // Dense gases find their pairs through neighbour shells (neighbour_shells.hpp).
            perf.value("neighbour_skin", engine_.neighbour_skin());
            detail.value("shell_exits", c.shell_exits);
            detail.value("periodic_wraps", c.wraps);
        }
    }

  private:
    std::uint64_t next_check() const {
        return watchdog_.enabled ? window_start_events_ + watchdog_.window : UINT64_MAX;
    }
    // Watchdog, once per window of events: progress of the simulated time, and a finite state
    // (positions are lazy, at each particle's own clock, but a NaN stays a NaN).
    bool check_window() {
        ProgressWindow w;
        w.events = engine_.counters().events - window_start_events_;
        w.t_begin = window_start_time_;
        w.t_end = engine_.now();
        w.particles = engine_.particles().size();
        w.reference_rate = reference_rate_;
        w.tc = tc_;
        failure_ = check_progress(watchdog_, w);
        if (failure_.empty()) failure_ = check_finite<D>(view_, *species_);
        if (reference_rate_ == 0) reference_rate_ = event_rate(w);
        window_start_events_ = engine_.counters().events;
        window_start_time_ = engine_.now();
        return failure_.empty();
    }

    DriverList<D>& drivers_;
    std::vector<std::string> driver_names_;
    CollisionFanout<D> fanout_;
    EventDrivenEngine<D> engine_;
    EventDrivenView<D> view_;
    WatchdogSettings watchdog_;
    double tc_;  // TC window, 0 with the guard off
    const SpeciesTable* species_;
    std::uint64_t kick_updates_ = 0;  // particles x kicks
    std::uint64_t window_start_events_ = 0;
    double window_start_time_ = 0;
    double reference_rate_ = 0;
    std::string failure_;
};

// Every contact needs a hard-particle form (a hard-sphere law, or a soft law's hard limit).
void check_event_driven(const Scene& sc, const EngineDemands& demands) {
    refuse_endless_run(sc, estimate_events(sc, demands));
    const ContactTable& c = sc.contacts;
    const auto& hard = c.law->hard_sphere;
    if (!hard) {
        throw SceneError(fmt::format(
            "{}: law '{}' has no hard-particle form for the event_driven engine (`gran list laws`)",
            sc.interactions_location, c.law->name));
    }
    if (!hard->problem) return;
    const std::size_t contacts = c.species * c.species + c.walls.size() * c.species;
    for (std::size_t k = 0; k < contacts; ++k) {
        if (const char* why = hard->problem(hard->pair_at(*c.table, k))) {
            throw SceneError(sc.interactions_location + ": " + why);
        }
    }
}

const bool registered = EngineRegistry::instance().add([] {
    EnginePlugin p;
    p.name = "event_driven";
    p.summary =
        "hard particles with instantaneous collisions, exact between events (Barrat & Trizac "
        "2002; McNamara & Falcon 2005)";
    p.schema = {choice("collapse_guard", "tc", {"tc", "none"},
                       "inelastic-collapse guard: TC model (collisions within tc of a previous "
                       "one are elastic)"),
                real("tc", "1e-6", "time", "TC-model time window", 0, 1e308)};
    p.description = R"md(
Hard particles, exact between events (per-particle clocks, cell lists, one pending event per
particle): collisions are instantaneous, with the restitution of the contact's law (a
hard-particle law, or a soft-contact law's hard limit when frictionless). Gravity makes free flight
parabolic; moving walls are met exactly; a sawtooth ramp is taken in its limit A -> 0. The
`collapse_guard: tc` is the TC model (Luding & McNamara 1998): a collision within `tc` of a
previous collision of either partner (or a wall hit within `tc` of one) is elastic; such
collisions are counted in `/performance/tc_guard_collisions`. A particle resting on a floor under
gravity makes micro-bounces of period 2 tc (docs/physics.md); the watchdog stops runs made of
them.)md";
    p.binary_collisions = true;
    p.check = check_event_driven;
    p.estimate = [](const Scene& sc, const EngineDemands& demands) {
        const EventEstimate e = estimate_events(sc, demands);
        return RunCost{e.events(), "events", 1, describe(e)};
    };
    set_runner<EventDrivenRunner>(p);
    return p;
}());

}  // namespace

}  // namespace gran
