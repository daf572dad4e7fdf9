#include "libgran/run/run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "libgran/plugins/engine.hpp"
#include "libgran/run/checkpoint.hpp"
#include "libgran/run/equilibration.hpp"
#include "libgran/run/frames.hpp"
#include "libgran/run/headline.hpp"
#include "libgran/run/initial_state.hpp"
#include "libgran/run/measurements.hpp"
#include "libgran/run/progress.hpp"
#include "libgran/run/result_file.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/run/target_run.hpp"
#include "libgran/run/trajectory.hpp"
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

// Where the schedule is: the phase (0 equilibration, 1 measurement), the next sample of it, and
// the phase's start (time and collisions), once it has started.
struct SchedulePosition {
    int phase = 0;
    std::size_t next_sample = 1;
    bool started = false;
    double t0 = 0;
    std::uint64_t c0 = 0;
};

// Where checkpoints go (path empty: none) and how often (wall-clock s; 0: only when interrupted).
struct CheckpointPlan {
    std::string path;
    double interval = 0;
    CheckpointHeader header;
};

// Equilibration then measurement, each with samples at fixed intervals (of time or collisions per
// particle); at each sample the observables are sampled and frames appended to the journal.
// Checkpoints between chunks of engine work; a loaded checkpoint continues where it was written.
template <int D>
class ScheduleLoop {
  public:
    ScheduleLoop(const Scene& sc, const RunOptions& opt, SimulationState<D>& st,
                 CheckpointPlan plan, double cpu0)
        : sc_(sc),
          opt_(opt),
          st_(st),
          runner_(*st.runner),
          expected_samples_(samples_in(sc.schedule.measurement)),
          frames_(frames_journal_path_for(opt.output), frame_box(sc), sc.frames, expected_samples_),
          progress_(opt.progress, opt.terminal, sc.progress_interval, runner_.work_unit()),
          plan_(std::move(plan)),
          cpu0_(cpu0),
          last_checkpoint_(std::chrono::steady_clock::now()),
          target_(sc.target, sc.schedule.measurement,
                  sc.schedule.unit == ScheduleUnit::Time ? "time" : "collisions per particle") {
        out_.measured_energy.reserve(expected_samples_);
    }

    ScheduleOutcome run() {
        while (pos_.phase < 2 && !out_.stopped()) {
            run_phase(pos_.phase == 1);
            if (out_.stopped()) break;
            pos_ = SchedulePosition{pos_.phase + 1};
        }
        progress_.finish();
        return std::move(out_);
    }
    // The outcome of a run stopped where it stands (a loaded checkpoint's state), without a new
    // checkpoint: `gran run --recover`.
    ScheduleOutcome stop_here() {
        out_.interrupted = true;
        return std::move(out_);
    }
    // Wall-clock and CPU seconds of the whole run (earlier sessions of a resumed run included).
    double elapsed() const { return prior_wall_ + progress_.elapsed(); }
    double cpu() const { return prior_cpu_ + double(std::clock()) / CLOCKS_PER_SEC - cpu0_; }
    // CPU seconds since the measurement started (meaningful once it has).
    double cpu_measuring() const { return cpu() - cpu_measure_start_; }
    std::uint64_t checkpoints() const { return checkpoints_; }
    double checkpoint_seconds() const { return checkpoint_seconds_; }
    std::uint64_t resumes() const { return resumes_; }
    FrameWriter& frames() { return frames_; }
    const TargetTracker& target() const { return target_; }

    // The whole state of the run: the schedule's, the frames', the engine's, every driver's and
    // every observable's (saving or loading, libgran/core/state_archive.hpp).
    void checkpoint(StateArchive& ar) {
        ar.section("schedule");
        ar.io(pos_.phase);
        ar.io(pos_.next_sample);
        ar.io(pos_.started);
        ar.io(pos_.t0);
        ar.io(pos_.c0);
        ar.io(out_.samples);
        ar.io(out_.measured_energy);
        ar.io(out_.t_measure_start);
        ar.io(out_.coll_measure_start);
        double wall = elapsed(), cpu_time = cpu();
        ar.io(wall);
        ar.io(cpu_time);
        ar.io(checkpoints_);
        ar.io(checkpoint_seconds_);
        ar.io(resumes_);
        if (ar.loading()) {
            prior_wall_ = wall;
            prior_cpu_ = cpu_time;
            ++resumes_;
        }
        if (target_.active()) {
            target_.checkpoint(ar);
            ar.io(cpu_measure_start_);
            ar.io(expected_samples_);
        }
        ar.io(frames_);
        ar.io(runner_);
        for (auto& d : st_.drivers) ar.io(*d);
        for (auto& o : st_.observables) ar.io(*o);
    }

  private:
    std::size_t samples_in(double length) const {
        return static_cast<std::size_t>(std::floor(length / sc_.schedule.sample_interval + 1e-9));
    }

    void start_phase(bool measuring) {
        if (pos_.started) return;
        pos_.started = true;
        pos_.t0 = runner_.now();
        pos_.c0 = runner_.collisions();
        if (measuring) {
            out_.t_measure_start = pos_.t0;
            out_.coll_measure_start = pos_.c0;
            cpu_measure_start_ = cpu();
        }
    }

    void run_phase(bool measuring) {
        const auto& s = sc_.schedule;
        const double length = measuring ? s.measurement : s.equilibration;
        if (length <= 0) return;
        start_phase(measuring);
        if (measuring && target_.active()) {
            measure_to_target();
            return;
        }
        const std::size_t nsamples = samples_in(length);
        while (pos_.next_sample <= nsamples) {
            const std::size_t k = pos_.next_sample;
            if (!advance_to(pos_.t0, pos_.c0, k, measuring)) return;
            sample(measuring);
            const double done =
                (measuring ? s.equilibration : 0.0) + length * double(k) / double(nsamples);
            progress_.update(measuring ? "measurement" : "equilibration",
                             done / (s.equilibration + s.measurement), runner_.work());
            ++pos_.next_sample;
            checkpoint_if_due(std::chrono::steady_clock::now());
        }
    }

    // The measurement of a run with a target (run.target_error): samples up to each look,
    // the look (libgran/run/target_run.hpp), on until the targets are reached, an error stops
    // falling, or max_cost is spent (checked after every sample and chunk of work).
    void measure_to_target() {
        const auto& s = sc_.schedule;
        while (true) {
            const double look = target_.next_look_length();
            const std::size_t nsamples = samples_in(look);
            expected_samples_ = std::max(expected_samples_, nsamples);
            while (pos_.next_sample <= nsamples) {
                if (!advance_to(pos_.t0, pos_.c0, pos_.next_sample, true)) {
                    if (capped_) {
                        target_.stopped_at_cap(observables_summary_now<D>(sc_, st_),
                                               measured_length(), cpu(), cpu_measuring());
                    } else {
                        target_.stopped(out_.status());
                    }
                    return;
                }
                sample(true);
                progress_.update("measurement (to the targets)",
                                 (s.equilibration + measured_length()) / (s.equilibration + look),
                                 runner_.work());
                ++pos_.next_sample;
                checkpoint_if_due(std::chrono::steady_clock::now());
                if (target_.over_cap(cpu(), runner_.work())) {
                    target_.stopped_at_cap(observables_summary_now<D>(sc_, st_), measured_length(),
                                           cpu(), cpu_measuring());
                    return;
                }
            }
            if (target_.take_look(observables_summary_now<D>(sc_, st_), measured_length(), cpu(),
                                  cpu_measuring()) ||
                opt_.pilot)
                return;
        }
    }

    // The measurement so far, in schedule units.
    double measured_length() const {
        if (sc_.schedule.unit == ScheduleUnit::Time) return runner_.now() - out_.t_measure_start;
        const double n = double(runner_.view().particles().size());
        return 2.0 * double(runner_.collisions() - out_.coll_measure_start) / std::max(n, 1.0);
    }

    // To the k-th sample of a phase that started at time t0 with c0 collisions; false when the
    // run stops there (interrupt, no more events, watchdog). An interrupted run writes a
    // checkpoint first: it can be resumed.
    bool advance_to(double t0, std::uint64_t c0, std::size_t k, bool measuring) {
        const auto& s = sc_.schedule;
        const bool by_time = s.unit == ScheduleUnit::Time;
        const double at = double(k) * s.sample_interval;  // time, or collisions per particle
        const double n = double(runner_.view().particles().size());
        const double t_target = by_time ? t0 + at : kInf;
        const std::uint64_t c_target =
            by_time ? UINT64_MAX : c0 + static_cast<std::uint64_t>(std::llround(at * n / 2.0));
        const Advance adv = advance_in_chunks(t_target, c_target, t0, c0, measuring);
        if (capped_) return false;  // max_cost spent mid-interval (a run with a target)
        if (adv == Advance::Interrupted) save_checkpoint();
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
    // progress line moves from the start and within long intervals between samples, and
    // checkpoints can be written between chunks. The engines stop between two events or steps
    // and a stop changes nothing, so the chunks (and checkpoints) leave the trajectory bit for
    // bit unchanged.
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
            const auto end = std::chrono::steady_clock::now();
            const double secs = std::chrono::duration<double>(end - start).count();
            const double grow = secs > 0 ? std::clamp(0.25 / secs, 0.25, 4.0) : 4.0;
            chunk_ = std::max<std::uint64_t>(16, std::uint64_t(double(chunk_) * grow));
            const double done = s.unit == ScheduleUnit::Time
                                    ? (runner_.now() - t0)
                                    : 2.0 * double(runner_.collisions() - c0) / std::max(n, 1.0);
            progress_.update(measuring ? "measurement" : "equilibration",
                             (before + std::min(done, length)) / (s.equilibration + s.measurement),
                             runner_.work());
            checkpoint_if_due(end);
            if (measuring && target_.active() && target_.over_cap(cpu(), runner_.work())) {
                capped_ = true;
                return Advance::Reached;
            }
        }
    }

    // Between chunks and after samples: a checkpoint once `interval` has passed since the last.
    void checkpoint_if_due(std::chrono::steady_clock::time_point now) {
        if (plan_.interval > 0 &&
            std::chrono::duration<double>(now - last_checkpoint_).count() >= plan_.interval)
            save_checkpoint();
    }

    // The state now, atomically to the checkpoint file, after the frames so far are on disk.
    void save_checkpoint() {
        if (plan_.path.empty()) return;
        frames_.sync();
        const auto start = std::chrono::steady_clock::now();
        ++checkpoints_;
        StateArchive ar = StateArchive::saver();
        checkpoint(ar);
        Checkpoint c{plan_.header, ar.bytes()};
        c.header.writes = checkpoints_;
        try {
            write_checkpoint(plan_.path, c);
        } catch (const OutputError& e) {  // the previous checkpoint is intact; the run goes on
            spdlog::warn("{}", e.what());
        }
        last_checkpoint_ = std::chrono::steady_clock::now();
        const double secs = std::chrono::duration<double>(last_checkpoint_ - start).count();
        checkpoint_seconds_ += secs;
        spdlog::debug("checkpoint {}: {:.3g} MB in {:.3g} s", checkpoints_,
                      double(c.state.size()) / 1e6, secs);
    }

    void sample(bool measuring) {
        const EngineView<D>& view = runner_.view();
        SampleContext<D> ctx{runner_.now(),     measuring,
                             expected_samples_, view,
                             sc_.species,       std::int64_t(runner_.work()),
                             target_.active()};
        for (auto& o : st_.observables) o->sample(ctx);
        if (!measuring) return;
        ++out_.samples;
        out_.measured_energy.push_back(view.kinetic_energy_per_particle(sc_.species));
        if (frames_.due(out_.samples)) {
            frame_of<D>(view, std::int64_t(runner_.work()), frame_);
            frames_.append(frame_);
        }
        if (opt_.on_sample) opt_.on_sample(out_.samples, runner_.now());
    }

    const Scene& sc_;
    const RunOptions& opt_;
    SimulationState<D>& st_;
    EngineRunner<D>& runner_;
    std::size_t expected_samples_;
    FrameWriter frames_;
    Progress progress_;
    ScheduleOutcome out_;
    SchedulePosition pos_;
    CheckpointPlan plan_;
    double cpu0_;
    double prior_wall_ = 0, prior_cpu_ = 0;  // earlier sessions of a resumed run
    std::uint64_t checkpoints_ = 0, resumes_ = 0;
    double checkpoint_seconds_ = 0;  // wall-clock s spent writing them
    std::chrono::steady_clock::time_point last_checkpoint_;
    std::uint64_t chunk_ = 1024;  // engine work per advance call (advance_in_chunks)
    Frame frame_;                 // one frame, reused
    TargetTracker target_;        // run.target_error (inactive without one)
    double cpu_measure_start_ = 0;
    bool capped_ = false;  // max_cost was spent between two samples
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
    report_equilibration(check_equilibration(out.measured_energy), sc.schedule, sc.info.driven,
                         perf);
}

// The checkpoints of a run to `output` (none without a path).
CheckpointPlan checkpoint_plan(const Scene& sc, const RunOptions& opt) {
    CheckpointPlan plan;
    plan.path = checkpoint_path_for(opt.output);
    plan.interval = sc.checkpoint_interval;
    plan.header = checkpoint_header(sc, opt.command_line);
    return plan;
}

// The checkpoint's state into a freshly built simulation (CheckpointError when it does not fit).
template <int D>
void load_state(ScheduleLoop<D>& loop, const Checkpoint& c, const std::string& path) {
    try {
        StateArchive ar = StateArchive::loader(c.state);
        loop.checkpoint(ar);
        if (!ar.at_end()) throw StateMismatch("the state is longer than this scene's");
    } catch (const StateMismatch& e) {
        throw CheckpointError(fmt::format("{}: cannot resume: {}", path, e.what()));
    }
}

// Runs the scene's Simulation through its schedule (from a checkpoint's state when `resume` is
// given) and writes the result.
template <int D>
RunReport run_with(const Scene& sc, const RunOptions& opt, Simulation& sim, double cpu0,
                   const Checkpoint* resume) {
    SimulationState<D>& st = sim.state<D>();
    EngineRunner<D>& runner = *st.runner;
    ScheduleLoop<D> loop(sc, opt, st, checkpoint_plan(sc, opt), cpu0);
    if (resume) {
        load_state(loop, *resume, checkpoint_path_for(opt.output));
        spdlog::info("resumed from {} at t = {:.6g} ({} {})", checkpoint_path_for(opt.output),
                     runner.now(), runner.work(), runner.work_unit());
    }
    // Created once the scene is known to run (the runner checked it): a failing run leaves the
    // .part file and never touches an earlier result.
    ResultSink sink(opt.output);
    write_provenance(sink.root(), sc, opt.command_line);
    const ScheduleOutcome out = opt.recover_only ? loop.stop_here() : loop.run();
    RunTotals totals;
    totals.wall_time = loop.elapsed();
    totals.cpu_time = loop.cpu();
    totals.cpu_time_measuring = out.samples > 0 ? loop.cpu_measuring() : 0.0;
    totals.checkpoints = loop.checkpoints();
    totals.checkpoint_time = loop.checkpoint_seconds();
    totals.resumes = loop.resumes();
    if (opt.recover_only) {
        spdlog::info("writing what was measured up to the checkpoint");
    } else if (out.interrupted) {
        spdlog::warn("interrupted: writing what was measured so far");
    }
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
    write_trajectory(loop.frames(), sink, sink.destination(totals.completed), sc, opt.command_line,
                     runner.work_unit());
    write_summary_header(sink.summary(), sc, opt.output, out.status(), out.watchdog_stop, n);
    write_results<D>(sink.root(), sc, runner, st.drivers, st.observables, out, totals);
    if (loop.target().active()) {
        ResultGroup tg = sink.root().group("target");
        loop.target().write(tg, totals.cpu_time, runner.work(), runner.work_unit());
    }
    if (const YAML::Node h = headline(sink.summary()); h.size() > 0) sink.summary()["headline"] = h;
    for (const auto& q : sink.unreliable())
        spdlog::warn("{}: the value or its error bar is not finite; status: unreliable", q);
    sink.finish(totals.completed);
    if (sink.written() != opt.output)
        spdlog::warn("the completed result {} is kept; this run's data is in {}", opt.output,
                     sink.written());
    if (out.interrupted) {
        spdlog::info("resume with: gran run --resume {}", opt.output);
    } else {  // the run has ended: nothing to resume
        loop.frames().remove();
        std::error_code ec;
        std::filesystem::remove(checkpoint_path_for(opt.output), ec);
    }

    RunReport rep;
    rep.completed = totals.completed;
    rep.error = out.watchdog_stop;
    rep.output = sink.written();
    rep.summary_file = sink.summary_file();
    rep.summary = sink.summary();
    rep.target_status = loop.target().outcome().status;
    rep.target_reason = loop.target().outcome().reason;
    return rep;
}

RunReport run_from(const Scene& scene, const RunOptions& options, const Checkpoint* resume) {
    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;  // the cost includes the set-up
    // Before anything runs: a run must not be wasted on a path it cannot write.
    check_output_path(options.output, {scene.file});
    Simulation sim(scene, options.interrupt);
    return scene.dimension == 2 ? run_with<2>(sim.scene(), options, sim, cpu0, resume)
                                : run_with<3>(sim.scene(), options, sim, cpu0, resume);
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
    if (std::filesystem::exists(checkpoint_path_for(options.output))) {
        spdlog::warn(
            "{} holds a checkpoint of an earlier run; this run starts over and replaces "
            "it (gran run --resume {} would continue it)",
            checkpoint_path_for(options.output), options.output);
    }
    return run_from(scene, options, nullptr);
}

RunReport resume_run(const RunOptions& options, const Scene* given) {
    const Checkpoint c = read_checkpoint(checkpoint_path_for(options.output));
    const Scene scene = scene_of(c);
    check_resumable(c, given ? *given : scene);
    // A scene given beside the checkpoint is the same but for its checkpoint interval: its own.
    return run_from(given ? *given : scene, options, &c);
}

}  // namespace gran
