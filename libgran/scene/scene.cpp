#include "libgran/scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/scene/placement.hpp"
#include "libgran/scene/scene_schemas.hpp"

namespace gran {

namespace {

ParamSpec list_of(ParamType t, std::string name, std::string doc, bool opt = true) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = t;
    s.doc = std::move(doc);
    s.optional = opt;
    return s;
}

ParamSpec gravity_spec() {
    ParamSpec g = real("gravity", "", "length/time^2",
                       "uniform gravitational acceleration vector, one component per axis (e.g. "
                       "[0, -9.81] in SI; default none); parabolic free flight in the "
                       "event-driven engine (pair collisions stay exact: both partners fall "
                       "alike)");
    g.type = ParamType::RealList;
    g.optional = true;
    g.default_value = "";
    return g;
}

}  // namespace

Schema top_schema() {
    return {
        optional(text("title", "", "free text describing the scene, copied to results")),
        integer("dimension", "", "2 (disks) or 3 (spheres)", 2, 3),
        integer("seed", "1", "random seed: the same scene and seed give identical results", 0,
                9.2e18),
        optional(integer("particles", "",
                         "total number of particles: needed when species give number_fraction; "
                         "given with counts, they must add up to it",
                         1, 1e9)),
        list_of(ParamType::Map, "box", "box geometry (see section box)", false),
        list_of(ParamType::List, "species", "list of species (see section species)", false),
        list_of(ParamType::Map, "interactions",
                "pair laws (see section interactions; default: every pair elastic and smooth)"),
        list_of(ParamType::Map, "initial",
                "initial configuration (see section initial; default: random placement, T = 1)"),
        list_of(ParamType::List, "drivers",
                "energy injection: list of {type: <driver>, ...} (`gran list drivers`; default: "
                "none, free cooling)"),
        list_of(ParamType::List, "observables",
                "measurements: list of {type: <observable>, ...} (`gran list observables`; "
                "default: none)"),
        list_of(ParamType::Map, "engine",
                "engine and numerical settings (see section engine; default: event_driven)"),
        list_of(ParamType::Map, "run", "run schedule (see section run)", false),
        list_of(ParamType::Map, "output",
                "output settings (see section output; default: no frames)"),
        gravity_spec(),
        choice("units", "reduced", {"reduced", "SI"},
               "unit system the numbers are written in: reduced (lengths, masses and energies as "
               "given, k_B = 1) or SI (m, kg, s, Hz, J, temperatures as energies; e.g. McNamara & "
               "Falcon 2005). No number is converted: write every value in the chosen system. "
               "Results state it in /parameters@units"),
    };
}

Schema box_schema() {
    ParamSpec lengths =
        real("lengths", "", "length",
             "box edge lengths, one per axis; the box is [0, L_a) on each axis", 0, 1e308, true);
    lengths.type = ParamType::RealList;
    lengths.optional = true;
    lengths.default_value = "";
    ParamSpec aspect =
        real("aspect", "", "", "edge-length ratios used with packing_fraction (default all 1)", 0,
             1e308, true);
    aspect.type = ParamType::RealList;
    aspect.optional = true;
    ParamSpec periodic =
        boolean("periodic", "",
                "per axis: periodic (true) or bounded by static elastic walls at 0 and L "
                "(default: all true)");
    periodic.type = ParamType::BoolList;
    periodic.default_value = "";
    periodic.optional = true;
    return {lengths,
            optional(real("packing_fraction", "", "",
                          "packing fraction: the box is sized to reach it", 0, 1, true, true)),
            aspect, periodic};
}

Schema initial_schema() {
    return {choice("placement", "random", {"random", "lattice", "close_packed"},
                   "random: random sequential insertion (largest first; jams near packing fraction "
                   "0.55 in 2D, 0.38 in 3D); lattice: a square/cubic lattice with shuffled species "
                   "(up to pi/4, pi/6); close_packed: a hexagonal (2D) or fcc (3D) lattice "
                   "stretched to the box, up to the densest packing 0.9069 / 0.7405 (less on "
                   "bounded axes, which keep a radius of clearance), vacancies spread evenly"),
            real("temperature", "1", "energy",
                 "Maxwellian velocities at this temperature for every species, zero total "
                 "momentum",
                 0, 1e308, true)};
}

Schema engine_schema() {
    return {choice("type", "event_driven", {"event_driven", "dem"},
                   "simulation engine: event_driven (hard particles, instantaneous collisions) or "
                   "dem (time-stepped soft spheres with friction, Bhateja et al. 2016)"),
            choice("collapse_guard", "tc", {"tc", "none"},
                   "event_driven: inelastic-collapse guard: TC model (collisions within tc of a "
                   "previous one are elastic)"),
            real("tc", "1e-6", "time", "event_driven: TC-model time window", 0, 1e308),
            choice("contact_law", "linear_dashpot",
                   {"linear_dashpot", "cundall_strack", "hertz_mindlin"},
                   "dem: contact law of every pair and wall: linear_dashpot (Bhateja et al. Eqs. "
                   "A5-A9: linear spring, dashpot from e, Coulomb-capped tangential dashpot), "
                   "cundall_strack (tangential spring with history), hertz_mindlin"),
            real("stiffness", "0", "mass/time^2",
                 "dem: normal stiffness k_n of a grain-grain contact (hertz_mindlin: coefficient "
                 "of delta^(3/2), mass/(length^(1/2) time^2)); 0: set from contact_time",
                 0, 1e308),
            real("contact_time", "0", "time",
                 "dem: head-on contact duration t_c to give the stiffness when stiffness = 0 "
                 "(hertz_mindlin: at reference_speed)",
                 0, 1e308),
            real("dt", "0", "time", "dem: time step; 0: dt_fraction x the shortest contact time", 0,
                 1e308),
            real("dt_fraction", "0.02", "",
                 "dem: time step as a fraction of the shortest contact duration (when dt = 0); at "
                 "most 0.2",
                 0, 1, true, false),
            real("friction", "0", "",
                 "dem: Coulomb friction coefficient mu of grain-grain contacts (Eq. A8); 0: "
                 "smooth, no rotation",
                 0, 1e308),
            real("tangential_damping", "0", "mass/time",
                 "dem: tangential dashpot c_t (Eq. A7), capped by mu |F_n|", 0, 1e308),
            optional(real("tangential_damping_ratio", "", "",
                          "dem: c_t as a multiple of the contact's own normal dashpot c_n "
                          "(replaces tangential_damping; e.g. 1: c_t = c_n)",
                          0, 1e308)),
            optional(real("wall_friction", "", "",
                          "dem: friction coefficient against walls (default: friction)", 0, 1e308)),
            optional(real("wall_tangential_damping", "", "mass/time",
                          "dem: tangential dashpot against walls (default: tangential_damping)", 0,
                          1e308)),
            real("tangential_stiffness_ratio", "0.2857142857142857", "",
                 "dem, cundall_strack and hertz_mindlin: k_t / k_n (2/7: equal normal and "
                 "tangential periods for uniform spheres)",
                 0, 1e308, true),
            real("reference_speed", "0", "velocity",
                 "dem: impact speed of the isolated test collisions reported with the run (and "
                 "hertz_mindlin: of contact_time); 0: sqrt(T0 / m) of the lightest species",
                 0, 1e308),
            real("skin", "0.1", "largest diameter",
                 "dem: Verlet-list skin (the list is rebuilt once a grain moved skin / 2)", 0, 10)};
}

Schema run_schema() {
    return {choice("unit", "collisions_per_particle", {"collisions_per_particle", "time"},
                   "unit of the schedule lengths (collisions per particle = 2 N_coll / N)"),
            real("equilibration", "0", "unit",
                 "length of the equilibration phase: not measured (except by kinetic_energy); "
                 "checked after the run (/performance/equilibration, MSER-5, warning when too "
                 "short)",
                 0, 1e308),
            real("measurement", "", "unit", "length of the measurement phase", 0, 1e308, true),
            real("sample_interval", "1", "unit", "interval between samples of the observables", 0,
                 1e308, true),
            real("progress_interval", "10", "s",
                 "seconds between progress log lines when not on a terminal", 0, 1e308, true),
            list_of(ParamType::Map, "watchdog",
                    "stops a run that stalls or produces NaN (see section run.watchdog; on by "
                    "default)")};
}

Schema watchdog_schema() {
    return {
        boolean("enabled", "true",
                "stop a run whose simulated time stalls, whose event rate explodes or whose "
                "state turns non-finite (with a message; the result keeps what was measured)"),
        integer("window", "1000000",
                "events (event_driven) or steps (dem) between checks; a window that leaves the "
                "simulated time unchanged stops the run",
                1, 1e18),
        real("max_rate_growth", "1e6", "",
             "event_driven: stop when the events per particle per unit time of a window exceed "
             "this multiple of the first window's (inelastic collapse)",
             1, 1e308),
        real("max_events_per_tc", "0.1", "",
             "event_driven with the TC model: stop when a window has more events per particle "
             "per TC window engine.tc than this: grains resting on each other or on a floor are "
             "then resolved by micro-collisions every ~tc (use the dem engine for beds at rest)",
             0, 1e308, true)};
}

Schema output_schema() {
    return {integer(
        "frames", "0",
        "trajectory frames (positions, velocities) written under /particles/all (equally spaced "
        "in the measurement)",
        0, 1e6)};
}

namespace {

// engine.type: dem. Grain-grain restitution comes from the pair laws (constant_restitution
// alpha, smooth: roughness on this engine is friction, engine.friction); walls are elastic unless
// a wall driver sets its restitution.
void read_dem_settings(const Params& ep, Scene& sc) {
    DemSceneSettings& d = sc.dem;
    const std::string law = ep.str("contact_law");
    d.law = law == "cundall_strack"  ? DemLaw::cundall_strack
            : law == "hertz_mindlin" ? DemLaw::hertz_mindlin
                                     : DemLaw::linear_dashpot;
    d.pair.k_n = ep.real("stiffness");
    d.pair.t_c = ep.real("contact_time");
    if (d.pair.k_n == 0 && d.pair.t_c == 0) {
        ep.fail("stiffness", "the dem engine needs `stiffness` (k_n) or `contact_time` (t_c)");
    }
    if (d.pair.k_n > 0 && d.pair.t_c > 0) {
        ep.fail("contact_time", "give `stiffness` or `contact_time`, not both");
    }
    d.pair.mu = ep.real("friction");
    d.pair.gamma_t = ep.real("tangential_damping");
    if (ep.has("tangential_damping_ratio"))
        d.pair.gamma_t_ratio = ep.real("tangential_damping_ratio");
    d.pair.k_t_ratio = ep.real("tangential_stiffness_ratio");
    double m_min = kInf;
    for (const auto& sp : sc.species.species) m_min = std::min(m_min, sp.mass);
    d.probe_speed = ep.real("reference_speed") > 0 ? ep.real("reference_speed")
                                                   : std::sqrt(sc.temperature / m_min);
    d.pair.reference_speed = d.probe_speed;
    if (d.law == DemLaw::hertz_mindlin && d.pair.t_c > 0 && ep.real("reference_speed") == 0) {
        ep.fail("reference_speed",
                "hertz_mindlin with contact_time needs the impact speed at "
                "which t_c holds (reference_speed)");
    }
    d.wall = d.pair;
    d.wall.e = 1;  // elastic unless a wall driver says otherwise
    if (ep.has("wall_friction")) d.wall.mu = ep.real("wall_friction");
    if (ep.has("wall_tangential_damping")) {
        d.wall.gamma_t = ep.real("wall_tangential_damping");
        d.wall.gamma_t_ratio = -1;
    }
    d.settings.dt = ep.real("dt");
    d.settings.dt_fraction = ep.real("dt_fraction");
    d.settings.skin = ep.real("skin");
    if (d.settings.dt == 0 && d.settings.dt_fraction > 0.2) {
        ep.fail("dt_fraction", fmt::format("dt_fraction {} exceeds 1/5: velocity Verlet needs at "
                                           "least 5 steps per contact (default 1/50)",
                                           d.settings.dt_fraction));
    }
    const std::size_t ns = sc.species.size();
    for (std::size_t a = 0; a < ns; ++a) {
        for (std::size_t b = a; b < ns; ++b) {
            const PairCoefficients& c = sc.species.pair(a, b);
            const std::string pair = sc.species.species[a].name + "-" + sc.species.species[b].name;
            if (c.law != "constant_restitution") {
                ep.fail("type", fmt::format("pair {} uses law '{}'; the dem engine takes "
                                            "constant_restitution (alpha is e_p) and makes "
                                            "impact-speed dependence with contact_law: "
                                            "hertz_mindlin",
                                            pair, c.law));
            }
            if (c.beta != -1) {
                ep.fail("type", fmt::format("pair {} has beta = {}; on the dem engine roughness is "
                                            "Coulomb friction: set engine.friction (and "
                                            "tangential_damping) and leave beta = -1",
                                            pair, c.beta));
            }
        }
    }
}

std::vector<PluginEntry> read_plugins(const YAML::Node& list, const Where& w, bool observable,
                                      YAML::Node& resolved) {
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
        const Schema* schema = nullptr;
        std::string known;
        if (observable) {
            if (auto* p = Registry<Observable>::instance().find(type)) schema = &p->schema;
            known = Registry<Observable>::instance().names();
        } else {
            if (auto* p = Registry<Driver>::instance().find(type)) schema = &p->schema;
            known = Registry<Driver>::instance().names();
        }
        if (!schema) {
            fail(wk.child("type"), child(e, "type"),
                 fmt::format("unknown {} '{}'; known: {}", observable ? "observable" : "driver",
                             type, known));
        }
        Schema s = *schema;
        s.push_back(optional(text("name", "", "name of the result group (default: the type)")));
        Params p = read_params(e, s, wk, {"type"});
        PluginEntry entry{type, p.has("name") ? p.str("name") : type, p};
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

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : s) {
        if (c == sep) {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    parts.push_back(cur);
    return parts;
}

}  // namespace

void apply_override(YAML::Node& root, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw SceneError(fmt::format(
            "--set '{}': expected key=value, e.g. --set run.measurement=100", assignment));
    }
    const auto keys = split(assignment.substr(0, eq), '.');
    YAML::Node value;
    try {
        value = YAML::Load(assignment.substr(eq + 1));
    } catch (const YAML::Exception& e) {
        throw SceneError(fmt::format("--set '{}': value is not valid YAML: {}", assignment, e.msg));
    }
    // Walk with explicit node copies (yaml-cpp nodes are handles).
    std::vector<YAML::Node> chain{root};
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        YAML::Node cur = chain.back();
        const std::string& key = keys[k];
        const bool index = !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit);
        if (index) {
            const std::size_t idx = std::stoul(key);
            if (!cur.IsSequence() || idx >= cur.size()) {
                throw SceneError(fmt::format("--set '{}': '{}' is not an index of an existing list",
                                             assignment, key));
            }
            chain.push_back(cur[idx]);
        } else {
            if (cur.IsSequence()) {
                throw SceneError(fmt::format("--set '{}': '{}' is a list; use a numeric index",
                                             assignment, key));
            }
            if (!cur[key]) cur[key] = YAML::Node(YAML::NodeType::Map);
            chain.push_back(cur[key]);
        }
    }
    YAML::Node last = chain.back();
    const std::string& key = keys.back();
    if (!key.empty() && std::all_of(key.begin(), key.end(), ::isdigit) && last.IsSequence()) {
        const std::size_t idx = std::stoul(key);
        if (idx >= last.size())
            throw SceneError(fmt::format("--set '{}': index {} out of range", assignment, idx));
        last[idx] = value;
    } else {
        last[key] = value;
    }
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
    std::ifstream in(path);
    if (!in) throw SceneError(fmt::format("{}: cannot open scene file", path));
    YAML::Node root;
    try {
        root = YAML::LoadFile(path);
    } catch (const YAML::ParserException& e) {
        throw SceneError(fmt::format("{}:{}:{}: YAML syntax error: {}", path, e.mark.line + 1,
                                     e.mark.column + 1, e.msg));
    }
    std::vector<std::pair<std::string, std::string>> paths;
    for (const auto& o : overrides) {
        apply_override(root, o);
        // "species.1.mass=2" -> "species[1].mass"
        std::string p;
        for (const auto& k : split(o.substr(0, o.find('=')), '.')) {
            const bool index = !k.empty() && std::all_of(k.begin(), k.end(), ::isdigit);
            p += index ? "[" + k + "]" : (p.empty() ? k : "." + k);
        }
        paths.emplace_back(p, o);
    }
    OverrideScope scope(paths);
    return parse_scene(root, path);
}

Scene parse_scene(const YAML::Node& root, const std::string& file) {
    const Where top{file, ""};
    if (!root.IsMap())
        fail(top, root, "expected a scene: a map with keys dimension, box, species, run, ...");
    Scene sc;
    sc.file = file;
    Params tp = read_params(root, top_schema(), top);
    sc.dimension = int(tp.integer("dimension"));
    sc.seed = static_cast<std::uint64_t>(tp.integer("seed"));
    if (tp.has("title")) sc.title = tp.str("title");
    const int d = sc.dimension;
    YAML::Node res;
    if (tp.has("title")) res["title"] = sc.title;
    res["dimension"] = d;
    res["seed"] = sc.seed;
    sc.units = tp.str("units");
    res["units"] = sc.units;
    if (tp.has("gravity")) {
        const std::vector<double> g = tp.reals("gravity");
        if (int(g.size()) != d)
            tp.fail("gravity",
                    fmt::format("expected {} components (one per axis), got {}", d, g.size()));
        for (int a = 0; a < d; ++a) sc.engine.gravity[std::size_t(a)] = g[std::size_t(a)];
        res["gravity"] = g;
    }

    // Species and interactions.
    YAML::Node rs, ri;
    sc.species = read_species(child(root, "species"), child(root, "interactions"),
                              tp.has("particles") ? tp.integer("particles") : 0, top, rs, ri);
    if (tp.has("particles") && std::int64_t(sc.species.total_count()) != tp.integer("particles")) {
        tp.fail("particles", fmt::format("species counts add up to {}, not to particles = {}",
                                         sc.species.total_count(), tp.integer("particles")));
    }
    for (auto& s : sc.species.species) {
        if (s.inertia_factor == 0) s.inertia_factor = d == 2 ? 0.5 : 0.4;
    }
    for (std::size_t k = 0; k < sc.species.size(); ++k)
        rs[k]["inertia_factor"] = sc.species.species[k].inertia_factor;
    res["particles"] = sc.species.total_count();
    res["species"] = rs;
    res["interactions"] = ri;

    // Box.
    const Where wb = top.child("box");
    Params bp = read_params(child(root, "box"), box_schema(), wb);
    const double vd = d == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
    double particle_volume = 0;
    for (const auto& s : sc.species.species)
        particle_volume += double(s.count) * vd * std::pow(s.diameter, d);
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
    double volume = 1;
    for (double l : sc.box_length) volume *= l;
    sc.packing_fraction = particle_volume / volume;
    const double dmax = sc.species.max_diameter();
    for (int a = 0; a < d; ++a) {
        const double need = sc.periodic[a] ? 2 * dmax : dmax;
        if (sc.box_length[a] < need) {
            bp.fail(
                bp.has("lengths") ? "lengths" : "packing_fraction",
                fmt::format("box length {:.4g} along axis {} is below {:.4g} ({})",
                            sc.box_length[a], a, need,
                            sc.periodic[a] ? "twice the largest diameter, needed on a periodic axis"
                                           : "the largest diameter"));
        }
    }
    if (sc.packing_fraction > max_packing_fraction(d)) {
        bp.fail(bp.has("lengths") ? "lengths" : "packing_fraction",
                fmt::format("packing fraction {:.4g} exceeds the densest packing {:.4f} of {}",
                            sc.packing_fraction, max_packing_fraction(d),
                            d == 2 ? "disks" : "spheres"));
    }
    YAML::Node rb;
    for (double l : sc.box_length) rb["lengths"].push_back(l);
    for (bool p : sc.periodic) rb["periodic"].push_back(p);
    res["box"] = rb;
    sc.box_location = locate(wb, child(root, "box"));

    // Initial configuration.
    Params ip = read_params(child(root, "initial"), initial_schema(), top.child("initial"));
    sc.placement = ip.str("placement");
    sc.temperature = ip.real("temperature");
    res["initial"] = ip.resolved();

    // Engine.
    Params ep = read_params(child(root, "engine"), engine_schema(), top.child("engine"));
    sc.engine.tc_guard = ep.str("collapse_guard") == "tc";
    sc.engine.tc = ep.real("tc");
    sc.engine_type = ep.str("type");
    sc.engine_location = locate(top.child("engine"), child(root, "engine"));
    if (sc.engine_type == "dem") read_dem_settings(ep, sc);
    res["engine"] = ep.resolved();

    // Run schedule.
    Params rp = read_params(child(root, "run"), run_schema(), top.child("run"));
    if (sc.engine_type == "dem" && rp.str("unit") != "time") {
        rp.fail("unit", "the dem engine schedules by time: set run.unit: time");
    }
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
    res["run"] = rp.resolved();
    res["run"]["watchdog"] = wp.resolved();

    // Plugins.
    YAML::Node rd, ro;
    sc.drivers = read_plugins(child(root, "drivers"), top.child("drivers"), false, rd);
    sc.observables = read_plugins(child(root, "observables"), top.child("observables"), true, ro);
    res["drivers"] = rd;
    res["observables"] = ro;

    Params op = read_params(child(root, "output"), output_schema(), top.child("output"));
    sc.frames = static_cast<std::size_t>(op.integer("frames"));
    res["output"] = op.resolved();
    sc.resolved = res;
    return sc;
}

}  // namespace gran
