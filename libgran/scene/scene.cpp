#include "libgran/scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "libgran/core/h5.hpp"
#include "libgran/plugins/engine.hpp"
#include "libgran/plugins/placement.hpp"
#include "libgran/scene/interactions.hpp"
#include "libgran/scene/moved_keys.hpp"
#include "libgran/scene/placement.hpp"
#include "libgran/scene/plugin_check.hpp"
#include "libgran/scene/schemas.hpp"
#include "libgran/scene/species.hpp"

namespace gran {

namespace {

// dimension, seed, title, units, gravity.
Params read_top(const YAML::Node& root, const Where& top, Scene& sc, YAML::Node& res) {
    Params tp = read_params(root, top_schema(), top);
    sc.dimension = int(tp.integer("dimension"));
    sc.seed = static_cast<std::uint64_t>(tp.integer("seed"));
    if (tp.has("title")) sc.title = tp.str("title");
    if (tp.has("title")) res["title"] = sc.title;
    res["dimension"] = sc.dimension;
    res["seed"] = sc.seed;
    sc.units = tp.str("units");
    res["units"] = sc.units;
    if (tp.has("gravity")) {
        const std::vector<double> g = tp.reals("gravity");
        if (int(g.size()) != sc.dimension)
            tp.fail("gravity", fmt::format("expected {} components (one per axis), got {}",
                                           sc.dimension, g.size()));
        for (int a = 0; a < sc.dimension; ++a) sc.gravity[std::size_t(a)] = g[std::size_t(a)];
        res["gravity"] = g;
    }
    return tp;
}

// Edge lengths (given, or from a packing fraction and aspect ratios) and periodic axes.
void read_box_lengths(const Params& bp, Scene& sc, double particle_volume) {
    const int d = sc.dimension;
    if (bp.has("lengths") == bp.has("packing_fraction")) {
        bp.fail("", "give exactly one of 'lengths' or 'packing_fraction'");
    }
    if (bp.has("lengths")) {
        sc.box_length = bp.reals("lengths");
        if (int(sc.box_length.size()) != d) {
            bp.fail("lengths", fmt::format("expected {} lengths (one per axis), got {}", d,
                                           sc.box_length.size()));
        }
        if (bp.has("aspect"))
            bp.fail("aspect", "'aspect' goes with packing_fraction, not with lengths");
    } else {
        std::vector<double> aspect =
            bp.has("aspect") ? bp.reals("aspect") : std::vector<double>(std::size_t(d), 1.0);
        if (int(aspect.size()) != d)
            bp.fail("aspect", fmt::format("expected {} ratios, got {}", d, aspect.size()));
        double prod = 1;
        for (double a : aspect) prod *= a;
        const double volume = particle_volume / bp.real("packing_fraction");
        const double scale = std::pow(volume / prod, 1.0 / d);
        for (double a : aspect) sc.box_length.push_back(a * scale);
    }
    if (bp.has("periodic")) {
        const auto per = bp.booleans("periodic");
        if (int(per.size()) != d)
            bp.fail("periodic",
                    fmt::format("expected {} flags (one per axis), got {}", d, per.size()));
        sc.periodic.assign(per.begin(), per.end());
    } else {
        sc.periodic.assign(std::size_t(d), true);
    }
}

void read_box(const YAML::Node& root, const Where& top, Scene& sc, YAML::Node& res) {
    const int d = sc.dimension;
    const Where wb = top.child("box");
    Params bp = read_params(child(root, "box"), box_schema(), wb);
    const double vd = d == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
    double particle_volume = 0;
    for (const auto& s : sc.species.species)
        particle_volume += double(s.count) * vd * std::pow(s.diameter, d);
    read_box_lengths(bp, sc, particle_volume);
    double volume = 1;
    for (double l : sc.box_length) volume *= l;
    sc.packing_fraction = particle_volume / volume;
    const double dmax = sc.species.max_diameter();
    const std::string key = bp.has("lengths") ? "lengths" : "packing_fraction";
    // Sizes near 1e300 overflow the volumes (found by fuzzing): no engine computes with them.
    if (!std::isfinite(particle_volume) || !std::isfinite(volume) ||
        !std::isfinite(sc.packing_fraction)) {
        bp.fail(key, fmt::format("the box or the particles' volume overflows (box volume {:.4g}, "
                                 "particle volume {:.4g}): choose units in which diameters and "
                                 "box lengths are far from 1e300",
                                 volume, particle_volume));
    }
    for (int a = 0; a < d; ++a) {
        const double need = sc.periodic[a] ? 2 * dmax : dmax;
        if (sc.box_length[a] < need) {
            bp.fail(key, fmt::format("box length {:.4g} along axis {} is below {:.4g} ({})",
                                     sc.box_length[a], a, need,
                                     sc.periodic[a]
                                         ? "twice the largest diameter, needed on a periodic axis"
                                         : "the largest diameter"));
        }
    }
    if (sc.packing_fraction > max_packing_fraction(d)) {
        bp.fail(key, fmt::format("packing fraction {:.4g} exceeds the densest packing {:.4f} of {}",
                                 sc.packing_fraction, max_packing_fraction(d),
                                 d == 2 ? "disks" : "spheres"));
    }
    YAML::Node rb;
    for (double l : sc.box_length) rb["lengths"].push_back(l);
    for (bool p : sc.periodic) rb["periodic"].push_back(p);
    res["box"] = rb;
    sc.box_location = locate(wb, child(root, "box"));
}

void read_initial(const YAML::Node& root, const Where& top, Scene& sc, YAML::Node& res) {
    Params ip = read_params(child(root, "initial"), initial_schema(), top.child("initial"));
    sc.placement = PlacementRegistry::instance().find(ip.str("placement"));
    if (!sc.placement) {
        ip.fail("placement", fmt::format("unknown placement '{}'; known: {}", ip.str("placement"),
                                         PlacementRegistry::instance().names()));
    }
    sc.temperature = ip.real("temperature");
    res["initial"] = ip.resolved();
}

// engine.type picks the engine plugin, whose schema validates the rest of the section.
void read_engine(const YAML::Node& root, const Where& top, Scene& sc, YAML::Node& res) {
    const Where we = top.child("engine");
    const YAML::Node node = child(root, "engine");
    const YAML::Node type = child(node, "type");
    if (node.IsDefined() && !node.IsNull() && !node.IsMap())
        fail(we, node, "expected a map: `type` and the engine's numerical settings");
    if (type.IsDefined() && !type.IsScalar())
        fail(we.child("type"), type, "expected the name of an engine");
    const std::string name = type.IsDefined() ? type.Scalar() : "event_driven";
    sc.engine = EngineRegistry::instance().find(name);
    if (!sc.engine) {
        fail(we.child("type"), type,
             fmt::format("unknown engine '{}'; known: {}", name,
                         EngineRegistry::instance().names()));
    }
    Params ep = read_params(node, sc.engine->schema, we, {"type"});
    sc.engine_settings = PluginEntry{sc.engine->name, sc.engine->name, ep};
    YAML::Node r = ep.resolved();
    r["type"] = sc.engine->name;
    res["engine"] = r;
}

// Each run.target_error quantity names an observable of the scene ("observables.<name>....").
// Whether the quantity itself exists is known when the observable first writes (the first look).
void check_target_names(const Scene& sc) {
    for (const TargetError& t : sc.target.targets) {
        const std::string rest = t.quantity.substr(std::string("observables.").size());
        const std::string name = rest.substr(0, rest.find('.'));
        const auto it = std::find_if(sc.observables.begin(), sc.observables.end(),
                                     [&](const PluginEntry& o) { return o.name == name; });
        if (it != sc.observables.end() && rest.find('.') != std::string::npos) {
            // Free cooling (no driver, dissipative contacts) has no steady state: whole-run
            // averages keep drifting while their error bars shrink; only the scaling state of
            // the cooling state is a steady quantity.
            const bool cooling = !sc.info.driven && std::any_of(sc.info.nominal_restitution.begin(),
                                                                sc.info.nominal_restitution.end(),
                                                                [](double e) { return e < 1; });
            if (cooling && it->type != "cooling_state") {
                throw SceneError(fmt::format(
                    "{}: free cooling has no steady state: '{}' averages the whole run, "
                    "transient included, and a longer run changes what it measures, not only "
                    "its error; give a target on the cooling_state observable's scaling_state "
                    "quantities instead",
                    t.location, t.quantity));
            }
            continue;
        }
        std::vector<std::string> names;
        for (const PluginEntry& o : sc.observables) names.push_back(o.name);
        throw SceneError(
            fmt::format("{}: '{}' is not a quantity of an observable of this scene: expected "
                        "observables.<name>.<quantity> with <name> one of [{}]",
                        t.location, t.quantity, fmt::join(names, ", ")));
    }
}

void read_run(const YAML::Node& root, const Where& top, Scene& sc, YAML::Node& res) {
    Params rp = read_params(child(root, "run"), run_schema(), top.child("run"));
    sc.schedule.unit =
        rp.str("unit") == "time" ? ScheduleUnit::Time : ScheduleUnit::CollisionsPerParticle;
    sc.schedule.equilibration = rp.real("equilibration");
    sc.schedule.measurement = rp.real("measurement");
    sc.schedule.sample_interval = rp.real("sample_interval");
    sc.progress_interval = rp.real("progress_interval");
    if (sc.schedule.sample_interval > sc.schedule.measurement) {
        rp.fail("sample_interval",
                "sample_interval is longer than the measurement: no sample would be taken");
    }
    if (sc.schedule.measurement / sc.schedule.sample_interval > 1e8) {
        rp.fail("sample_interval", "more than 1e8 samples: increase sample_interval");
    }
    Params wp = read_params(child(child(root, "run"), "watchdog"), watchdog_schema(),
                            top.child("run").child("watchdog"));
    sc.watchdog.enabled = wp.boolean("enabled");
    sc.watchdog.window = static_cast<std::uint64_t>(wp.integer("window"));
    sc.watchdog.max_rate_growth = wp.real("max_rate_growth");
    sc.watchdog.max_events_per_tc = wp.real("max_events_per_tc");
    Params cp = read_params(child(child(root, "run"), "checkpoint"), checkpoint_schema(),
                            top.child("run").child("checkpoint"));
    sc.checkpoint_interval = cp.real("interval");
    sc.target = read_accuracy_target(child(root, "run"), top.child("run"),
                                     sc.engine->binary_collisions ? "events" : "steps");
    res["run"] = rp.resolved();
    res["run"]["watchdog"] = wp.resolved();
    res["run"]["checkpoint"] = cp.resolved();
    sc.run_settings = rp;
}

template <class R>
std::vector<PluginEntry> read_plugins(const YAML::Node& list, const Where& w, const R& registry,
                                      const char* what, YAML::Node& resolved) {
    std::vector<PluginEntry> out;
    resolved = YAML::Node(YAML::NodeType::Sequence);
    if (!list.IsDefined() || list.IsNull()) return out;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const Where wk = w.item(k);
        const YAML::Node e = list[k];
        if (!e.IsMap()) fail(wk, e, "expected a map with a `type` key");
        if (!child(e, "type").IsDefined()) fail(wk, e, "missing required key 'type'");
        if (!child(e, "type").IsScalar())
            fail(wk.child("type"), child(e, "type"), "expected the name of a plugin");
        const std::string type = child(e, "type").as<std::string>();
        const auto* plugin = registry.find(type);
        if (!plugin) {
            fail(wk.child("type"), child(e, "type"),
                 fmt::format("unknown {} '{}'; known: {}", what, type, registry.names()));
        }
        Schema s = plugin->schema;
        s.push_back(optional(text("name", "", "name of the result group (default: the type)")));
        Params p = read_params(e, s, wk, {"type"});
        PluginEntry entry{type, p.has("name") ? p.str("name") : type, p};
        if (const std::string why = h5::name_problem(entry.name); !why.empty())
            p.fail("name", "'" + entry.name + "' cannot name a result group: " + why);
        for (const auto& other : out) {
            if (other.name == entry.name) {
                p.fail("type", fmt::format("two entries named '{}': give one a distinct `name`",
                                           entry.name));
            }
        }
        YAML::Node r = p.resolved();
        r["type"] = type;
        resolved.push_back(r);
        out.push_back(std::move(entry));
    }
    return out;
}

}  // namespace

Scene parse_scene(const YAML::Node& root, const std::string& file) {
    const Where top{file, ""};
    if (!root.IsMap())
        fail(top, root, "expected a scene: a map with keys dimension, box, species, run, ...");
    refuse_moved_keys(root, top);
    Scene sc;
    sc.file = file;
    YAML::Node res;
    const Params tp = read_top(root, top, sc, res);
    YAML::Node rs;
    sc.species =
        read_species(child(root, "species"), tp.has("particles") ? tp.integer("particles") : 0,
                     sc.dimension, top, rs);
    if (tp.has("particles") && std::int64_t(sc.species.total_count()) != tp.integer("particles")) {
        tp.fail("particles", fmt::format("species counts add up to {}, not to particles = {}",
                                         sc.species.total_count(), tp.integer("particles")));
    }
    sc.species_location = locate(top.child("species"), child(root, "species"));
    res["particles"] = sc.species.total_count();
    res["species"] = rs;
    res["interactions"] = YAML::Node(YAML::NodeType::Map);  // keeps its place; filled below
    read_box(root, top, sc, res);
    read_initial(root, top, sc, res);
    read_engine(root, top, sc, res);
    read_run(root, top, sc, res);
    YAML::Node rd, ro;
    sc.drivers = read_plugins(child(root, "drivers"), top.child("drivers"),
                              DriverRegistry::instance(), "driver", rd);
    sc.observables = read_plugins(child(root, "observables"), top.child("observables"),
                                  ObservableRegistry::instance(), "observable", ro);
    res["drivers"] = rd;
    res["observables"] = ro;
    Params op = read_params(child(root, "output"), output_schema(), top.child("output"));
    sc.frames = static_cast<std::size_t>(op.integer("frames"));
    res["output"] = op.resolved();
    sc.interactions_location = locate(top.child("interactions"), child(root, "interactions"));
    if (sc.dimension == 2) {
        check_plugins<2>(sc, root, top, res);
    } else {
        check_plugins<3>(sc, root, top, res);
    }
    check_target_names(sc);
    sc.resolved = res;
    return sc;
}

SceneInfo plugin_info(const Scene& scene, std::size_t index) {
    SceneInfo info = scene.info;
    info.index = index;
    info.species = &scene.species;  // this copy's table (a Scene may have been copied or moved)
    return info;
}

}  // namespace gran
