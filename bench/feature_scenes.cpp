#include "bench/feature_scenes.hpp"

#include <stdexcept>

namespace gran::bench {

namespace {

YAML::Node flow_list(std::initializer_list<YAML::Node> items) {
    YAML::Node l(YAML::NodeType::Sequence);
    for (const auto& x : items) l.push_back(x);
    return l;
}

// Bounded last axis (static elastic walls at 0 and L), the other axes periodic.
void add_walls(YAML::Node& s, const Geometry& g) {
    YAML::Node periodic(YAML::NodeType::Sequence);
    for (int a = 0; a < g.dim; ++a) periodic.push_back(a + 1 < g.dim);
    s["box"]["periodic"] = periodic;
}

// Gravity along the bounded axis with scale height T / (m g) = L / 2 (T = m = 1): the gas is
// stratified but fills the box.
void add_gravity(YAML::Node& s, const Geometry& g) {
    YAML::Node acc(YAML::NodeType::Sequence);
    for (int a = 0; a < g.dim; ++a) acc.push_back(a + 1 < g.dim ? 0.0 : -2.0 / g.box_length());
    s["gravity"] = acc;
}

void add_driver(YAML::Node& s, const YAML::Node& d) {
    s["drivers"].push_back(d);
}

void add_observable(YAML::Node& s, const std::string& type,
                    std::initializer_list<std::pair<const char*, YAML::Node>> params = {}) {
    YAML::Node o;
    o["type"] = type;
    for (const auto& [k, v] : params) o[k] = v;
    s["observables"].push_back(o);
}

Feature observable(const std::string& type, const std::string& baseline, const std::string& engine,
                   std::function<void(YAML::Node&, const Geometry&)> add) {
    const std::string prefix = engine == "dem" ? "dem_" : "";
    return {prefix + "obs_" + type, "observable " + type, baseline, engine, std::move(add)};
}

// Adds the observable `type` with the parameter axis: the last axis.
std::function<void(YAML::Node&, const Geometry&)> on_last_axis(const char* type) {
    return [type](YAML::Node& s, const Geometry& g) {
        add_observable(s, type, {{"axis", YAML::Node(g.last_axis())}});
    };
}

// Adds the observable `type` with its default parameters.
std::function<void(YAML::Node&, const Geometry&)> plain(const char* type) {
    return [type](YAML::Node& s, const Geometry&) { add_observable(s, type); };
}

// Event-driven: the bare gas, then laws and species.
void add_law_features(std::vector<Feature>& f, const Calibration& cal) {
    const std::string ed = "event_driven";
    f.push_back({"bare", "bare gas (elastic smooth, periodic)", "", ed, {}});
    f.push_back({"rotations", "rough particles (beta = 1: rotation, energy conserved)", "bare", ed,
                 [](YAML::Node& s, const Geometry&) { s["interactions"]["beta"] = 1.0; }});
    f.push_back({"inelastic", "inelastic (alpha = 0.9, free cooling)", "bare", ed,
                 [](YAML::Node& s, const Geometry&) { s["interactions"]["alpha"] = 0.9; }});
    f.push_back({"impact_restitution",
                 "impact-speed restitution (mcnamara_falcon r0 0.9, v0 1.5) vs alpha = 0.9",
                 "inelastic", ed, [](YAML::Node& s, const Geometry&) {
                     s["interactions"].remove("alpha");
                     s["interactions"]["law"] = "mcnamara_falcon";
                     s["interactions"]["r0"] = 0.9;
                     s["interactions"]["v0"] = 1.5;
                 }});
    f.push_back({"thermostat",
                 "stochastic thermostat (default interval, T ~ 1) vs alpha = 0.9 free cooling",
                 "inelastic", ed, [cal](YAML::Node& s, const Geometry& g) {
                     // Heating strength balances cooling at T = 1: dT/dt = strength (m = 1)
                     // against (1 - alpha^2) omega T / d (docs/physics.md, Haff's law).
                     YAML::Node d;
                     d["type"] = "stochastic_thermostat";
                     d["strength"] = (1 - 0.81) * cal.omega / g.dim;
                     add_driver(s, d);
                 }});
    f.push_back({"mixture_mass", "binary mixture, masses 3:1 (equal diameters)", "bare", ed,
                 [](YAML::Node& s, const Geometry& g) {
                     YAML::Node a, b;
                     a["name"] = "heavy";
                     a["mass"] = 3.0;
                     a["count"] = g.n / 2;
                     b["name"] = "light";
                     b["count"] = g.n - g.n / 2;
                     s["species"] = flow_list({a, b});
                 }});
    f.push_back({"mixture_size", "binary mixture, diameters 1.4:1 (same packing fraction)", "bare",
                 ed, [](YAML::Node& s, const Geometry& g) {
                     YAML::Node a, b;
                     a["name"] = "large";
                     a["diameter"] = 1.4;
                     a["count"] = g.n / 2;
                     b["name"] = "small";
                     b["count"] = g.n - g.n / 2;
                     s["species"] = flow_list({a, b});
                 }});
}

// Event-driven: walls, gravity and the wall drivers.
void add_wall_features(std::vector<Feature>& f) {
    const std::string ed = "event_driven";
    f.push_back({"walls", "static elastic walls on the last axis", "bare", ed, add_walls});
    f.push_back({"gravity", "gravity (scale height L/2) vs walls", "walls", ed, add_gravity});
    f.push_back({"sawtooth_wall", "sawtooth walls (v0 = 1, both) vs static walls", "walls", ed,
                 [](YAML::Node& s, const Geometry& g) {
                     YAML::Node d;
                     d["type"] = "sawtooth_wall";
                     d["axis"] = g.last_axis();
                     d["velocity"] = 1.0;
                     add_driver(s, d);
                 }});
    f.push_back({"thermal_wall", "thermal walls (T0 = 1, both) vs static walls", "walls", ed,
                 [](YAML::Node& s, const Geometry& g) {
                     YAML::Node d;
                     d["type"] = "thermal_wall";
                     d["axis"] = g.last_axis();
                     d["temperature"] = 1.0;
                     add_driver(s, d);
                 }});
    f.push_back({"vibrating_wall", "vibrating floor (two_parabolas, A = 1, V = 1) vs gravity",
                 "gravity", ed, [](YAML::Node& s, const Geometry& g) {
                     YAML::Node d;
                     d["type"] = "vibrating_wall";
                     d["axis"] = g.last_axis();
                     d["amplitude"] = 1.0;
                     d["frequency"] = 0.25;
                     add_driver(s, d);
                 }});
}

// Event-driven: observables and trajectory output.
void add_observable_features(std::vector<Feature>& f) {
    const std::string ed = "event_driven";
    f.push_back(observable("temperatures", "bare", ed, plain("temperatures")));
    f.push_back(observable("velocity_pdf", "bare", ed, plain("velocity_pdf")));
    f.push_back(observable("angular_velocity_pdf", "rotations", ed, plain("angular_velocity_pdf")));
    f.push_back(observable("profiles", "bare", ed, on_last_axis("profiles")));
    f.push_back({"obs_profiles_no_pressure", "observable profiles, pressure: false", "bare", ed,
                 [](YAML::Node& s, const Geometry& g) {
                     add_observable(
                         s, "profiles",
                         {{"axis", YAML::Node(g.last_axis())}, {"pressure", YAML::Node(false)}});
                 }});
    f.push_back(observable("collision_statistics", "bare", ed, plain("collision_statistics")));
    f.push_back(
        observable("restitution_statistics", "inelastic", ed, plain("restitution_statistics")));
    f.push_back(observable("kinetic_energy", "bare", ed, plain("kinetic_energy")));
    f.push_back(observable("slab_velocity_pdf", "bare", ed, on_last_axis("slab_velocity_pdf")));
    f.push_back(observable("wall_pressure", "walls", ed, on_last_axis("wall_pressure")));
    f.push_back(observable("local_temperature", "walls", ed, on_last_axis("local_temperature")));
    f.push_back(observable("barycentric_height", "walls", ed, on_last_axis("barycentric_height")));
    f.push_back({"frames", "trajectory output (output.frames: 20)", "bare", ed,
                 [](YAML::Node& s, const Geometry&) { s["output"]["frames"] = 20; }});
}

// DEM: the bare gas, laws, walls, gravity, observables and trajectory output.
void add_dem_features(std::vector<Feature>& f) {
    const std::string dem = "dem";
    f.push_back({"dem_bare", "DEM bare gas (elastic, frictionless, periodic)", "", dem, {}});
    f.push_back({"dem_friction", "DEM friction (cundall_strack, mu = 0.5, e = 0.9) vs e = 0.9",
                 "dem_inelastic", dem, [](YAML::Node& s, const Geometry&) {
                     s["interactions"]["law"] = "cundall_strack";
                     s["interactions"]["friction"] = 0.5;
                 }});
    f.push_back({"dem_inelastic", "DEM inelastic (e = 0.9)", "dem_bare", dem,
                 [](YAML::Node& s, const Geometry&) { s["interactions"]["restitution"] = 0.9; }});
    f.push_back({"dem_walls", "DEM static walls on the last axis", "dem_bare", dem, add_walls});
    f.push_back(
        {"dem_gravity", "DEM gravity (scale height L/2) vs walls", "dem_walls", dem, add_gravity});
    f.push_back(observable("temperatures", "dem_bare", dem, plain("temperatures")));
    f.push_back(observable("velocity_pdf", "dem_bare", dem, plain("velocity_pdf")));
    f.push_back(observable("profiles", "dem_bare", dem, on_last_axis("profiles")));
    f.push_back(observable("collision_statistics", "dem_bare", dem, plain("collision_statistics")));
    f.push_back(observable("kinetic_energy", "dem_bare", dem, plain("kinetic_energy")));
    f.push_back({"dem_frames", "DEM trajectory output (output.frames: 20)", "dem_bare", dem,
                 [](YAML::Node& s, const Geometry&) { s["output"]["frames"] = 20; }});
}

}  // namespace

YAML::Node bare_scene(const std::string& engine, const Geometry& g, const RunLength& run) {
    YAML::Node s;
    s["dimension"] = g.dim;
    s["seed"] = 7;
    YAML::Node sp;
    sp["name"] = "grain";
    sp["count"] = g.n;
    s["species"] = flow_list({sp});
    s["box"]["packing_fraction"] = g.phi;
    // A lattice start (random insertion cannot reach phi = 0.5 in 2D), melted by the
    // equilibration.
    s["initial"]["placement"] = "lattice";
    s["initial"]["temperature"] = 1.0;
    if (engine == "dem") {
        // Soft spheres, elastic (e = 1), frictionless: the DEM counterpart of the bare gas.
        // Contacts last t_c = 0.01, 1/60 (phi = 0.1) to 1/10 (phi = 0.3) of the mean free time
        // of spheres at T = 1; dt = t_c / 50.
        s["engine"]["type"] = "dem";
        s["interactions"]["law"] = "linear_dashpot";
        s["interactions"]["contact_time"] = 0.01;
        s["run"]["unit"] = "time";
        s["run"]["equilibration"] = 0.0;
        s["run"]["measurement"] = run.dem_measurement;
        s["run"]["sample_interval"] = run.dem_measurement / run.samples;
    } else {
        s["run"]["equilibration"] = run.ed_equilibration;
        s["run"]["measurement"] = run.ed_measurement;
        s["run"]["sample_interval"] = run.ed_measurement / run.samples;
    }
    return s;
}

std::vector<Feature> features(const Calibration& cal) {
    std::vector<Feature> f;
    add_law_features(f, cal);
    add_wall_features(f);
    add_observable_features(f);
    add_dem_features(f);
    return f;
}

YAML::Node feature_scene(const std::vector<Feature>& all, const std::string& key, const Geometry& g,
                         const RunLength& run) {
    for (const auto& f : all) {
        if (f.key != key) continue;
        if (f.baseline.empty()) return bare_scene(f.engine, g, run);
        YAML::Node s = feature_scene(all, f.baseline, g, run);
        f.add(s, g);
        return s;
    }
    throw std::invalid_argument("no feature " + key);
}

}  // namespace gran::bench
