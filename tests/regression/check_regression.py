#!/usr/bin/python3
"""Bit-identity of results across refactorings (issue #12).

Runs every scene of tests/regression/scenes/ with the given `gran` binary and compares the result
with tests/regression/reference/<scene>.h5, which the build *before* the change made (see README.md
in this folder). Compared bit for bit: every dataset and attribute under /observables and
/particles, and every dataset under /drivers (wall hits and impulses, injected energy). Not
compared: /parameters (the resolved scene is written in the new spelling) and /performance
(timings).

    check_regression.py GRAN_BINARY [--scene NAME] [--keep DIR]

Items a change adds on purpose (new quantities) are listed with their reason in additions.txt;
they are reported and do not fail. Nothing may be missing or differ.

Exit status 0 when every scene matches, 1 otherwise (the first differences are printed).
"""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
COMPARED = ("observables", "particles", "drivers")


def items(f):
    """Every dataset and attribute below the compared groups: path -> value."""
    out = {}

    def visit(name, obj):
        top = name.split("/")[0]
        if isinstance(obj, h5py.Dataset):
            out[name] = obj[()]
        if top == "drivers":
            return  # driver attributes are descriptions, not results
        for key, value in obj.attrs.items():
            out[f"{name}@{key}"] = value

    # Group by group: /particles is an external link to the trajectory file since issue 14,
    # which visititems on the file would not follow.
    for top in COMPARED:
        if top in f:
            f[top].visititems(lambda name, obj, top=top: visit(f"{top}/{name}", obj))
    return out


def in_reference_layout(got, problems):
    """The trajectory items of a result in the reference files' layout (issue 14 changed it on
    purpose): box edges were a vector, now one D x D matrix of edge vectors per frame (its
    diagonal must be the old vector); `step` was the frame index, now the engine's events or
    steps at the frame (must increase strictly; compared as the frame index)."""
    edges = got.pop("particles/all/box/edges/value", None)
    if edges is not None:
        diagonals = {tuple(np.diag(frame)) for frame in edges}
        if len(diagonals) != 1 or np.count_nonzero(edges[0] - np.diag(np.diag(edges[0]))):
            problems.append("differs particles/all/box/edges/value: not one diagonal box")
        got["particles/all/box/edges"] = np.diag(edges[0])
    for element in ("position", "velocity"):
        key = f"particles/all/{element}/step"
        if key in got:
            steps = np.asarray(got[key])
            if np.any(np.diff(steps) <= 0):
                problems.append(f"differs {key}: not strictly increasing")
            got[key] = np.arange(len(steps), dtype=steps.dtype)
    return got


def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind in "OSU" or b.dtype.kind in "OSU":
        return a.shape == b.shape and all(
            (x.decode() if isinstance(x, bytes) else x) == (y.decode() if isinstance(y, bytes) else y)
            for x, y in zip(a.ravel().tolist(), b.ravel().tolist()))
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def additions():
    """The documented additions: compiled patterns on "<scene>:<item>"."""
    out = []
    for line in (HERE / "additions.txt").read_text().splitlines():
        pattern = line.split("#", 1)[0].strip()
        if pattern:
            out.append(re.compile(pattern))
    return out


def compare(result, reference, scene="", allowed=()):
    problems = []
    with h5py.File(result, "r") as fr, h5py.File(reference, "r") as fref:
        got, want = items(fr), items(fref)
    if "particles/all/box/edges" in want:  # a reference made before issue 14
        got = in_reference_layout(got, problems)
    for key in sorted(set(want) - set(got)):
        problems.append(f"missing {key}")
    added = 0
    for key in sorted(set(got) - set(want)):
        if any(p.search(f"{scene}:{key}") for p in allowed):
            added += 1
        else:
            problems.append(f"extra {key}")
    for key in sorted(set(got) & set(want)):
        if not same(got[key], want[key]):
            problems.append(f"differs {key}: {np.ravel(got[key])[:3]} != {np.ravel(want[key])[:3]}")
    return problems, len(want), added


def report_failure(name, problems, n, shown=10):
    """Prints a run whose items differ from the reference, with its first `shown` differences."""
    print(f"FAIL {name}: {len(problems)} of {n} items differ")
    for p in problems[:shown]:
        print("   ", p)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gran")
    ap.add_argument("--scene", action="append", help="only these scenes (file stems)")
    ap.add_argument("--keep", help="write the results here instead of a temporary folder")
    args = ap.parse_args()
    scenes = sorted((HERE / "scenes").glob("*.yaml"))
    if args.scene:
        scenes = [s for s in scenes if s.stem in args.scene]
    if not scenes:
        print("no scenes", file=sys.stderr)
        return 1
    failed = 0
    allowed = additions()
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(args.keep or tmp)
        out.mkdir(parents=True, exist_ok=True)
        for scene in scenes:
            result = out / f"{scene.stem}.h5"
            run = subprocess.run([args.gran, "run", "-q", str(scene), "-o", str(result)],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                print(f"FAIL {scene.stem}: gran exited {run.returncode}\n{run.stdout}{run.stderr}")
                failed += 1
                continue
            problems, n, added = compare(result, HERE / "reference" / f"{scene.stem}.h5",
                                         scene.stem, allowed)
            if problems:
                failed += 1
                report_failure(scene.stem, problems, n)
            else:
                extra = f", {added} documented additions" if added else ""
                print(f"ok   {scene.stem}: {n} items bit-identical{extra}")
    print(f"{len(scenes) - failed} of {len(scenes)} scenes bit-identical")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
