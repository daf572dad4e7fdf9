#!/usr/bin/python3
"""Coverage of the error bars of runs stopped at their target (issue 17).

Usage: /usr/bin/python3 studies/targets/coverage.py RESULTS_DIR [coverage|coverage-fixed|coverage-n100]

RESULTS_DIR holds coverage.yaml's 200 replicas (or coverage-fixed.yaml's, the control without a
target) and truth.yaml's long run (`gran study ... -o RESULTS_DIR` for each). Prints the fraction of replicas whose gamma lies within 1 and 2 of
their own error bars of the truth (nominal 68.3% and 95.4%, with the binomial standard error of
the fraction), and the spread of the lengths at which they stopped.
"""
import math
import sys
from pathlib import Path

from gran.studies import StudyFolder

GAMMA = "observables.temperatures.ratios.light_over_heavy.gamma"


def main():
    directory = Path(sys.argv[1] if len(sys.argv) > 1 else "results/targets")
    name = sys.argv[2] if len(sys.argv) > 2 else "coverage"
    runs = StudyFolder(directory, name).table
    truth_table = StudyFolder(directory, "truth").table
    truth, truth_error = truth_table.value_and_error(truth_table.rows[0], GAMMA)
    within = {1: 0, 2: 0}
    lengths = []
    for row in runs.rows:
        value, error = runs.value_and_error(row, GAMMA)
        for k in within:
            within[k] += abs(value - truth) <= k * error
        measured = runs.number(row, "target.measured")
        lengths.append(measured if math.isfinite(measured)
                       else runs.number(row, "performance.collisions_per_particle"))
    n = len(runs.rows)
    print(f"truth: gamma = {truth:.5f} +- {truth_error:.5f} (one run of 2e5 collisions per "
          f"particle)")
    for k, nominal in ((1, 0.683), (2, 0.954)):
        f = within[k] / n
        print(f"within {k} sigma: {within[k]}/{n} = {f:.3f} +- {math.sqrt(f * (1 - f) / n):.3f} "
              f"(nominal {nominal})")
    lengths.sort()
    print(f"stopped after {lengths[0]:.0f} to {lengths[-1]:.0f} collisions per particle "
          f"(median {lengths[n // 2]:.0f})")


if __name__ == "__main__":
    main()
