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

#include "libgran/core/h5.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/run/equilibration.hpp"
#include "libgran/run/initial_state.hpp"
#include "libgran/run/watchdog.hpp"

namespace gran {

namespace {

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

// The scene's drivers and observables, built with what they may read of the scene.
template <int D>
std::pair<DriverList<D>, ObservableList<D>> make_plugins(const Scene& sc) {
    DriverList<D> drivers;
    for (std::size_t k = 0; k < sc.drivers.size(); ++k) {
        drivers.push_back(DriverRegistry::instance().find(sc.drivers[k].type)->template make<D>(
            sc.drivers[k].params, plugin_info(sc, k)));
    }
    ObservableList<D> observables;
    for (std::size_t k = 0; k < sc.observables.size(); ++k) {
        observables.push_back(
            ObservableRegistry::instance().find(sc.observables[k].type)->template make<D>(
                sc.observables[k].params, plugin_info(sc, k)));
    }
    return {std::move(drivers), std::move(observables)};
}

template <int D>
RunReport run_with(const Scene& sc, const RunOptions& opt, DriverList<D>& drivers,
                   ObservableList<D>& observables) {
    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;
    const auto runner_ptr = sc.engine->template make<D>(sc, drivers, observables);
    EngineRunner<D>& runner = *runner_ptr;
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

    Progress progress(opt, sc.progress_interval, runner.work_unit());
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
            const Advance adv = runner.advance(t_target, c_target, UINT64_MAX, opt.interrupt);
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
    return run_with<D>(sc, opt, drivers, observables);
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
    return scene.dimension == 2 ? run_dim<2>(scene, options) : run_dim<3>(scene, options);
}

}  // namespace gran
