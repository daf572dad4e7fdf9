// The scene sections as `gran list` documents them: each schema with its summary and the prose of
// docs/scene-reference.md. The prose of drivers, observables and pair laws lives with their
// registrations.
#include "libgran/scene/scene.hpp"
#include "libgran/scene/scene_schemas.hpp"
#include "species/species.hpp"

namespace gran {

namespace {

const char* const kBox =
    R"md(
Give exactly one of `lengths` or `packing_fraction`. Refused: a packing fraction above the
densest packing (0.9069 disks, 0.7405 spheres); a periodic edge shorter than twice the largest
diameter; a bounded edge shorter than the largest diameter.)md";

const char* const kInteractions =
    R"md(
The default law and its parameters apply to every pair; `pairs` overrides chosen pairs. Besides
`law` and `pairs` the section takes the parameters of its law (see the pair laws below); the
default, `constant_restitution` with its defaults, makes every pair elastic and smooth. Angular
velocities are allocated (and the rough collision rule used) only when some pair has beta != -1.)md";

const char* const kPairs =
    R"md(
Each entry of `interactions.pairs` names the pair (`between`), optionally its own `law`, and
that law's parameters. Parameters not given keep the values of the `interactions` section when the
pair uses the same law, else the law's defaults.)md";

const char* const kInitial =
    R"md(
Random insertion fails (with a message) above its jamming limit (about 0.54 for disks, 0.38
for spheres); use `lattice` there.)md";

const char* const kEngine =
    R"md(
`event_driven`: hard particles, instantaneous collisions (the pair laws below). Its
`collapse_guard: tc` is the TC model (Luding & McNamara 1998): a collision within `tc` of a previous
collision of either partner is elastic; such collisions are counted in
`/performance/tc_guard_collisions`.

`dem`: time-stepped soft spheres with friction and rotation (Bhateja, Sharma & Singh 2016,
Appendix). The same scene runs on this engine with `type: dem` and the keys marked dem (ignored by
the event-driven engine). Grain-grain restitution e_p is the pair law's `alpha` (law
`constant_restitution`, `beta: -1`: roughness on this engine is friction); wall restitution e_w is
the wall driver's `restitution` (walls without a driver are elastic). The schedule must be in time
(`run.unit: time`). Give `stiffness` or `contact_time`, not both; walls use the same k_n as the
grains. `dt_fraction` above 1/5 is refused (velocity Verlet needs 5 steps per contact). Contacts of
every pair and wall use one `contact_law`:

- `linear_dashpot`: the paper's Eqs. (A5)-(A9), F_n = k_n delta - c_n g_n with c_n from e (reduced
  mass of the pair, or the grain's mass at a wall), tangential dashpot
  F_t = -min(c_t |g_t|, mu |F_n|) t, no tangential spring (so c_t = 0 makes friction inactive);
- `cundall_strack`: the same normal force and a tangential spring k_t with history, Coulomb-capped;
- `hertz_mindlin`: F_n = k_n delta^(3/2) with Tsuji damping and a Mindlin tangential spring.

A dem run reports under `/performance`: `dt`, `dt_over_tc` (the largest over the contact kinds),
`steps`, `particle_steps_per_second`, contacts formed, `max_overlap` (largest delta / sigma), and
`isolated_collisions/<pair>` and `<species>-wall_e<e_w>`: the restitution and contact time an
isolated head-on collision achieves on the engine itself at this dt, next to the requested e and the
closed-form t_c. Drivers on this engine: `static_wall` and `vibrating_wall` (waveforms
`two_parabolas`, `sinusoid` and a real `sawtooth`, constant `restitution`); others are refused with
the reason, as are observables that need binary collision records (`restitution_statistics`;
`profiles` skips its collisional pressure). A collision counted by `collision_statistics` is a
contact that formed.)md";

const char* const kRun =
    R"md(
`equilibration`, `measurement` and `sample_interval` are in `unit`.)md";

const char* const kWatchdog =
    R"md(
Stops a run that would hang or silently produce NaN, with an error naming what happened, the
simulated time and what to change; the result is written with what was measured
(`/performance/completed = 0`, the message in the `/performance` attribute `watchdog_stop`, summary
`status: stopped by the watchdog` and `error`), and `gran run` exits with status 1. Checks run
between chunks of work, never per event (libgran/run/watchdog.hpp). On both engines positions,
velocities, angular velocities and the kinetic energy are checked to be finite at every sample and
every window.)md";

}  // namespace

std::vector<SectionDoc> scene_sections() {
    return {
        {"scene", "top-level keys of a scene file", top_schema()},
        {"box", "box geometry: give lengths, or packing_fraction (and aspect)", box_schema(), kBox},
        {"species", "one entry per species", species_schema()},
        {"interactions",
         "default pair law and its parameters, plus `pairs` overrides (see `gran list laws`)",
         interactions_schema(), kInteractions},
        {"interactions.pairs[]", "per-pair override: the pair and the law parameters to change",
         pair_override_schema(), kPairs},
        {"initial", "initial configuration", initial_schema(), kInitial},
        {"engine", "engine and numerical settings", engine_schema(), kEngine},
        {"run", "run schedule", run_schema(), kRun},
        {"run.watchdog", "stops runs that hang or produce NaN (on by default)", watchdog_schema(),
         kWatchdog},
        {"output", "output settings", output_schema()}};
}

std::string scene_reference_introduction() {
    return R"md(
A scene is one YAML file. Every key is checked: unknown keys, wrong types, out-of-range values and
inconsistent combinations stop the run with `file:line:column: key.path: what was expected`;
`gran check SCENE.yaml` validates a scene (and its initial placement) without running it.

Units are reduced: lengths, masses and temperatures (energies, k_B = 1) are whatever the scene uses;
time follows as length * sqrt(mass/energy). A typical choice is diameter 1, mass 1, T0 = 1. With
`units: SI` the numbers are read as m, kg, s, Hz and J instead (no number is converted).

`gran list [scene|laws|drivers|observables]` prints the keys below as plain text.)md";
}

}  // namespace gran
