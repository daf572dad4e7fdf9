#!/usr/bin/python3
"""Accuracy and cost of the stochastic thermostat against its kick interval (issue 15,
docs/physics.md).

    PYTHONPATH=python /usr/bin/python3 bench/thermostat_kicks.py [--out results/thermostat_kicks]
        [--particles 1000] [--measurement 600] [--seeds 1,2] [--cases m3a085,m10a05,mono3d]
        [--intervals 1/8,1/2,1,2]

For each case (a heated dilute gas, phi = 0.02, with a known white-noise theory) it runs the
thermostat with kicks every 1/32 of the mean free time (the reference: closest to white noise) and
at each of --intervals (in mean free times; the default interval is 1/8), with the same seeds, and
prints per interval the measured temperature ratio gamma = T_light / T_heavy
(binary cases) with its error bar, the Sonine coefficient a2 of each species (the `temperatures`
observable's sonine_a2), the CPU time per collision and its ratio to the reference, and the theory:
gamma from the Maxwellian theory of the heated mixture (libgran/core/kinetic_theory.cpp) and a2
from van Noije & Ernst, Granular Matter 1, 57 (1998), Eq. for the white-noise heated state:
  a2 = 16 (1 - alpha)(1 - 2 alpha^2) / (73 + 56 d - 24 d alpha - 105 alpha + 30 (1 - alpha) alpha^2).
Seeds are combined by inverse-variance weighting. The CPU times come from each run's own
performance group (the run loop's process CPU time), so other load on the machine inflates them.
"""

import argparse
import math
from pathlib import Path

import gran

CASES = {
    # name: (dimension, heavy mass, alpha)
    "m3a085": (2, 3.0, 0.85),
    "m10a05": (2, 10.0, 0.5),
    "mono3d": (3, 1.0, 0.5),
}


# Maxwellian theory of the heated mixture (libgran/core/kinetic_theory.cpp, the values
# docs/physics.md and tests/drivers/test_stochastic_thermostat.cpp compare with).
THEORY_GAMMA = {"m3a085": 0.7459, "m10a05": 0.1848}


def a2_white_noise(d, alpha):
    return 16 * (1 - alpha) * (1 - 2 * alpha**2) / (
        73 + 56 * d - 24 * d * alpha - 105 * alpha + 30 * (1 - alpha) * alpha**2)


def scene_dict(case, particles, measurement, seed, interval_fraction):
    d, mass, alpha = CASES[case]
    phi = 0.02
    species = [{"name": "heavy", "mass": mass, "diameter": 1, "number_fraction": 0.5},
               {"name": "light", "mass": 1, "diameter": 1, "number_fraction": 0.5}]
    if mass == 1.0:
        species = [{"name": "gas", "mass": 1, "diameter": 1, "number_fraction": 1}]
    # The strength only sets the temperature scale (T ~ 1 here); the ratios do not depend on it.
    thermostat = {"type": "stochastic_thermostat", "strength": 0.01 if d == 2 else 0.02}
    scene = {
        "dimension": d,
        "seed": seed,
        "particles": particles,
        "species": species,
        "interactions": {"alpha": alpha},
        "box": {"packing_fraction": phi},
        "drivers": [thermostat],
        "observables": [{"type": "temperatures"}],
        "run": {"unit": "collisions_per_particle", "equilibration": 100,
                "measurement": measurement, "sample_interval": 1},
    }
    s = gran.Scene.from_dict(scene)
    s.set("drivers.0.interval", default_interval(s) * 8 * interval_fraction)
    return s


def default_interval(scene):
    """The thermostat's default interval (1/8 of the Enskog mean free time at the initial
    temperature), as the driver reports it after a run of one collision per particle."""
    probe = gran.Scene.from_yaml(scene.to_yaml())
    probe.set("run.equilibration", 0).set("run.measurement", 2).set("run.sample_interval", 1)
    summary = gran.run(probe, progress=False).summary
    return summary["drivers"]["stochastic_thermostat"]["interval"]["value"]


def combine(values):
    """Inverse-variance weighted mean of (value, error) pairs."""
    w = [1 / e**2 for _, e in values if e > 0]
    if len(w) != len(values):
        return values[0]
    mean = sum(wi * v for wi, (v, _) in zip(w, values)) / sum(w)
    return mean, 1 / math.sqrt(sum(w))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="results/thermostat_kicks")
    ap.add_argument("--particles", type=int, default=1000)
    ap.add_argument("--measurement", type=float, default=600)
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--intervals", default="1/8,1/2,1,2",
                    help="kick intervals to compare with the 1/32 reference, in mean free times")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    seeds = [int(x) for x in args.seeds.split(",")]
    schemes = [("1/32", 1 / 32)]
    for f in args.intervals.split(","):
        num, _, den = f.partition("/")
        schemes.append((f, float(num) / float(den or 1)))
    print("| case | kicks every (mean free times) | gamma | a2 (per species) | CPU us/collision "
          "| cost / reference |")
    print("|---|---|---|---|---|---|")
    for case in args.cases.split(","):
        d, mass, alpha = CASES[case]
        rows = []
        for label, frac in schemes:
            gammas, a2s, cpu, coll = [], {}, 0.0, 0
            for seed in seeds:
                s = scene_dict(case, args.particles, args.measurement, seed, frac)
                tag = label.replace(" ", "_").replace("/", "-")
                r = gran.run(s, output=str(out / f"{case}_{tag}_s{seed}.h5"), progress=False)
                summ = r.summary
                obs = summ["observables"]
                if mass != 1.0:
                    g = obs["temperatures"]["ratios"]["light_over_heavy"]["gamma"]
                    gammas.append((g["value"], g["error"]))
                for sp, v in obs["temperatures"]["species"].items():
                    a2 = v["sonine_a2"]
                    a2s.setdefault(sp, []).append((a2["value"], a2["error"]))
                perf = summ["performance"]
                cpu += perf["cpu_time"]["value"]
                coll += perf["collisions"]
            rows.append((label, combine(gammas) if gammas else None,
                         {sp: combine(v) for sp, v in a2s.items()}, 1e6 * cpu / coll))
        ref_cost = rows[0][3]
        for label, g, a2, cost in rows:
            gs = f"{g[0]:.4f} ± {g[1]:.4f}" if g else "-"
            a2s = ", ".join(f"{sp} {v:+.4f} ± {e:.4f}" for sp, (v, e) in a2.items())
            print(f"| {case} | {label} | {gs} | {a2s} | {cost:.3f} | {cost / ref_cost:.2f} |")
        theory = []
        if mass != 1.0:
            theory.append(f"gamma (Maxwellian) {THEORY_GAMMA[case]:.4f}")
        theory.append(f"a2 (white noise, one species) {a2_white_noise(d, alpha):+.4f}")
        print(f"| {case} | theory | {'; '.join(theory)} | | | |")


if __name__ == "__main__":
    main()
