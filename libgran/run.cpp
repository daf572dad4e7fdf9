#include "libgran/run.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "drivers/driver.hpp"
#include "libgran/h5.hpp"
#include "libgran/placement.hpp"
#include "observables/observable.hpp"

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
        p = sc.placement == "lattice" ? place_lattice<D>(box, sc.species, rng)
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
    Progress(const RunOptions& o, double log_interval) : opt_(o), log_interval_(log_interval) {
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
            fmt::format("{:<13} {:5.1f}%  elapsed {:.0f}s  ETA {:.0f}s  {:.3g} events/s", phase,
                        100 * fraction, elapsed, eta, rate);
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
    std::vector<std::unique_ptr<Driver<D>>> drivers;
    for (std::size_t k = 0; k < sc.drivers.size(); ++k) {
        info.index = k;
        drivers.push_back(Registry<Driver>::instance()
                              .find(sc.drivers[k].type)
                              ->template make<D>(sc.drivers[k].params, info));
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

template <int D>
RunReport run_dim(const Scene& sc, const RunOptions& opt) {
    const Box<D> box = make_box<D>(sc);
    auto [drivers, observables] = make_plugins<D>(sc);

    const double cpu0 = double(std::clock()) / CLOCKS_PER_SEC;
    EventDrivenEngine<D> engine(box, sc.species, initial_particles<D>(sc), sc.engine);
    for (auto& d : drivers) d->attach(engine);
    CollisionFanout<D> fanout;
    for (auto& o : observables) {
        if (auto* s = o->collision_sink()) fanout.sinks.push_back(s);
    }
    if (fanout.sinks.size() == 1) engine.set_collision_sink(fanout.sinks[0]);
    if (fanout.sinks.size() > 1) engine.set_collision_sink(&fanout);

    const std::size_t n = engine.particles().size();
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

    Progress progress(opt, sc.progress_interval);
    bool interrupted = false;
    bool stalled = false;
    std::size_t samples_taken = 0;
    double t_measure_start = 0;
    std::uint64_t coll_measure_start = 0;

    for (int phase = 0; phase < 2 && !interrupted && !stalled; ++phase) {
        const bool measuring = phase == 1;
        const double length = measuring ? s.measurement : s.equilibration;
        if (length <= 0) continue;
        const double t0 = engine.now();
        const std::uint64_t c0 = engine.counters().collisions;
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
            // Advance to the sample, stopping for driver events on the way.
            while (true) {
                double t_driver = kInf;
                for (auto& d : drivers) t_driver = std::min(t_driver, d->next_time());
                const double t_stop = std::min(t_target, t_driver);
                const auto stop = engine.advance(t_stop, c_target, opt.interrupt);
                if (stop == EventDrivenEngine<D>::Stop::Interrupted) {
                    interrupted = true;
                    break;
                }
                if (stop == EventDrivenEngine<D>::Stop::NoEvents) {
                    stalled = true;
                    spdlog::warn("no more events (all particles at rest?): stopping the run early");
                    break;
                }
                if (stop == EventDrivenEngine<D>::Stop::CollisionLimit) break;
                // Time limit: fire the drivers that are due; stop when the sample time is reached.
                for (auto& d : drivers) {
                    if (d->next_time() <= engine.now()) {
                        engine.synchronize();
                        d->fire(engine);
                    }
                }
                if (engine.now() >= t_target) break;
            }
            if (interrupted || stalled) break;
            // Observables read positions and velocities at now() (under gravity velocities change
            // in free flight too).
            engine.synchronize();
            SampleContext<D> ctx{engine.now(), measuring, expected_samples, engine, sc.species};
            for (auto& o : observables) o->sample(ctx);
            if (measuring) {
                ++samples_taken;
                if (frame_every && samples_taken % frame_every == 0 &&
                    frame_time.size() < sc.frames) {
                    engine.synchronize();
                    frame_time.push_back(engine.now());
                    // Frames list particles by their original index (the engine re-sorts storage).
                    const std::size_t base = frame_pos.size();
                    frame_pos.resize(base + n * D);
                    frame_vel.resize(base + n * D);
                    const auto& ids = engine.ids();
                    for (std::size_t i = 0; i < n; ++i) {
                        for (int a = 0; a < D; ++a) {
                            frame_pos[base + ids[i] * D + std::size_t(a)] =
                                engine.particles().r[i][a];
                            frame_vel[base + ids[i] * D + std::size_t(a)] =
                                engine.particles().v[i][a];
                        }
                    }
                }
            }
            const double done =
                (measuring ? s.equilibration : 0.0) + length * double(k) / double(nsamples);
            progress.update(measuring ? "measurement" : "equilibration",
                            done / (s.equilibration + s.measurement), engine.counters().events);
        }
    }
    progress.finish();
    const double wall = progress.elapsed();
    const double cpu = double(std::clock()) / CLOCKS_PER_SEC - cpu0;
    if (interrupted) spdlog::warn("interrupted: writing what was measured so far");

    // Write to a temporary file and rename: an existing result is never clobbered by a failed run.
    const auto parent = std::filesystem::path(opt.output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    const std::string part = opt.output + ".part";
    RunReport rep;
    rep.completed = !interrupted && !stalled;
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

        const auto& c = engine.counters();
        const double measured_coll = double(c.collisions - coll_measure_start);
        h5::Group perf = root.group("performance");
        perf.write_scalar("wall_time", wall);
        perf.attr_on("wall_time", "unit", "s");
        perf.write_scalar("cpu_time", cpu);
        perf.attr_on("cpu_time", "unit", "s");
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
        perf.write_scalar("final_time", engine.now());
        perf.write_scalar("collisions_per_particle", 2.0 * double(c.collisions) / double(n));
        perf.write_scalar("measured_collisions_per_particle", 2.0 * measured_coll / double(n));
        perf.write_scalar("measured_time", engine.now() - t_measure_start);
        perf.write_scalar("samples", static_cast<std::int64_t>(samples_taken));
        perf.write_scalar("completed", static_cast<std::int64_t>(rep.completed ? 1 : 0));
        perf.write_scalar("interrupted", static_cast<std::int64_t>(interrupted ? 1 : 0));

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
            for (std::size_t i = 0; i < n; ++i)
                spec[engine.ids()[i]] = engine.particles().species[i];
            pg.write("species", spec);
        }

        summary["scene"] = sc.file;
        if (!sc.title.empty()) summary["title"] = sc.title;
        summary["result"] = opt.output;
        summary["status"] =
            interrupted ? "interrupted" : (stalled ? "stopped: no more events" : "completed");
        summary["dimension"] = D;
        summary["particles"] = n;
        summary["packing_fraction"] = sc.packing_fraction;
        summary["observables"] = obs_summary;
        if (drv_summary.size() > 0) summary["drivers"] = drv_summary;
        YAML::Node ps;
        ps["wall_time_s"] = wall;
        ps["cpu_time_s"] = cpu;
        ps["events"] = c.events;
        ps["collisions"] = c.collisions;
        ps["events_per_second"] = double(c.events) / std::max(cpu, 1e-9);
        ps["collisions_per_second"] = double(c.collisions) / std::max(cpu, 1e-9);
        ps["collisions_per_particle"] = 2.0 * double(c.collisions) / double(n);
        ps["tc_guard_collisions"] = c.tc_collisions;
        ps["overlap_collisions"] = c.overlap_collisions;
        ps["full_reschedules"] = c.full_reschedules;
        if (c.full_reschedules > 0 && c.collisions > 0) {
            ps["reschedules_per_collision_per_particle"] =
                double(c.full_reschedules) * double(n) / (2.0 * double(c.collisions));
        }
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

}  // namespace

void check_scene(const Scene& scene) {
    if (scene.dimension == 2) {
        (void)initial_particles<2>(scene);
        (void)make_plugins<2>(scene);
    } else {
        (void)initial_particles<3>(scene);
        (void)make_plugins<3>(scene);
    }
}

RunReport run_scene(const Scene& scene, const RunOptions& options) {
    return scene.dimension == 2 ? run_dim<2>(scene, options) : run_dim<3>(scene, options);
}

}  // namespace gran
