#!/usr/bin/python3
"""Bit-identity of two folders of run results (issue #12: paper reproductions before and after).

Compares every `<run>.h5` present in both folders with check_regression.compare (datasets and
attributes under /observables, /particles and /drivers, bit for bit; /parameters and /performance
are not compared). Study files (`*.study.h5`) are skipped: they hold copies of the run files; so are trajectories
(`*.trajectory.h5`), compared through the `/particles` link of their result.

    compare_result_dirs.py NEW_DIR OLD_DIR [--allow REGEX ...]

--allow: items (paths below the compared groups) the new build adds on purpose, e.g. the
rotational temperatures of frictional DEM grains (additions.txt). Exit status 0 when every common
run matches, 1 otherwise; runs present in only one folder are listed.
"""
import argparse
import pathlib
import re
import sys

from check_regression import compare, report_failure


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("new")
    ap.add_argument("old")
    ap.add_argument("--allow", action="append", default=[])
    a = ap.parse_args()
    allowed = [re.compile(r) for r in a.allow]  # searched in ":<item>"
    def runs(folder):  # trajectories are compared through their result's /particles link
        return {p.name for p in pathlib.Path(folder).glob("*.h5")
                if not p.name.endswith((".study.h5", ".trajectory.h5"))}

    new, old = runs(a.new), runs(a.old)
    failed = matched = items = added_total = 0
    for name in sorted(new & old):
        problems, n, added = compare(pathlib.Path(a.new) / name, pathlib.Path(a.old) / name,
                                     "", allowed)
        items += n
        added_total += added
        if problems:
            failed += 1
            report_failure(name, problems, n, shown=5)
        else:
            matched += 1
    for name in sorted(new - old):
        print(f"only in {a.new}: {name}")
    for name in sorted(old - new):
        print(f"only in {a.old}: {name}")
    print(f"{matched} of {len(new & old)} common runs bit-identical ({items} items compared, "
          f"{added_total} added items allowed); {failed} differ")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
