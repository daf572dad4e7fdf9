#!/usr/bin/python3
"""Bit-identity of results across refactorings (issue #12).

Runs every scene of tests/regression/scenes/ with the given `gran` binary and compares the result
with tests/regression/reference/<scene>.h5, which the build *before* the change made (see README.md
in this folder). Compared bit for bit: every dataset and attribute under /observables and
/particles, and every dataset under /drivers (wall hits and impulses, injected energy). Not
compared: /parameters (the resolved scene is written in the new spelling) and /performance
(timings).

    check_regression.py GRAN_BINARY [--scene NAME] [--keep DIR]
    check_regression.py GRAN_BINARY --scene NAME --update

Items a change adds on purpose (new quantities) are listed with their reason in additions.txt;
they are reported and do not fail. Nothing may be missing or differ.

--update (only with --scene): a change meant to change results (README.md) writes this build's
values into the named scenes' reference files, in their own layout, for the items that differ.
Nothing else is touched; a scene with missing or extra items is refused (that is a change of
layout, not of values).

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

    # Every link, walked by name: visititems would skip a second name of an object (the hard
    # links of H5MD time series sharing step and time) and external links (/particles links to
    # the trajectory file since issue 14).
    def walk(group, prefix, top):
        for name in group:
            obj = group[name]
            path = f"{prefix}/{name}"
            if isinstance(obj, h5py.Dataset):
                out[path] = obj[()]
            if top != "drivers":  # driver attributes are descriptions, not results
                for key, value in obj.attrs.items():
                    out[f"{path}@{key}"] = value
            if isinstance(obj, h5py.Group):
                walk(obj, path, top)

    for top in COMPARED:
        if top in f:
            if top != "drivers":
                for key, value in f[top].attrs.items():
                    out[f"{top}@{key}"] = value
            walk(f[top], top, top)
    return out


def series_in_reference_layout(got, problems):
    """Time series of observables in the reference files' layout: since issue 14 each is an H5MD
    element X/{step, time, value} (time and step shared by hard links); before, X was the values
    and the observable's `time` dataset the times. X/value becomes X (its unit X@unit), the
    observable's times its `time`; the steps must increase strictly."""
    for key in sorted(k for k in got if k.startswith("observables/") and k.endswith("/value")):
        x = key[: -len("/value")]
        if f"{x}/step" not in got or f"{x}/time" not in got:
            continue
        observable = "/".join(x.split("/")[:2])
        time = got.pop(f"{x}/time")
        steps = np.asarray(got.pop(f"{x}/step"))
        if np.any(np.diff(steps) <= 0):
            problems.append(f"differs {x}/step: not strictly increasing")
        got.setdefault(f"{observable}/time", time)
        got.setdefault(f"{observable}/time@unit", got.pop(f"{x}/time@unit", "time"))
        got.pop(f"{x}/time@unit", None)
        got[x] = got.pop(key)
        if f"{key}@unit" in got:
            got[f"{x}@unit"] = got.pop(f"{key}@unit")


def in_reference_layout(got, problems):
    """The trajectory items of a result in the reference files' layout (issue 14 changed it on
    purpose): box edges were a vector, now one D x D matrix of edge vectors per frame (its
    diagonal must be the old vector); `step` was the frame index, now the engine's events or
    steps at the frame (must increase strictly; compared as the frame index)."""
    series_in_reference_layout(got, problems)
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


def aligned(result, reference, problems):
    """The items of a result and of its reference file, the result's in the reference's layout."""
    with h5py.File(result, "r") as fr, h5py.File(reference, "r") as fref:
        got, want = items(fr), items(fref)
    if "particles/all/box/edges" in want or any(re.fullmatch(r"observables/[^/]+/time", k)
                                                for k in want):  # made before issue 14
        got = in_reference_layout(got, problems)
    return got, want


def compare(result, reference, scene="", allowed=()):
    problems = []
    got, want = aligned(result, reference, problems)
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


def update_reference(result, reference, scene="", allowed=()):
    """Writes the result's values of the items that differ into the reference file (its layout
    kept). Returns the problems that are not differing values (nothing is written then)."""
    problems, _, _ = compare(result, reference, scene, allowed)
    other = [p for p in problems if not p.startswith("differs ")]
    if other:
        return other
    got, want = aligned(result, reference, [])
    with h5py.File(reference, "r+") as fref:
        for key in sorted(k for k in set(got) & set(want) if not same(got[k], want[k])):
            if "@" in key:
                path, attr = key.split("@", 1)
                fref[path].attrs[attr] = got[key]
            else:
                fref[key][...] = got[key]
    return []


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
    ap.add_argument("--update", action="store_true",
                    help="write this build's values of the differing items into the references "
                         "of the --scene scenes")
    args = ap.parse_args()
    if args.update and not args.scene:
        print("--update needs --scene: references are rewritten one named scene at a time",
              file=sys.stderr)
        return 2
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
            reference = HERE / "reference" / f"{scene.stem}.h5"
            if args.update:
                refused = update_reference(result, reference, scene.stem, allowed)
                if refused:
                    print(f"NOT UPDATED {scene.stem}: not only values differ")
                    for p in refused[:10]:
                        print("   ", p)
                    failed += 1
                    continue
            problems, n, added = compare(result, reference, scene.stem, allowed)
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
