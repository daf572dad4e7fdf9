#include "libgran/run/run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "libgran/engines/dem/probe.hpp"
#include "libgran/engines/engine_view.hpp"
#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/run/equilibration.hpp"
#include "libgran/run/frames.hpp"
#include "libgran/run/progress.hpp"
#include "libgran/run/result_file.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/watchdog.hpp"
#include "libgran/scene/placement.hpp"

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

    void write_performance(ResultGroup& perf, double cpu) const {
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

    void write_performance(ResultGroup& perf, double cpu) const {
        const auto& c = engine_.counters();
        const double n = double(engine_.particles().size());
        perf.text("engine", "dem");
        perf.value("steps", c.steps);
        perf.value("particle_steps_per_second", double(c.steps) * n / std::max(cpu, 1e-9));
        perf.value("dt", engine_.dt());
        perf.value("contacts", c.contacts);
        perf.value("wall_contacts", c.wall_contacts);
        perf.file_only().value("active_contacts", c.active_contacts);
        perf.value("neighbour_list_builds", c.rebuilds);
        perf.value("max_overlap", c.max_overlap, "contact distance");
        // What the run's contacts achieve: isolated head-on collisions on this engine, same law,
        // parameters and dt, at the reference speed.
        const double v = sc_.dem.probe_speed;
        const std::size_t ns = sc_.species.size();
        double worst_dt_over_tc = 0;
        auto report = [&](const std::string& name, const DemProbeResult& r) {
            ResultGroup g = perf.group("isolated_collisions").group(name);
            g.value("requested_restitution", r.requested_restitution);
            g.value("restitution", r.restitution);
            g.value("contact_time", r.closed_form_duration);
            g.value("measured_contact_time", r.duration);
            g.value("dt_over_tc", r.dt_over_tc);
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
        perf.value("dt_over_tc", worst_dt_over_tc);
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

// What the schedule did, for the result.
struct ScheduleOutcome {
    bool interrupted = false;
    bool stalled = false;                 // no more events, or the watchdog stopped the run
    std::string watchdog_stop;            // why the watchdog stopped the run (empty: it did not)
    std::size_t samples = 0;              // measurement samples taken
    std::vector<double> measured_energy;  // per measurement sample, for the warm-up check
    double t_measure_start = 0;
    std::uint64_t coll_measure_start = 0;
    bool stopped() const { return interrupted || stalled; }
    std::string status() const {
        return interrupted              ? "interrupted"
               : !watchdog_stop.empty() ? "stopped by the watchdog"
               : stalled                ? "stopped: no more events"
                                        : "completed";
    }
};

// Equilibration then measurement, each with samples at fixed intervals (of time or collisions per
// particle); at each sample the observables are sampled and frames appended to the result file.
template <int D, class Runner>
class ScheduleLoop {
  public:
    ScheduleLoop(const Scene& sc, const RunOptions& opt, Runner& runner,
                 ObservableList<D>& observables, ResultGroup root)
        : sc_(sc),
          opt_(opt),
          runner_(runner),
          observables_(observables),
          expected_samples_(samples_in(sc.schedule.measurement)),
          frames_(std::move(root), frame_box(sc), sc.frames, expected_samples_),
          progress_(opt.progress, opt.terminal, sc.progress_interval, Runner::kWorkUnit) {
        out_.measured_energy.reserve(expected_samples_);
    }

    ScheduleOutcome run() {
        for (int phase = 0; phase < 2 && !out_.stopped(); ++phase) run_phase(phase == 1);
        progress_.finish();
        return std::move(out_);
    }
    double elapsed() const { return progress_.elapsed(); }

  private:
    std::size_t samples_in(double length) const {
        return static_cast<std::size_t>(std::floor(length / sc_.schedule.sample_interval + 1e-9));
    }

    void run_phase(bool measuring) {
        const auto& s = sc_.schedule;
        const double length = measuring ? s.measurement : s.equilibration;
        if (length <= 0) return;
        const double t0 = runner_.now();
        const std::uint64_t c0 = runner_.collisions();
        if (measuring) {
            out_.t_measure_start = t0;
            out_.coll_measure_start = c0;
        }
        const std::size_t nsamples = samples_in(length);
        for (std::size_t k = 1; k <= nsamples; ++k) {
            if (!advance_to(t0, c0, k)) return;
            sample(measuring);
            const double done =
                (measuring ? s.equilibration : 0.0) + length * double(k) / double(nsamples);
            progress_.update(measuring ? "measurement" : "equilibration",
                             done / (s.equilibration + s.measurement), runner_.work());
        }
    }

    // To the k-th sample of a phase that started at time t0 with c0 collisions; false when the
    // run stops there (interrupt, no more events, watchdog).
    bool advance_to(double t0, std::uint64_t c0, std::size_t k) {
        const auto& s = sc_.schedule;
        const bool by_time = s.unit == ScheduleUnit::Time;
        const double at = double(k) * s.sample_interval;  // time, or collisions per particle
        const double n = double(runner_.view().particles().size());
        const double t_target = by_time ? t0 + at : kInf;
        const std::uint64_t c_target =
            by_time ? UINT64_MAX : c0 + static_cast<std::uint64_t>(std::llround(at * n / 2.0));
        const Advance adv = runner_.advance(t_target, c_target, opt_.interrupt);
        out_.interrupted = adv == Advance::Interrupted;
        out_.stalled = adv == Advance::Stalled || adv == Advance::Watchdog;
        if (adv == Advance::Watchdog) out_.watchdog_stop = runner_.failure();
        if (out_.stopped()) return false;
        runner_.synchronize();
        if (sc_.watchdog.enabled) {  // never sample a NaN
            out_.watchdog_stop = check_finite<D>(runner_.view(), sc_.species);
            out_.stalled = !out_.watchdog_stop.empty();
        }
        return !out_.stalled;
    }

    void sample(bool measuring) {
        const EngineView<D>& view = runner_.view();
        SampleContext<D> ctx{runner_.now(), measuring, expected_samples_, view, sc_.species};
        for (auto& o : observables_) o->sample(ctx);
        if (!measuring) return;
        ++out_.samples;
        out_.measured_energy.push_back(view.kinetic_energy_per_particle(sc_.species));
        if (frames_.due(out_.samples)) {
            frame_of<D>(view, positions_, velocities_, species_);
            frames_.append(runner_.now(), positions_, velocities_, species_);
        }
    }

    const Scene& sc_;
    const RunOptions& opt_;
    Runner& runner_;
    ObservableList<D>& observables_;
    std::size_t expected_samples_;
    FrameWriter frames_;
    Progress progress_;
    ScheduleOutcome out_;
    std::vector<double> positions_, velocities_;  // one frame, reused
    std::vector<std::int64_t> species_;
};

// /observables, /drivers and /performance (with the summary's observables, drivers, performance).
template <int D, class Runner>
void write_results(ResultGroup root, const Scene& sc, const Runner& runner,
                   const DriverList<D>& drivers, const ObservableList<D>& observables,
                   const ScheduleOutcome& out, const RunTotals& totals) {
    for (std::size_t k = 0; k < observables.size(); ++k) {
        ResultGroup g = root.group("observables").group(sc.observables[k].name);
        g.attr("type", sc.observables[k].type);
        observables[k]->write(g);
    }
    for (std::size_t k = 0; k < drivers.size(); ++k) {
        ResultGroup g = root.group("drivers").group(sc.drivers[k].name);
        drivers[k]->write(g);
    }
    ResultGroup perf = root.group("performance");
    write_run_performance(perf, totals);
    runner.write_performance(perf, totals.cpu_time);
    // Free cooling (no driver injecting energy) is not meant to be stationary.
    const bool driven = std::any_of(sc.drivers.begin(), sc.drivers.end(),
                                    [](const auto& d) { return d.type != "none"; });
    report_equilibration(check_equilibration(out.measured_energy), sc.schedule, driven, perf);
}

template <int D, class Runner>
RunReport run_with(const Scene& sc, const RunOptions& opt, DriverList<D>& drivers,
                   ObservableList<D>& observables) {
    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;
    Runner runner(sc, drivers, observables);
    // Created once the scene is known to run (the runner checked it): a failing run leaves the
    // .part file and never touches an earlier result.
    ResultSink sink(opt.output);
    write_provenance(sink.root(), sc, opt.command_line);
    ScheduleOutcome out;
    RunTotals totals;
    {
        ScheduleLoop<D, Runner> loop(sc, opt, runner, observables, sink.root());
        out = loop.run();
        totals.wall_time = loop.elapsed();
    }  // closes the frames
    totals.cpu_time = double(std::clock()) / CLOCKS_PER_SEC - cpu0;
    if (out.interrupted) spdlog::warn("interrupted: writing what was measured so far");
    if (!out.watchdog_stop.empty()) spdlog::warn("watchdog: writing what was measured so far");

    const std::size_t n = runner.view().particles().size();
    totals.final_time = runner.now();
    totals.measured_time = runner.now() - out.t_measure_start;
    totals.measured_collisions_per_particle =
        2.0 * double(runner.collisions() - out.coll_measure_start) / double(n);
    totals.samples = out.samples;
    totals.completed = !out.stopped();
    totals.interrupted = out.interrupted;
    totals.watchdog_stop = out.watchdog_stop;
    write_summary_header(sink.summary(), sc, opt.output, out.status(), out.watchdog_stop, n);
    write_results<D>(sink.root(), sc, runner, drivers, observables, out, totals);
    sink.finish();

    RunReport rep;
    rep.completed = totals.completed;
    rep.error = out.watchdog_stop;
    rep.output = opt.output;
    rep.summary_file = sink.summary_file();
    rep.summary = sink.summary();
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
