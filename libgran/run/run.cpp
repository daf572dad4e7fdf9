#include "libgran/run/run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "libgran/plugins/driver.hpp"
#include "libgran/engines/dem/probe.hpp"
#include "libgran/engines/engine_view.hpp"
#include "libgran/run/equilibration.hpp"
#include "libgran/core/h5.hpp"
#include "libgran/scene/placement.hpp"
#include "libgran/run/watchdog.hpp"
#include "libgran/plugins/observable.hpp"

namespace gran {

namespace {

template <int D>
Box<D> make_box(const Scene& sc) {
    Box<D> box;
    for (int a = 0; a < D; ++a) {
        box.length[a] = sc.box_length[std::size_t(a)];
        box.periodic[std::size_t(a)] = sc.periodic[std::size_t(a)];
    }
    return box;
}

template <int D>
Particles<D> initial_particles(const Scene& sc) {
    const Box<D> box = make_box<D>(sc);
    Rng rng = make_rng(sc.seed, Stream::Placement);
    Particles<D> p;
    try {
        p = sc.placement == "lattice"        ? place_lattice<D>(box, sc.species, rng)
            : sc.placement == "close_packed" ? place_close_packed<D>(box, sc.species, rng)
                                             : place_random<D>(box, sc.species, rng);
    } catch (const PlacementError& e) {
        throw SceneError(sc.box_location + ": " + e.what());
    }
    Rng vrng = make_rng(sc.seed, Stream::Velocities);
    maxwellian_velocities<D>(p, sc.species, sc.temperature, vrng);
    return p;
}

// Forwards collisions to several subscribers.
template <int D>
class CollisionFanout final : public CollisionSink<D> {
  public:
    std::vector<CollisionSink<D>*> sinks;
    void on_collision(const CollisionRecord<D>& c) override {
        for (auto* s : sinks) s->on_collision(c);
    }
};

class Progress {
  public:
    Progress(const RunOptions& o, double log_interval, const char* unit)
        : opt_(o), log_interval_(log_interval), unit_(unit) {
        start_ = Clock::now();
        last_log_ = start_;
    }
    void update(const char* phase, double fraction, std::uint64_t events, bool force = false) {
        if (!opt_.progress) return;
        const auto now = Clock::now();
        const double since = std::chrono::duration<double>(now - last_draw_).count();
        if (!force && opt_.terminal && since < 0.2) return;
        if (!force && !opt_.terminal &&
            std::chrono::duration<double>(now - last_log_).count() < log_interval_)
            return;
        last_draw_ = now;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const double rate = elapsed > 0 ? double(events) / elapsed : 0;
        const double eta = fraction > 1e-9 ? elapsed * (1 - fraction) / fraction : 0;
        const std::string line =
            fmt::format("{:<13} {:5.1f}%  elapsed {:.0f}s  ETA {:.0f}s  {:.3g} {}/s", phase,
                        100 * fraction, elapsed, eta, rate, unit_);
        if (opt_.terminal) {
            std::fprintf(stderr, "\r%s   ", line.c_str());
            std::fflush(stderr);
            drawn_ = true;
        } else {
            spdlog::info("{}", line);
            last_log_ = now;
        }
    }
    void finish() {
        if (drawn_) std::fprintf(stderr, "\n");
    }
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  private:
    using Clock = std::chrono::steady_clock;
    const RunOptions& opt_;
    double log_interval_;
    const char* unit_;
    Clock::time_point start_, last_draw_{}, last_log_;
    bool drawn_ = false;
};

std::string summary_path_for(const std::string& out) {
    std::filesystem::path p(out);
    p.replace_extension(".summary.yaml");
    return p.string();
}

template <int D>
std::pair<std::vector<std::unique_ptr<Driver<D>>>, std::vector<std::unique_ptr<Observable<D>>>>
make_plugins(const Scene& sc) {
    SceneInfo info;
    info.dimension = D;
    info.seed = sc.seed;
    info.species = &sc.species;
    info.box_length = sc.box_length;
    info.periodic = sc.periodic;
    info.initial_temperature = sc.temperature;
    info.gravity = sc.engine.gravity;
    info.engine = sc.engine_type;
    std::vector<std::unique_ptr<Driver<D>>> drivers;
    for (std::size_t k = 0; k < sc.drivers.size(); ++k) {
        info.index = k;
        drivers.push_back(Registry<Driver>::instance()
                              .find(sc.drivers[k].type)
                              ->template make<D>(sc.drivers[k].params, info));
    }
    for (const auto& d : drivers) {
        if (d->peak_velocity() > info.peak_velocity) {
            info.peak_velocity = d->peak_velocity();
            info.drive_period = d->drive_period();
        }
    }
    std::vector<std::unique_ptr<Observable<D>>> observables;
    for (std::size_t k = 0; k < sc.observables.size(); ++k) {
        info.index = k;
        observables.push_back(Registry<Observable>::instance()
                                  .find(sc.observables[k].type)
                                  ->template make<D>(sc.observables[k].params, info));
    }
    return {std::move(drivers), std::move(observables)};
}

// Watchdog: stopped with a reason (runner.failure()), see libgran/watchdog.hpp.
enum class Advance { Reached, Interrupted, Stalled, Watchdog };

template <int D>
using DriverList = std::vector<std::unique_ptr<Driver<D>>>;
template <int D>
using ObservableList = std::vector<std::unique_ptr<Observable<D>>>;

// The event-driven engine in the run loop: stops at driver events (thermostat kicks) and at
// collision counts (schedules in collisions per particle).
template <int D>
class EventDrivenRunner {
  public:
    static constexpr const char* kWorkUnit = "events";

    EventDrivenRunner(const Scene& sc, DriverList<D>& drivers, ObservableList<D>& observables)
        : drivers_(drivers),
          engine_(make_box<D>(sc), sc.species, initial_particles<D>(sc), sc.engine),
          view_(engine_),
          watchdog_(sc.watchdog),
          tc_(sc.engine.tc_guard ? sc.engine.tc : 0.0),
          species_(&sc.species) {
        for (auto& d : drivers) d->attach(engine_);
        for (auto& o : observables) {
            if (auto* s = o->collision_sink()) fanout_.sinks.push_back(s);
        }
        if (fanout_.sinks.size() == 1) engine_.set_collision_sink(fanout_.sinks[0]);
        if (fanout_.sinks.size() > 1) engine_.set_collision_sink(&fanout_);
    }

    const EngineView<D>& view() const { return view_; }
    double now() const { return engine_.now(); }
    std::uint64_t collisions() const { return engine_.counters().collisions; }
    std::uint64_t work() const { return engine_.counters().events; }

    Advance advance(double t_target, std::uint64_t c_target, const std::atomic<bool>* interrupt) {
        while (true) {
            double t_driver = kInf;
            for (auto& d : drivers_) t_driver = std::min(t_driver, d->next_time());
            const double t_stop = std::min(t_target, t_driver);
            const auto stop = engine_.advance(t_stop, c_target, interrupt, next_check());
            using Stop = typename EventDrivenEngine<D>::Stop;
            if (stop == Stop::Interrupted) return Advance::Interrupted;
            if (stop == Stop::EventLimit) {
                if (!check_window()) return Advance::Watchdog;
                continue;
            }
            if (stop == Stop::NoEvents) {
                spdlog::warn("no more events (all particles at rest?): stopping the run early");
                return Advance::Stalled;
            }
            if (stop == Stop::CollisionLimit) return Advance::Reached;
            // Time limit: fire the drivers that are due; stop when the sample time is reached.
            for (auto& d : drivers_) {
                if (d->next_time() <= engine_.now()) {
                    engine_.synchronize();
                    d->fire(engine_);
                }
            }
            if (engine_.now() >= t_target) return Advance::Reached;
        }
    }
    // Observables read positions and velocities at now() (under gravity velocities change in free
    // flight too).
    void synchronize() { engine_.synchronize(); }
    const std::string& failure() const { return failure_; }

    void write_performance(h5::Group& perf, YAML::Node& ps, double cpu) const {
        const auto& c = engine_.counters();
        const double n = double(engine_.particles().size());
        perf.attr("engine", "event_driven");
        perf.write_scalar("events", static_cast<std::int64_t>(c.events));
        perf.write_scalar("collisions", static_cast<std::int64_t>(c.collisions));
        perf.write_scalar("events_per_second", double(c.events) / std::max(cpu, 1e-9));
        perf.write_scalar("collisions_per_second", double(c.collisions) / std::max(cpu, 1e-9));
        perf.write_scalar("cell_crossings", static_cast<std::int64_t>(c.cell_crossings));
        perf.write_scalar("wall_hits", static_cast<std::int64_t>(c.wall_hits));
        perf.write_scalar("stale_events", static_cast<std::int64_t>(c.stale_events));
        perf.write_scalar("tc_guard_collisions", static_cast<std::int64_t>(c.tc_collisions));
        perf.write_scalar("overlap_collisions", static_cast<std::int64_t>(c.overlap_collisions));
        perf.write_scalar("full_reschedules", static_cast<std::int64_t>(c.full_reschedules));
        perf.write_scalar("collisions_per_particle", 2.0 * double(c.collisions) / n);
        ps["engine"] = "event_driven";
        ps["events"] = c.events;
        ps["collisions"] = c.collisions;
        ps["events_per_second"] = double(c.events) / std::max(cpu, 1e-9);
        ps["collisions_per_second"] = double(c.collisions) / std::max(cpu, 1e-9);
        ps["collisions_per_particle"] = 2.0 * double(c.collisions) / n;
        ps["tc_guard_collisions"] = c.tc_collisions;
        ps["overlap_collisions"] = c.overlap_collisions;
        ps["full_reschedules"] = c.full_reschedules;
        if (c.full_reschedules > 0 && c.collisions > 0) {
            ps["reschedules_per_collision_per_particle"] =
                double(c.full_reschedules) * n / (2.0 * double(c.collisions));
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
    CollisionFanout<D> fanout_;
    EventDrivenEngine<D> engine_;
    EventDrivenView<D> view_;
    WatchdogSettings watchdog_;
    double tc_;  // TC window, 0 with the guard off
    const SpeciesTable* species_;
    std::uint64_t window_start_events_ = 0;
    double window_start_time_ = 0;
    double reference_rate_ = 0;
    std::string failure_;
};

// engine.type: dem. Grain-grain restitution per species pair from the pair laws (alpha).
inline DemContactTable dem_contact_table(const Scene& sc) {
    const std::size_t ns = sc.species.size();
    DemContactSpec pair = sc.dem.pair;
    pair.e = sc.species.pair(0, 0).alpha;
    try {
        DemContactTable table(sc.species, sc.dem.law, pair, sc.dem.wall);
        for (std::size_t a = 0; a < ns; ++a) {
            for (std::size_t b = a; b < ns; ++b) {
                DemContactSpec s = sc.dem.pair;
                s.e = sc.species.pair(a, b).alpha;
                table.set_pair(a, b, s);
            }
        }
        return table;
    } catch (const std::invalid_argument& e) {
        throw SceneError(sc.engine_location + ": " + e.what());
    }
}

// More steps than any run can take (1e14 steps of one particle: ~100 days at 1e7 steps/s).
constexpr double kMaxDemSteps = 1e14;

// The soft-sphere DEM engine in the run loop: whole time steps up to each sample; walls come from
// the wall drivers; no collision records (observables that need them are refused).
template <int D>
class DemRunner {
  public:
    static constexpr const char* kWorkUnit = "steps";

    DemRunner(const Scene& sc, DriverList<D>& drivers, ObservableList<D>& observables)
        : sc_(sc),
          table_(dem_contact_table(sc)),
          engine_(make_engine(sc, table_)),
          view_(engine_),
          watchdog_(sc.watchdog) {
        // A time step so short that the schedule cannot be stepped through in any run time (e.g.
        // springs stiff enough to make t_c ~ 1e-150): refused rather than left to "hang".
        const double steps = (sc.schedule.equilibration + sc.schedule.measurement) / engine_.dt();
        if (steps > kMaxDemSteps) {
            throw SceneError(fmt::format(
                "{}: dt = {:.4g} would need {:.3g} steps for the run's {:g} time units (more than "
                "{:g}: months of computing even for one grain): lower engine.stiffness (or raise "
                "engine.contact_time) "
                "or shorten the run",
                sc.engine_location, engine_.dt(), steps,
                sc.schedule.equilibration + sc.schedule.measurement, kMaxDemSteps));
        }
        for (std::size_t k = 0; k < drivers.size(); ++k) {
            const std::string why = drivers[k]->attach(engine_);
            if (!why.empty()) sc.drivers[k].params.fail(drivers[k]->dem_refusal_key(), why);
        }
        for (std::size_t k = 0; k < observables.size(); ++k) {
            if (observables[k]->collision_sink()) {
                sc.observables[k].params.fail(
                    "type",
                    "this observable (with these options) needs the binary collision "
                    "records of the event_driven engine; the dem engine has contacts of "
                    "finite duration");
            }
        }
    }

    const EngineView<D>& view() const { return view_; }
    double now() const { return engine_.now(); }
    std::uint64_t collisions() const { return engine_.counters().contacts; }
    std::uint64_t work() const { return engine_.counters().steps; }
    const DemEngine<D>& engine() const { return engine_; }

    Advance advance(double t_target, std::uint64_t, const std::atomic<bool>* interrupt) {
        if (!watchdog_.enabled) {
            const auto stop = engine_.advance(t_target, interrupt);
            return stop == DemEngine<D>::Stop::Interrupted ? Advance::Interrupted
                                                           : Advance::Reached;
        }
        // Watchdog: chunks of `window` whole steps (the same steps as one advance), each followed
        // by a finiteness check. Time cannot stall here: now() = t0 + steps dt with dt > 0.
        while (engine_.now() < t_target) {
            const double chunk_end =
                engine_.now() + (double(watchdog_.window) - 0.5) * engine_.dt();
            const auto stop = engine_.advance(std::min(t_target, chunk_end), interrupt);
            if (stop == DemEngine<D>::Stop::Interrupted) return Advance::Interrupted;
            failure_ = check_finite<D>(view_, sc_.species);
            if (!failure_.empty()) return Advance::Watchdog;
        }
        return Advance::Reached;
    }
    void synchronize() {}  // the state is always at now()
    const std::string& failure() const { return failure_; }

    void write_performance(h5::Group& perf, YAML::Node& ps, double cpu) const {
        const auto& c = engine_.counters();
        const double n = double(engine_.particles().size());
        const double psteps = double(c.steps) * n / std::max(cpu, 1e-9);
        perf.attr("engine", "dem");
        perf.write_scalar("steps", static_cast<std::int64_t>(c.steps));
        perf.write_scalar("particle_steps_per_second", psteps);
        perf.write_scalar("dt", engine_.dt());
        perf.write_scalar("contacts", static_cast<std::int64_t>(c.contacts));
        perf.write_scalar("wall_contacts", static_cast<std::int64_t>(c.wall_contacts));
        perf.write_scalar("active_contacts", static_cast<std::int64_t>(c.active_contacts));
        perf.write_scalar("neighbour_list_builds", static_cast<std::int64_t>(c.rebuilds));
        perf.write_scalar("max_overlap", c.max_overlap);
        perf.attr_on("max_overlap", "unit", "contact distance");
        ps["engine"] = "dem";
        ps["steps"] = c.steps;
        ps["particle_steps_per_second"] = psteps;
        ps["dt"] = engine_.dt();
        ps["contacts"] = c.contacts;
        ps["wall_contacts"] = c.wall_contacts;
        ps["neighbour_list_builds"] = c.rebuilds;
        ps["max_overlap"] = c.max_overlap;
        // What the run's contacts achieve: isolated head-on collisions on this engine, same law,
        // parameters and dt, at the reference speed.
        const double v = sc_.dem.probe_speed;
        const std::size_t ns = sc_.species.size();
        double worst_dt_over_tc = 0;
        YAML::Node iso;
        auto report = [&](const std::string& name, const DemProbeResult& r) {
            h5::Group g = perf.group("isolated_collisions/" + name);
            g.write_scalar("requested_restitution", r.requested_restitution);
            g.write_scalar("restitution", r.restitution);
            g.write_scalar("contact_time", r.closed_form_duration);
            g.write_scalar("measured_contact_time", r.duration);
            g.write_scalar("dt_over_tc", r.dt_over_tc);
            YAML::Node y;
            y["requested_restitution"] = r.requested_restitution;
            y["restitution"] = r.restitution;
            y["contact_time"] = r.closed_form_duration;
            y["measured_contact_time"] = r.duration;
            y["dt_over_tc"] = r.dt_over_tc;
            iso[name] = y;
            worst_dt_over_tc = std::max(worst_dt_over_tc, r.dt_over_tc);
        };
        try {
            for (std::size_t a = 0; a < ns; ++a) {
                for (std::size_t b = a; b < ns; ++b) {
                    report(sc_.species.species[a].name + "-" + sc_.species.species[b].name,
                           probe_pair_collision<D>(sc_.species, table_, a, b, v, engine_.dt()));
                }
            }
            std::vector<double> wall_e;
            for (int code = 0; code < 2 * D; ++code) {
                if (!engine_.wall_is_set(code / 2, code % 2)) continue;
                const double e = engine_.wall_contact(code, 0).restitution;
                if (std::find(wall_e.begin(), wall_e.end(), e) != wall_e.end()) continue;
                wall_e.push_back(e);
                for (std::size_t s = 0; s < ns; ++s) {
                    report(fmt::format("{}-wall_e{:g}", sc_.species.species[s].name, e),
                           probe_wall_collision<D>(sc_.species, table_, s, e, v, engine_.dt()));
                }
            }
        } catch (const std::exception& e) {
            spdlog::warn("isolated-collision check failed: {}", e.what());
        }
        perf.write_scalar("dt_over_tc", worst_dt_over_tc);
        ps["dt_over_tc"] = worst_dt_over_tc;
        ps["isolated_collisions"] = iso;
    }

  private:
    static DemEngine<D> make_engine(const Scene& sc, const DemContactTable& table) {
        DemSettings s = sc.dem.settings;
        s.gravity = sc.engine.gravity;
        try {
            return DemEngine<D>(make_box<D>(sc), sc.species, table, initial_particles<D>(sc), s);
        } catch (const std::invalid_argument& e) {
            throw SceneError(sc.engine_location + ": " + e.what());
        }
    }

    const Scene& sc_;
    DemContactTable table_;
    DemEngine<D> engine_;
    DemView<D> view_;
    WatchdogSettings watchdog_;
    std::string failure_;
};

template <int D, class Runner>
RunReport run_with(const Scene& sc, const RunOptions& opt, DriverList<D>& drivers,
                   ObservableList<D>& observables) {
    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;
    Runner runner(sc, drivers, observables);
    const EngineView<D>& view = runner.view();

    const std::size_t n = view.particles().size();
    const auto& s = sc.schedule;
    const bool by_time = s.unit == ScheduleUnit::Time;
    auto coll_of = [&](double cpp) {
        return static_cast<std::uint64_t>(std::llround(cpp * double(n) / 2.0));
    };
    const std::size_t expected_samples =
        static_cast<std::size_t>(std::floor(s.measurement / s.sample_interval + 1e-9));

    // Trajectory frames (equally spaced over the measurement samples).
    std::vector<double> frame_time;
    std::vector<double> frame_pos, frame_vel;
    std::size_t frame_every =
        sc.frames > 0 ? std::max<std::size_t>(1, expected_samples / sc.frames) : 0;

    Progress progress(opt, sc.progress_interval, Runner::kWorkUnit);
    bool interrupted = false;
    bool stalled = false;
    std::string watchdog_stop;  // why the watchdog stopped the run (empty: it did not)
    std::size_t samples_taken = 0;
    std::vector<double> measured_energy;  // per measurement sample, for the warm-up check
    measured_energy.reserve(expected_samples);
    double t_measure_start = 0;
    std::uint64_t coll_measure_start = 0;

    for (int phase = 0; phase < 2 && !interrupted && !stalled; ++phase) {
        const bool measuring = phase == 1;
        const double length = measuring ? s.measurement : s.equilibration;
        if (length <= 0) continue;
        const double t0 = runner.now();
        const std::uint64_t c0 = runner.collisions();
        if (measuring) {
            t_measure_start = t0;
            coll_measure_start = c0;
        }
        const std::size_t nsamples =
            static_cast<std::size_t>(std::floor(length / s.sample_interval + 1e-9));
        for (std::size_t k = 1; k <= nsamples && !interrupted && !stalled; ++k) {
            const double t_target = by_time ? t0 + double(k) * s.sample_interval : kInf;
            const std::uint64_t c_target =
                by_time ? UINT64_MAX : c0 + coll_of(double(k) * s.sample_interval);
            const Advance adv = runner.advance(t_target, c_target, opt.interrupt);
            interrupted = adv == Advance::Interrupted;
            stalled = adv == Advance::Stalled || adv == Advance::Watchdog;
            if (adv == Advance::Watchdog) watchdog_stop = runner.failure();
            if (interrupted || stalled) break;
            runner.synchronize();
            if (sc.watchdog.enabled) {
                watchdog_stop = check_finite<D>(view, sc.species);  // never sample a NaN
                stalled = !watchdog_stop.empty();
                if (stalled) break;
            }
            SampleContext<D> ctx{runner.now(), measuring, expected_samples, view, sc.species};
            for (auto& o : observables) o->sample(ctx);
            if (measuring) {
                ++samples_taken;
                measured_energy.push_back(view.kinetic_energy_per_particle(sc.species));
                if (frame_every && samples_taken % frame_every == 0 &&
                    frame_time.size() < sc.frames) {
                    frame_time.push_back(runner.now());
                    // Frames list particles by their original index (the engine may re-sort).
                    const std::size_t base = frame_pos.size();
                    frame_pos.resize(base + n * D);
                    frame_vel.resize(base + n * D);
                    const auto& p = view.particles();
                    for (std::size_t i = 0; i < n; ++i) {
                        const std::size_t at = base + std::size_t(view.id(i)) * D;
                        for (int a = 0; a < D; ++a) {
                            frame_pos[at + std::size_t(a)] = p.r[i][a];
                            frame_vel[at + std::size_t(a)] = p.v[i][a];
                        }
                    }
                }
            }
            const double done =
                (measuring ? s.equilibration : 0.0) + length * double(k) / double(nsamples);
            progress.update(measuring ? "measurement" : "equilibration",
                            done / (s.equilibration + s.measurement), runner.work());
        }
    }
    progress.finish();
    const double wall = progress.elapsed();
    const double cpu = double(std::clock()) / CLOCKS_PER_SEC - cpu0;
    if (interrupted) spdlog::warn("interrupted: writing what was measured so far");
    if (!watchdog_stop.empty()) spdlog::warn("watchdog: writing what was measured so far");

    // Write to a temporary file and rename: an existing result is never clobbered by a failed run.
    const auto parent = std::filesystem::path(opt.output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    const std::string part = opt.output + ".part";
    RunReport rep;
    rep.completed = !interrupted && !stalled;
    rep.error = watchdog_stop;
    rep.output = opt.output;
    rep.summary_file = summary_path_for(opt.output);
    YAML::Node summary;
    {
        h5::File file = h5::File::create(part);
        h5::Group root = file.root();
        h5::Group h5md = root.group("h5md");
        const std::vector<std::int64_t> version{1, 1};
        h5md.attr("version", std::span<const std::int64_t>(version));
        const char* user = std::getenv("USER");
        h5md.group("author").attr("name", user ? user : "gran user");
        h5::Group creator = h5md.group("creator");
        creator.attr("name", "gran");
        creator.attr("version", GRAN_VERSION);

        h5::Group par = root.group("parameters");
        YAML::Emitter em;
        em << sc.resolved;
        par.write_string("scene", em.c_str());
        par.attr("source_file", sc.file);
        par.attr("packing_fraction", sc.packing_fraction);
        std::string cmd;
        for (const auto& a : opt.command_line) cmd += (cmd.empty() ? "" : " ") + a;
        par.attr("command_line", cmd);
        par.attr("units", sc.units == "SI"
                              ? "SI: lengths in m, masses in kg, times in s, energies in J, "
                                "temperatures as energies (k_B = 1: J)"
                              : "reduced: lengths, masses and energies as given in the scene "
                                "(k_B = 1)");

        YAML::Node obs_summary;
        for (std::size_t k = 0; k < observables.size(); ++k) {
            h5::Group g = root.group("observables/" + sc.observables[k].name);
            g.attr("type", sc.observables[k].type);
            YAML::Node os;
            observables[k]->write(g, os);
            obs_summary[sc.observables[k].name] = os;
        }
        YAML::Node drv_summary;
        for (std::size_t k = 0; k < drivers.size(); ++k) {
            h5::Group g = root.group("drivers/" + sc.drivers[k].name);
            YAML::Node ds;
            drivers[k]->write(g, ds);
            drv_summary[sc.drivers[k].name] = ds;
        }

        const double measured_coll = double(runner.collisions() - coll_measure_start);
        h5::Group perf = root.group("performance");
        perf.write_scalar("wall_time", wall);
        perf.attr_on("wall_time", "unit", "s");
        perf.write_scalar("cpu_time", cpu);
        perf.attr_on("cpu_time", "unit", "s");
        YAML::Node ps;
        ps["wall_time_s"] = wall;
        ps["cpu_time_s"] = cpu;
        runner.write_performance(perf, ps, cpu);
        perf.write_scalar("final_time", runner.now());
        perf.write_scalar("measured_collisions_per_particle", 2.0 * measured_coll / double(n));
        perf.write_scalar("measured_time", runner.now() - t_measure_start);
        perf.write_scalar("samples", static_cast<std::int64_t>(samples_taken));
        perf.write_scalar("completed", static_cast<std::int64_t>(rep.completed ? 1 : 0));
        perf.write_scalar("interrupted", static_cast<std::int64_t>(interrupted ? 1 : 0));
        // Free cooling (no driver injecting energy) is not meant to be stationary.
        const bool driven = std::any_of(sc.drivers.begin(), sc.drivers.end(),
                                        [](const auto& d) { return d.type != "none"; });
        report_equilibration(check_equilibration(measured_energy), s, driven, perf, ps);
        if (!watchdog_stop.empty()) perf.attr("watchdog_stop", watchdog_stop);

        if (!frame_time.empty()) {
            h5::Group pg = root.group("particles/all");
            h5::Group bx = pg.group("box");
            bx.attr("dimension", static_cast<std::int64_t>(D));
            std::vector<std::string> boundary;
            for (int a = 0; a < D; ++a)
                boundary.push_back(sc.periodic[std::size_t(a)] ? "periodic" : "none");
            bx.attr("boundary", boundary);
            bx.write("edges", sc.box_length);
            const std::vector<std::size_t> shape{frame_time.size(), n, std::size_t(D)};
            std::vector<std::int64_t> steps(frame_time.size());
            for (std::size_t k = 0; k < steps.size(); ++k) steps[k] = std::int64_t(k);
            for (const char* what : {"position", "velocity"}) {
                h5::Group q = pg.group(what);
                q.write("value", std::string(what) == "position" ? frame_pos : frame_vel, shape);
                q.write("time", frame_time);
                q.write("step", steps);
            }
            std::vector<std::int64_t> spec(n);
            for (std::size_t i = 0; i < n; ++i) spec[view.id(i)] = view.particles().species[i];
            pg.write("species", spec);
        }

        summary["scene"] = sc.file;
        if (!sc.title.empty()) summary["title"] = sc.title;
        summary["result"] = opt.output;
        summary["status"] = interrupted              ? "interrupted"
                            : !watchdog_stop.empty() ? "stopped by the watchdog"
                            : stalled                ? "stopped: no more events"
                                                     : "completed";
        if (!watchdog_stop.empty()) summary["error"] = watchdog_stop;
        summary["dimension"] = D;
        summary["particles"] = n;
        summary["packing_fraction"] = sc.packing_fraction;
        summary["observables"] = obs_summary;
        if (drv_summary.size() > 0) summary["drivers"] = drv_summary;
        summary["performance"] = ps;
        file.close();
    }
    std::filesystem::rename(part, opt.output);
    {
        std::ofstream out(rep.summary_file);
        YAML::Emitter em;
        em << summary;
        out << "# gran run summary (values with one-standard-error bars)\n" << em.c_str() << "\n";
    }
    rep.summary = summary;
    return rep;
}

template <int D>
RunReport run_dim(const Scene& sc, const RunOptions& opt) {
    auto [drivers, observables] = make_plugins<D>(sc);
    if (sc.engine_type == "dem") return run_with<D, DemRunner<D>>(sc, opt, drivers, observables);
    return run_with<D, EventDrivenRunner<D>>(sc, opt, drivers, observables);
}

}  // namespace

namespace {
template <int D>
void check_dim(const Scene& sc) {
    auto [drivers, observables] = make_plugins<D>(sc);
    if (sc.engine_type == "dem") {
        // Builds the engine: the time step, contact parameters and wall drivers are checked.
        DemRunner<D> runner(sc, drivers, observables);
    } else {
        (void)initial_particles<D>(sc);
    }
}
}  // namespace

void check_scene(const Scene& scene) {
    if (scene.dimension == 2) {
        check_dim<2>(scene);
    } else {
        check_dim<3>(scene);
    }
}

RunReport run_scene(const Scene& scene, const RunOptions& options) {
    return scene.dimension == 2 ? run_dim<2>(scene, options) : run_dim<3>(scene, options);
}

}  // namespace gran
