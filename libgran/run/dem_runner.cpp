// The soft-sphere DEM engine as an engine plugin (`engine.type: dem`): its numerical settings, its
// checks at load (a soft-contact law, a schedule in time, walls with positions, no kicks, no
// binary collision records, a time step every contact resolves, a cost that can be paid:
// libgran/run/dem_cost.hpp), and its runner: whole time steps to each sample, watchdog windows of
// steps, and what its contacts achieve in isolated collisions.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "libgran/engines/dem/engine.hpp"
#include "libgran/engines/dem/probe.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/run/dem_cost.hpp"
#include "libgran/run/initial_state.hpp"
#include "libgran/run/watchdog.hpp"

namespace gran {

namespace {

template <int D>
class DemView final : public EngineView<D> {
  public:
    explicit DemView(const DemEngine<D>& e) : e_(e) {}
    const char* engine_name() const override { return "dem"; }
    const Particles<D>& particles() const override { return e_.particles(); }
    std::uint32_t id(std::size_t k) const override { return e_.ids()[k]; }
    double now() const override { return e_.now(); }
    double species_inertia(std::uint32_t s) const override { return e_.species_inertia(s); }
    const Vec<D>& gravity() const override { return e_.gravity(); }
    std::uint64_t collisions() const override { return e_.counters().contacts; }
    const std::vector<std::uint64_t>& pair_collisions() const override { return none_; }
    const std::array<std::uint64_t, 2 * D>& wall_hits() const override { return e_.wall_hits(); }
    const std::array<double, 2 * D>& wall_impulse() const override { return e_.wall_impulse(); }
    double wall_position(int code, double t) const override { return e_.wall_position(code, t); }
    std::vector<double> contact_virial() const override { return e_.contact_virial(); }

  private:
    const DemEngine<D>& e_;
    std::vector<std::uint64_t> none_;
};

DemSettings dem_settings(const Scene& sc) {
    const Params& p = sc.engine_settings.params;
    DemSettings s;
    s.dt = p.real("dt");
    s.dt_fraction = p.real("dt_fraction");
    s.skin = p.real("skin");
    s.threads = int(p.integer("threads"));
    s.sort_interval = std::uint64_t(p.integer("sort_interval"));
    s.gravity = sc.gravity;
    return s;
}

// Impact speed of the isolated test collisions: given, or sqrt(T0 / m) of the lightest species.
double probe_speed(const Scene& sc) {
    const double v = sc.engine_settings.params.real("probe_speed");
    return v > 0 ? v : std::sqrt(sc.temperature / sc.species.min_mass());
}

// Whole time steps up to each sample; walls from the drivers' wall descriptions.
template <int D>
class DemRunner final : public EngineRunner<D> {
  public:
    DemRunner(const Scene& sc, DriverList<D>& drivers, ObservableList<D>&)
        : sc_(sc),
          engine_(make_box<D>(sc), sc.species, sc.contacts, initial_particles<D>(sc),
                  dem_settings(sc)),
          view_(engine_) {
        for (auto& d : drivers) {
            for (const WallSpec<D>& w : d->walls()) {
                engine_.set_wall(w.axis, w.side, w.motion, sc.contacts.wall_named(w.partner));
                if (w.slide_axis >= 0)
                    engine_.set_wall_slide(w.axis, w.side, w.slide_axis, w.slide);
            }
        }
        for (auto& d : drivers) d->observe(view_);
    }

    const char* work_unit() const override { return "steps"; }
    const EngineView<D>& view() const override { return view_; }
    double now() const override { return engine_.now(); }
    std::uint64_t collisions() const override { return engine_.counters().contacts; }
    std::uint64_t work() const override { return engine_.counters().steps; }
    void synchronize() override {}  // the state is always at now()
    const std::string& failure() const override { return failure_; }

    Advance advance(double t_target, std::uint64_t, std::uint64_t w_target,
                    const std::atomic<bool>* interrupt) override {
        // A number of steps as a time: whole steps while now() < t (now() = t0 + steps dt).
        if (w_target != UINT64_MAX) {
            const double steps_left = double(w_target) - double(engine_.counters().steps);
            t_target = std::min(t_target, engine_.now() + (steps_left - 0.5) * engine_.dt());
        }
        if (!sc_.watchdog.enabled) {
            const auto stop = engine_.advance(t_target, interrupt);
            return stop == DemEngine<D>::Stop::Interrupted ? Advance::Interrupted
                                                           : Advance::Reached;
        }
        // Watchdog: chunks of `window` whole steps (the same steps as one advance), each followed
        // by a finiteness check. Time cannot stall here: now() = t0 + steps dt with dt > 0.
        while (engine_.now() < t_target) {
            const double chunk_end =
                engine_.now() + (double(sc_.watchdog.window) - 0.5) * engine_.dt();
            const auto stop = engine_.advance(std::min(t_target, chunk_end), interrupt);
            if (stop == DemEngine<D>::Stop::Interrupted) return Advance::Interrupted;
            failure_ = check_finite<D>(view_, sc_.species);
            if (!failure_.empty()) return Advance::Watchdog;
        }
        return Advance::Reached;
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("dem runner");
        ar.io(engine_);
        ar.io(failure_);
    }

    void write_performance(ResultGroup& perf, double cpu) const override {
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
        perf.value("spatial_sorts", c.sorts);
        perf.value("max_overlap", c.max_overlap, "contact distance");
        write_isolated_collisions(perf);
    }

  private:
    // What the run's contacts achieve: isolated head-on collisions on this engine, same law,
    // parameters and dt, at the probe speed.
    void write_isolated_collisions(ResultGroup& perf) const {
        const double v = probe_speed(sc_);
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
        const auto& sp = sc_.species.species;
        try {
            for (std::size_t a = 0; a < ns; ++a) {
                for (std::size_t b = a; b < ns; ++b) {
                    report(
                        sp[a].name + "-" + sp[b].name,
                        probe_pair_collision<D>(sc_.species, sc_.contacts, a, b, v, engine_.dt()));
                }
            }
            std::vector<std::size_t> walls;
            for (int code = 0; code < 2 * D; ++code) {
                if (!engine_.wall_is_set(code / 2, code % 2)) continue;
                const std::size_t w = engine_.wall_partner(code);
                if (std::find(walls.begin(), walls.end(), w) != walls.end()) continue;
                walls.push_back(w);
                for (std::size_t s = 0; s < ns; ++s) {
                    report(
                        sp[s].name + "-" + sc_.contacts.walls[w],
                        probe_wall_collision<D>(sc_.species, sc_.contacts, s, w, v, engine_.dt()));
                }
            }
        } catch (const std::exception& e) {
            spdlog::warn("isolated-collision check failed: {}", e.what());
        }
        perf.value("dt_over_tc", worst_dt_over_tc);
    }

    const Scene& sc_;
    DemEngine<D> engine_;
    DemView<D> view_;
    std::string failure_;
};

[[noreturn]] void refuse_at(const std::string& location, const std::string& why) {
    throw SceneError(location + ": " + why);
}

// A soft-contact law for every contact, each contact resolved by the time step.
void check_contacts(const Scene& sc, double dt) {
    const ContactTable& c = sc.contacts;
    const auto& soft = c.law->soft_contact;
    if (!soft) {
        refuse_at(sc.interactions_location,
                  c.laws.size() > 1
                      ? fmt::format("the dem engine takes one contact law for every contact; "
                                    "this scene uses {}",
                                    fmt::join(c.laws, ", "))
                      : fmt::format("law '{}' has no soft-contact form: on the dem engine use "
                                    "linear_dashpot, cundall_strack or hertz_mindlin, with a "
                                    "stiffness or a contact time (`gran list laws`)",
                                    c.law->name));
    }
    for (std::size_t w = 0; w < c.walls.size(); ++w) {
        for (std::size_t s = 0; s < c.species; ++s) {
            const double t = soft->duration(*c.table, c.wall_index(w, s));
            if (dt > t / 5) {
                refuse_at(sc.interactions_location,
                          fmt::format("the {}-{} contact lasts {:.6g} < 5 dt (dt = {:.6g}): "
                                      "velocity Verlet needs at least 5 steps per contact",
                                      sc.species.species[s].name, c.walls[w], t, dt));
            }
        }
    }
}

// What the scene's drivers and observables ask that this engine cannot do.
void check_demands(const Scene& sc, const EngineDemands& demands) {
    for (const auto& w : demands.walls) {
        const PluginEntry& d = sc.drivers[w.driver];
        if (w.replaces_contact)
            d.params.fail("type", "a " + d.type + " is not available on the dem engine");
        if (w.motion.kind == WallMotion::Kind::sawtooth) {
            d.params.fail(w.motion_key,
                          "the sawtooth limit (A -> 0) has no wall position; on the dem engine "
                          "give vibrating_wall `amplitude` and `frequency` (a real sawtooth, "
                          "v0 = 2 A f)");
        }
    }
    for (std::size_t k : demands.kick_drivers) {
        sc.drivers[k].params.fail("type",
                                  "this driver is not available on the dem engine (engine.type: "
                                  "dem supports static_wall and vibrating_wall)");
    }
    for (std::size_t k : demands.collision_observables) {
        sc.observables[k].params.fail(
            "type",
            "this observable (with these options) needs the binary collision records of the "
            "event_driven engine; the dem engine has contacts of finite duration");
    }
}

// The neighbour cutoff sigma + skin must stay below half of every periodic length (minimum image).
void check_cutoff(const Scene& sc) {
    const Params& ep = sc.engine_settings.params;
    const double dmax = sc.species.max_diameter();
    const double widest = dmax + ep.real("skin") * dmax;
    for (std::size_t a = 0; a < sc.periodic.size(); ++a) {
        if (sc.periodic[a] && !(widest < 0.5 * sc.box_length[a])) {
            ep.fail("skin", fmt::format("the neighbour cutoff sigma + skin = {:.6g} must stay "
                                        "below half the periodic length {:.6g} along axis {} "
                                        "(minimum image)",
                                        widest, sc.box_length[a], a));
        }
    }
}

void check_dem(const Scene& sc, const EngineDemands& demands) {
    const Params& ep = sc.engine_settings.params;
    if (sc.schedule.unit != ScheduleUnit::Time)
        sc.run_settings.fail("unit", "the dem engine schedules by time: set run.unit: time");
    if (ep.real("dt") == 0 && ep.real("dt_fraction") > 0.2) {
        ep.fail("dt_fraction", fmt::format("dt_fraction {} exceeds 1/5: velocity Verlet needs at "
                                           "least 5 steps per contact (default 1/50)",
                                           ep.real("dt_fraction")));
    }
    check_demands(sc, demands);
    if (!sc.contacts.law->soft_contact) check_contacts(sc, 0);
    DemEstimate cost;
    try {
        cost = estimate_particle_steps(sc);
    } catch (const std::invalid_argument& e) {
        ep.fail("dt", e.what());
    }
    check_contacts(sc, cost.dt);
    check_cutoff(sc);
    // A run that cannot be stepped through in any run time (e.g. springs stiff enough to make
    // t_c ~ 1e-150): refused rather than left to "hang".
    refuse_endless_run(sc, cost);
}

const bool registered = EngineRegistry::instance().add([] {
    EnginePlugin p;
    p.name = "dem";
    p.summary =
        "time-stepped soft spheres (velocity Verlet) with a soft-contact law: friction, rotation "
        "(Bhateja et al. 2016)";
    p.schema = {
        real("dt", "0", "time", "time step; 0: dt_fraction x the shortest contact duration", 0,
             1e308),
        real("dt_fraction", "0.02", "",
             "time step as a fraction of the shortest contact duration (when dt = 0); at most 0.2",
             0, 1, true, false),
        real("skin", "0.1", "largest diameter",
             "Verlet-list skin (the list is rebuilt once a grain moved skin / 2)", 0, 10),
        integer("threads", "1",
                "threads of one run's steps, at most one per 4096 grains; every result is the "
                "same to the last bit for any number (docs/performance.md: what a second "
                "thread gains)",
                1, 256),
        integer("sort_interval", "1000",
                "steps between renumberings of the grains in space (the neighbour list's cell "
                "order: neighbours near in memory), from 8192 grains on (smaller systems stay "
                "in the cache); 0: never. Outputs keep the input order; the round-off of the "
                "force sums follows the storage order, so the bits of a large run depend on it "
                "(never on engine.threads)",
                0, 1e12),
        real("probe_speed", "0", "velocity",
             "impact speed of the isolated test collisions reported with the run; 0: sqrt(T0 / "
             "m) of the lightest species",
             0, 1e308)};
    p.description = R"md(
Time-stepped soft spheres with friction and rotation (Bhateja, Sharma & Singh 2016, Appendix):
velocity Verlet, Verlet neighbour lists, the contact forces of a soft-contact law (one law for
every contact: `linear_dashpot`, `cundall_strack`, `hertz_mindlin`). The schedule must be in time
(`run.unit: time`). The time step is `dt`, or `dt_fraction` times the shortest contact duration
over grain-grain and grain-wall contacts; above a fifth of it is refused (velocity Verlet needs
5 steps per contact). A run costs particles x simulated time / dt particle-steps (`gran check`
prints it); more than 10^15 is refused, naming the key to change. Walls need a position: a `vibrating_wall` `sawtooth` is the real sawtooth
ramp; the sawtooth limit, thermal walls and the thermostat's kicks are refused with the reason, as
are observables that need binary collision records (`restitution_statistics`; `profiles` skips its
collisional pressure). A collision counted by `collision_statistics` is a contact that formed.
Rough grains start at rest in rotation.

A dem run reports under `/performance`: `dt`, `dt_over_tc` (the largest over the contact kinds),
`steps`, `particle_steps_per_second`, contacts formed, `neighbour_list_builds`, `spatial_sorts`
(`sort_interval`), `max_overlap` (largest delta / sigma), and
`isolated_collisions/<species>-<species>` and `<species>-<wall partner>`: the restitution and
contact time an isolated head-on collision achieves on the engine itself at this dt (at
`probe_speed`), next to the requested e and the closed-form t_c.)md";
    p.binary_collisions = false;
    // Rough grains start at rest in rotation (the beds of Bhateja et al. 2016 start from rest).
    p.thermal_initial_spin = false;
    p.check = check_dem;
    p.estimate = [](const Scene& sc, const EngineDemands&) {
        return run_cost(estimate_particle_steps(sc));
    };
    set_runner<DemRunner>(p);
    return p;
}());

}  // namespace

}  // namespace gran
