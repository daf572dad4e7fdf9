#include "libgran/run/run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "libgran/plugins/engine.hpp"
#include "libgran/run/equilibration.hpp"
#include "libgran/run/frames.hpp"
#include "libgran/run/initial_state.hpp"
#include "libgran/run/progress.hpp"
#include "libgran/run/result_file.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/run/watchdog.hpp"

namespace gran {

namespace {

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
template <int D>
class ScheduleLoop {
  public:
    ScheduleLoop(const Scene& sc, const RunOptions& opt, EngineRunner<D>& runner,
                 ObservableList<D>& observables, ResultGroup root)
        : sc_(sc),
          opt_(opt),
          runner_(runner),
          observables_(observables),
          expected_samples_(samples_in(sc.schedule.measurement)),
          frames_(std::move(root), frame_box(sc), sc.frames, expected_samples_),
          progress_(opt.progress, opt.terminal, sc.progress_interval, runner.work_unit()) {
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
            if (!advance_to(t0, c0, k, measuring)) return;
            sample(measuring);
            const double done =
                (measuring ? s.equilibration : 0.0) + length * double(k) / double(nsamples);
            progress_.update(measuring ? "measurement" : "equilibration",
                             done / (s.equilibration + s.measurement), runner_.work());
        }
    }

    // To the k-th sample of a phase that started at time t0 with c0 collisions; false when the
    // run stops there (interrupt, no more events, watchdog).
    bool advance_to(double t0, std::uint64_t c0, std::size_t k, bool measuring) {
        const auto& s = sc_.schedule;
        const bool by_time = s.unit == ScheduleUnit::Time;
        const double at = double(k) * s.sample_interval;  // time, or collisions per particle
        const double n = double(runner_.view().particles().size());
        const double t_target = by_time ? t0 + at : kInf;
        const std::uint64_t c_target =
            by_time ? UINT64_MAX : c0 + static_cast<std::uint64_t>(std::llround(at * n / 2.0));
        const Advance adv = advance_in_chunks(t_target, c_target, t0, c0, measuring);
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

    // Advances to the target in chunks of engine work of about a quarter of a second, so that the
    // progress line moves from the start and within long intervals between samples. The engines
    // stop between two events or steps, so the chunks leave the trajectory bit for bit unchanged.
    Advance advance_in_chunks(double t_target, std::uint64_t c_target, double t0, std::uint64_t c0,
                              bool measuring) {
        const auto& s = sc_.schedule;
        const double length = measuring ? s.measurement : s.equilibration;
        const double before = measuring ? s.equilibration : 0.0;
        const double n = double(runner_.view().particles().size());
        while (true) {
            const auto start = std::chrono::steady_clock::now();
            const Advance adv =
                runner_.advance(t_target, c_target, runner_.work() + chunk_, opt_.interrupt);
            const bool reached = runner_.now() >= t_target || runner_.collisions() >= c_target;
            if (adv != Advance::Reached || reached) return adv;
            const double secs =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const double grow = secs > 0 ? std::clamp(0.25 / secs, 0.25, 4.0) : 4.0;
            chunk_ = std::max<std::uint64_t>(16, std::uint64_t(double(chunk_) * grow));
            const double done = s.unit == ScheduleUnit::Time
                                    ? (runner_.now() - t0)
                                    : 2.0 * double(runner_.collisions() - c0) / std::max(n, 1.0);
            progress_.update(measuring ? "measurement" : "equilibration",
                             (before + std::min(done, length)) / (s.equilibration + s.measurement),
                             runner_.work());
        }
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
    EngineRunner<D>& runner_;
    ObservableList<D>& observables_;
    std::size_t expected_samples_;
    FrameWriter frames_;
    Progress progress_;
    ScheduleOutcome out_;
    std::uint64_t chunk_ = 1024;  // engine work per advance call (advance_in_chunks)
    std::vector<double> positions_, velocities_;  // one frame, reused
    std::vector<std::int64_t> species_;
};

// /observables, /drivers and /performance (with the summary's observables, drivers, performance).
template <int D>
void write_results(ResultGroup root, const Scene& sc, const EngineRunner<D>& runner,
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

// Runs the scene's Simulation through its schedule and writes the result.
template <int D>
RunReport run_with(const Scene& sc, const RunOptions& opt, Simulation& sim, double cpu0) {
    SimulationState<D>& st = sim.state<D>();
    EngineRunner<D>& runner = *st.runner;
    // Created once the scene is known to run (the runner checked it): a failing run leaves the
    // .part file and never touches an earlier result.
    ResultSink sink(opt.output);
    write_provenance(sink.root(), sc, opt.command_line);
    ScheduleOutcome out;
    RunTotals totals;
    {
        ScheduleLoop<D> loop(sc, opt, runner, st.observables, sink.root());
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
    write_results<D>(sink.root(), sc, runner, st.drivers, st.observables, out, totals);
    for (const auto& q : sink.unreliable())
        spdlog::warn("{}: the value or its error bar is not finite; status: unreliable", q);
    sink.finish(totals.completed);
    if (sink.written() != opt.output)
        spdlog::warn("the completed result {} is kept; this run's data is in {}", opt.output,
                     sink.written());

    RunReport rep;
    rep.completed = totals.completed;
    rep.error = out.watchdog_stop;
    rep.output = sink.written();
    rep.summary_file = sink.summary_file();
    rep.summary = sink.summary();
    return rep;
}

}  // namespace

void check_scene(const Scene& scene) {
    if (scene.dimension == 2) {
        (void)initial_particles<2>(scene);
    } else {
        (void)initial_particles<3>(scene);
    }
}

RunReport run_scene(const Scene& scene, const RunOptions& options) {
    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;  // the cost includes the set-up
    // Before anything runs: a run must not be wasted on a path it cannot write.
    check_output_path(options.output, {scene.file});
    Simulation sim(scene, options.interrupt);
    return scene.dimension == 2 ? run_with<2>(sim.scene(), options, sim, cpu0)
                                : run_with<3>(sim.scene(), options, sim, cpu0);
}

}  // namespace gran
