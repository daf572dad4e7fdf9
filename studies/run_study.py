#!/usr/bin/python3
"""Run a gran study: one base scene, a list of points (each a set of scene-key overrides), replicas,
on all local cores; resume by skipping points whose result is complete.

Usage: /usr/bin/python3 studies/run_study.py STUDY.yaml [-o OUTDIR] [-j JOBS] [--gran build/gran]

Study file keys:
  scene:     path of the base scene (relative to the study file)
  points:    list of {name: ..., set: {key: value, ...}, ...any extra fields kept as metadata}
  grid:      optional {key: [v1, v2, ...], ...}: every point is combined with every grid combination
  replicas:  number of seeds per point (default 1; seeds 1..replicas)
Each run writes OUTDIR/<point>[_r<k>].h5 (and its summary); a point whose file exists with
/performance/completed == 1 is not run again. A table of all runs goes to OUTDIR/runs.csv.
"""
import argparse
import csv
import itertools
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import yaml


def expand(study):
    points = study.get("points") or [{"name": "point", "set": {}}]
    grid = study.get("grid") or {}
    keys = list(grid)
    combos = list(itertools.product(*(grid[k] for k in keys))) or [()]
    replicas = int(study.get("replicas", 1))
    runs = []
    for p in points:
        for combo in combos:
            overrides = dict(p.get("set", {}))
            suffix = ""
            for k, v in zip(keys, combo):
                overrides[k] = v
                suffix += f"_{k.split('.')[-1]}{v}"
            for r in range(1, replicas + 1):
                name = p["name"] + suffix + (f"_r{r}" if replicas > 1 else "")
                if replicas > 1:
                    overrides = dict(overrides, seed=r)
                runs.append({"name": name, "point": p, "set": dict(overrides)})
    return runs


def complete(path):
    try:
        with h5py.File(path, "r") as f:
            return int(f["performance/completed"][()]) == 1
    except (OSError, KeyError):
        return False


def run_one(gran, scene, outdir, run):
    out = outdir / f"{run['name']}.h5"
    if complete(out):
        return run["name"], "reused"
    cmd = [gran, "run", str(scene), "-o", str(out), "-q"]
    for k, v in run["set"].items():
        cmd += ["--set", f"{k}={yaml.safe_dump(v, default_flow_style=True).strip().removesuffix('...').strip()}"]
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        raise RuntimeError(f"{run['name']}: {' '.join(cmd)}\n{res.stderr}")
    return run["name"], "ran"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study")
    ap.add_argument("-o", "--outdir")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--gran", default="build/gran")
    args = ap.parse_args()
    study_path = Path(args.study)
    study = yaml.safe_load(study_path.read_text())
    scene = study_path.parent / study["scene"]
    outdir = Path(args.outdir or Path("results") / study_path.parent.name)
    outdir.mkdir(parents=True, exist_ok=True)
    runs = expand(study)
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        done = list(pool.map(lambda r: run_one(args.gran, scene, outdir, r), runs))
    for name, how in done:
        print(f"{how:7s} {name}")
    with open(outdir / "runs.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["name", "result", "overrides"])
        for r in runs:
            w.writerow([r["name"], str(outdir / f"{r['name']}.h5"), ";".join(f"{k}={v}" for k, v in r["set"].items())])
    print(f"{sum(1 for _, h in done if h == 'ran')} run, {sum(1 for _, h in done if h == 'reused')} reused; "
          f"table: {outdir / 'runs.csv'}")


if __name__ == "__main__":
    sys.exit(main())
