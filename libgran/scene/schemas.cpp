#include "libgran/scene/schemas.hpp"

#include "libgran/scene/scene.hpp"

#include "libgran/scene/interactions.hpp"
#include "libgran/scene/species.hpp"

namespace gran {

ParamSpec list_of(ParamType t, std::string name, std::string doc, bool opt) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = t;
    s.doc = std::move(doc);
    s.optional = opt;
    return s;
}

namespace {
ParamSpec gravity_spec() {
    ParamSpec g = real("gravity", "", "length/time^2",
                       "uniform gravitational acceleration vector, one component per axis (e.g. "
                       "[0, -9.81] in SI); parabolic free flight in the event-driven engine");
    g.type = ParamType::RealList;
    g.optional = true;
    g.default_value = "";
    return g;
}

}  // namespace

Schema top_schema() {
    return {
        optional(text("title", "", "free text describing the scene")),
        integer("dimension", "", "2 (disks) or 3 (spheres)", 2, 3),
        integer("seed", "1", "random seed: the same scene and seed give identical results", 0,
                9.2e18),
        optional(integer("particles", "",
                         "total number of particles (when species give number_fraction)", 1, 1e9)),
        list_of(ParamType::Map, "box", "box geometry (see section box)", false),
        list_of(ParamType::List, "species", "list of species (see section species)", false),
        list_of(ParamType::Map, "interactions",
                "contact laws of every grain-grain and grain-wall contact (see section "
                "interactions)"),
        list_of(ParamType::Map, "initial", "initial configuration (see section initial)"),
        list_of(ParamType::List, "drivers",
                "energy injection: list of {type: <driver>, ...} (`gran list drivers`)"),
        list_of(ParamType::List, "observables",
                "measurements: list of {type: <observable>, ...} (`gran list observables`)"),
        list_of(ParamType::Map, "engine",
                "engine (`type`) and its numerical settings (`gran list engines`)"),
        list_of(ParamType::Map, "run", "run schedule (see section run)", false),
        list_of(ParamType::Map, "output", "output settings (see section output)"),
        gravity_spec(),
        choice("units", "reduced", {"reduced", "SI"},
               "unit system the numbers are written in: reduced (lengths, masses and energies as "
               "given, k_B = 1) or SI (m, kg, s, Hz, J; e.g. McNamara & Falcon 2005)"),
    };
}

Schema box_schema() {
    ParamSpec lengths =
        real("lengths", "", "length", "box edge lengths, one per axis", 0, 1e308, true);
    lengths.type = ParamType::RealList;
    lengths.optional = true;
    lengths.default_value = "";
    ParamSpec aspect =
        real("aspect", "", "", "edge-length ratios used with packing_fraction (default all 1)", 0,
             1e308, true);
    aspect.type = ParamType::RealList;
    aspect.optional = true;
    ParamSpec periodic =
        boolean("periodic", "", "per axis: periodic (true) or bounded by static elastic walls");
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
                   "random non-overlapping insertion, a square/cubic lattice, or a hexagonal/fcc "
                   "lattice (close_packed: up to the densest packing)"),
            real("temperature", "1", "energy", "initial temperature of every species (Maxwellian)",
                 0, 1e308, true)};
}

Schema run_schema() {
    return {choice("unit", "collisions_per_particle", {"collisions_per_particle", "time"},
                   "unit of the schedule lengths (collisions per particle = 2 N_coll / N)"),
            real("equilibration", "0", "unit", "length of the equilibration phase (not measured)",
                 0, 1e308),
            real("measurement", "", "unit", "length of the measurement phase", 0, 1e308, true),
            real("sample_interval", "1", "unit", "interval between samples of the observables", 0,
                 1e308, true),
            real("progress_interval", "10", "s",
                 "seconds between progress log lines when not on a terminal", 0, 1e308, true),
            list_of(ParamType::Map, "watchdog",
                    "stops a run that stalls or produces NaN (see section run.watchdog)")};
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
             "per TC window engine.tc than this (resting contacts resolved by micro-collisions)",
             0, 1e308, true)};
}

Schema output_schema() {
    return {integer(
        "frames", "0",
        "trajectory frames written under /particles (equally spaced in the measurement)", 0, 1e6)};
}

std::vector<SectionDoc> scene_sections() {
    return {
        {"scene", "top-level keys of a scene file", top_schema()},
        {"box", "box geometry: give lengths, or packing_fraction (and aspect)", box_schema()},
        {"species", "one entry per species", species_schema()},
        {"interactions",
         "the contact law of every contact and its keys (`gran list laws`), `walls` for every "
         "grain-wall contact, `pairs` for single contacts",
         interactions_schema()},
        {"interactions.pairs[]",
         "one contact: two species, or a species and a wall partner (a wall driver's name, or "
         "`box`), and the law keys to change",
         pair_override_schema()},
        {"initial", "initial configuration", initial_schema()},
        {"engine", "engine type; its numerical settings are listed by `gran list engines`",
         {text("type", "event_driven", "simulation engine (`gran list engines`)")}},
        {"run", "run schedule", run_schema()},
        {"run.watchdog", "stops runs that hang or produce NaN (on by default)", watchdog_schema()},
        {"output", "output settings", output_schema()}};
}

}  // namespace gran
