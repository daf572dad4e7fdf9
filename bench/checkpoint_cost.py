#!/usr/bin/python3
"""What checkpoints cost a run (docs/reliability.md, "Checkpoint cost").

    bench/checkpoint_cost.py GRAN [--pairs K] [--stress S] [--out DIR]

For the demo (studies/demo/vibrated-mixture-2d.yaml) and 10^5 thermostatted disks
(bench/checkpoint_cost/thermostat-1e5.yaml):
  1. K pairs of runs, alternating, with the default interval (run.checkpoint.interval = 300 s)
     and with checkpoints off (0): the median ratio of their wall-clock times;
  2. one run with a checkpoint every S seconds (default 5): the time each checkpoint took, as the
     run measures it (/performance/checkpoint_time over /performance/checkpoints), and the
     fraction of a run it would cost at the default interval (time per checkpoint / 300 s).
"""
import argparse
import pathlib
import statistics
import subprocess
import sys

import h5py

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENES = {"demo": ROOT / "studies/demo/vibrated-mixture-2d.yaml",
          "1e5 disks": ROOT / "bench/checkpoint_cost/thermostat-1e5.yaml"}
DEFAULT_INTERVAL = 300.0


def run(gran, scene, out, interval):
    subprocess.run([gran, "run", str(scene), "-o", str(out), "-q", "--set",
                    f"run.checkpoint.interval={interval}"], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(out, "r") as f:
        p = f["performance"]
        return {k: float(p[k][()]) for k in ("wall_time", "checkpoints", "checkpoint_time")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gran")
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--stress", type=float, default=5.0)
    ap.add_argument("--out", default="results/checkpoint_cost")
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    print("| scene | wall time, default interval / off (median of %d pairs) | checkpoints at the "
          "default interval | s per checkpoint (every %g s) | cost at the default interval |"
          % (a.pairs, a.stress))
    print("|---|---|---|---|---|")
    for name, scene in SCENES.items():
        ratios, written = [], []
        for k in range(a.pairs):
            on = run(a.gran, scene, out / "on.h5", DEFAULT_INTERVAL)
            off = run(a.gran, scene, out / "off.h5", 0)
            ratios.append(on["wall_time"] / off["wall_time"])
            written.append(int(on["checkpoints"]))
        stress = run(a.gran, scene, out / "stress.h5", a.stress)
        if stress["checkpoints"] == 0:
            per = float("nan")
        else:
            per = stress["checkpoint_time"] / stress["checkpoints"]
        print(f"| {name} | {statistics.median(ratios):.3f} (min {min(ratios):.3f}, max "
              f"{max(ratios):.3f}) | {max(written)} | {per:.3f} ({int(stress['checkpoints'])} "
              f"written in a {stress['wall_time']:.0f} s run) | {100 * per / DEFAULT_INTERVAL:.3f}% |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
