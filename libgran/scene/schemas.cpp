#include "libgran/scene/schemas.hpp"

#include "libgran/scene/interactions.hpp"
#include "libgran/scene/scene.hpp"
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
            list_of(ParamType::Map, "target_error",
                    "measure until each named summary quantity's error bar is below its target: "
                    "{observables.<name>.<quantity>: 0.002 or 1%}; `measurement` is then the "
                    "shortest measurement (see the run section's text)"),
            optional(text("max_cost", "",
                          "with target_error: stop at this cost if the targets are not reached: "
                          "CPU seconds (600, '600 s') or engine work ('1e9 events', '1e8 "
                          "steps')")),
            integer("min_effective_samples", "20",
                    "with target_error: effective samples (n_eff) an error bar needs before a "
                    "target counts as reached",
                    2, 1e12),
            list_of(ParamType::Map, "watchdog",
                    "stops a run that stalls or produces NaN (see section run.watchdog)"),
            list_of(ParamType::Map, "checkpoint",
                    "checkpoints for `gran run --resume` (see section run.checkpoint)")};
}

Schema checkpoint_schema() {
    return {real("interval", "300", "s",
                 "wall-clock seconds between checkpoints (0: none; a run also writes one when "
                 "interrupted)",
                 0, 1e308)};
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
        "trajectory frames (equally spaced in the measurement) written to OUT.trajectory.h5 (H5MD) "
        "and OUT.trajectory.xdmf (ParaView); /particles of OUT.h5 links to them",
        0, 1e6)};
}

namespace {

const char* const kBox =
    R"md(
Give exactly one of `lengths` or `packing_fraction`. Refused: a packing fraction above the
densest packing (0.9069 disks, 0.7405 spheres); a periodic edge shorter than twice the largest
diameter; a bounded edge shorter than the largest diameter. The walls of bounded axes that no wall
driver claims are static walls; in `interactions` they are the wall partner `box`.)md";

const char* const kInteractions =
    R"md(
The single home of contact physics, for both engines. The default law and its keys apply to every
contact: between two species, and between a species and a wall (a wall is a contact partner of
infinite mass that does not rotate). `walls` changes the keys (or the law) of every grain-wall
contact; `pairs` entries change single contacts. A wall partner is named by the wall driver that
puts it there (the driver's `name`, by default its type), or `box` for the walls of bounded axes
that no driver claims. Keys a `walls` or `pairs` entry leaves out take the values of the level
above when it has the same law (a wall pair: `walls`, else the defaults), else the law's own
defaults; the default, `constant_restitution` with its defaults, makes every contact elastic and
smooth. Angular velocities exist only when some contact needs them (a tangential restitution
beta != -1, or friction). Several hard-particle laws may be mixed per contact on the event-driven
engine (one indirect call per collision); the dem engine takes one law for every contact.

```yaml
interactions:
  law: linear_dashpot
  restitution: 0.9
  stiffness: 2.0e+5
  walls: {friction: 0.4}
  pairs:
    - {between: [heavy, light], restitution: 0.8}
    - {between: [heavy, box], restitution: 1}
```

Keys that lived elsewhere before (`engine.contact_law`, `engine.stiffness`, `engine.friction`,
..., a wall driver's `restitution`, `restitution_law`, `r0`, `v0`, `gamma`) are refused with their
new spelling.)md";

const char* const kPairs =
    R"md(
Each entry of `interactions.pairs` names the contact (`between`: two species, or a species and a
wall partner), optionally its own `law`, and that law's keys. A contact given twice, a partner that
does not exist (the message lists the known ones) and a contact between two walls are refused.)md";

const char* const kInitial =
    R"md(
`placement` is one of the placements below (`gran list placements`). Random insertion fails (with
a message) above its jamming limit (about 0.54 for disks, 0.38 for spheres); use `lattice` or
`close_packed` there.)md";

const char* const kEngine =
    R"md(
`type` chooses the engine (`gran list engines`); the other keys of the section are that engine's
numerical settings, listed with it below. A key of the other engine is refused (e.g. `dt_fraction`
on `event_driven`).)md";

const char* const kRun =
    R"md(
`equilibration`, `measurement` and `sample_interval` are in `unit`; the dem engine schedules by
time.

**Runs with a target** (`target_error`): instead of a fixed length, the run measures until every
named quantity's error bar (the blocking or jackknife error of its summary, with its effective
samples n_eff) is below its target and has at least `min_effective_samples` effective samples,
or until `max_cost` is spent. It looks at the error bars after `measurement` and then each time
the measurement has grown by half again (1.5x, 2.25x, ...): a handful of geometrically spaced
looks keeps the bias of stopping on a lucky error small. After the first look it prints, per
quantity, the forecast CPU time to reach its target; `gran check` runs that first look as a
pilot and prints the same forecast. Quantities are named as in a run summary and a study table,
e.g.

    run:
      measurement: 100          # the first look
      target_error: {observables.temperatures.ratios.light_over_heavy.gamma: 0.002,
                     observables.temperatures.T_mixture: 1%}
      max_cost: 600 s

The result's summary has a `target` section: each quantity's target, the error reached, whether
it was met, the status (`reached` or `target_not_reached`, and why), the cost, and the forecast
against the cost spent (docs/choosing-speed-or-accuracy.md, "Runs with a target").)md";

const char* const kWatchdog =
    R"md(
Stops a run that would hang or silently produce NaN, with an error naming what happened, the
simulated time and what to change; the result is written with what was measured
(`/performance/completed = 0`, the message in the `/performance` attribute `watchdog_stop`, summary
`status: stopped by the watchdog` and `error`), and `gran run` exits with status 1. Checks run
between chunks of work, never per event (libgran/run/watchdog.hpp). On both engines positions,
velocities, angular velocities and the kinetic energy are checked to be finite at every sample and
every window.)md";

const char* const kCheckpoint =
    R"md(
Every `interval` seconds of wall-clock time, and when the run is interrupted (SIGINT, SIGTERM,
SIGHUP, SIGUSR1, SIGXCPU), the run writes OUT.h5.checkpoint: the complete state (particles and
their clocks, pending events or forces and contact history, every random stream, the drivers'
and observables' accumulators, the schedule position), atomically. `gran run --resume OUT.h5`
continues from it and gives the same result, bit for bit, as a run never interrupted
(docs/reliability.md). Trajectory frames go to OUT.h5.frames.part while the run goes on. Both
files are removed once the run has ended (completed, or stopped by the watchdog); an interrupted
run keeps them for the resume.)md";

}  // namespace

std::vector<SectionDoc> scene_sections() {
    return {
        {"scene", "top-level keys of a scene file", top_schema()},
        {"box", "box geometry: give lengths, or packing_fraction (and aspect)", box_schema(), kBox},
        {"species", "one entry per species", species_schema()},
        {"interactions",
         "the contact law of every contact and its keys (`gran list laws`), `walls` for every "
         "grain-wall contact, `pairs` for single contacts",
         interactions_schema(), kInteractions},
        {"interactions.pairs[]",
         "one contact: two species, or a species and a wall partner (a wall driver's name, or "
         "`box`), and the law keys to change",
         pair_override_schema(), kPairs},
        {"initial", "initial configuration", initial_schema(), kInitial},
        {"engine",
         "engine type; its numerical settings are listed with each engine",
         {text("type", "event_driven", "simulation engine (`gran list engines`)")},
         kEngine},
        {"run", "run schedule", run_schema(), kRun},
        {"run.watchdog", "stops runs that hang or produce NaN (on by default)", watchdog_schema(),
         kWatchdog},
        {"run.checkpoint", "checkpoints a killed or interrupted run resumes from",
         checkpoint_schema(), kCheckpoint},
        {"output", "output settings", output_schema()}};
}

std::string scene_reference_introduction() {
    return R"md(
A scene is one YAML file. Every key is checked: unknown keys, wrong types, out-of-range values and
inconsistent combinations stop the run with `file:line:column: key.path: what was expected`;
`gran check SCENE.yaml` makes every check `gran run` makes, the initial placement included,
without running (and without building an engine).

Units are reduced: lengths, masses and temperatures (energies, k_B = 1) are whatever the scene uses;
time follows as length * sqrt(mass/energy). A typical choice is diameter 1, mass 1, T0 = 1. With
`units: SI` the numbers are read as m, kg, s, Hz and J instead (no number is converted).

`gran list [scene|laws|engines|drivers|observables|placements]` prints the keys below as plain
text.)md";
}

}  // namespace gran
