#!/usr/bin/python3
"""Compare the Barrat & Trizac 2002 study results with the paper's Tables I and II.

Usage: /usr/bin/python3 studies/barrat-trizac-2002/compare.py [RESULTS_DIR]
Writes RESULTS_DIR/comparison.csv (quantity,paper,measured,error; table rows only) and
RESULTS_DIR/tables.png. figures.py calls the same functions and rewrites comparison.csv with the
rows of the figures added (`make reproduce-barrat-trizac-2002` runs figures.py).
"""
import csv
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402

HERE = Path(__file__).resolve().parent
HEADER = ["quantity", "paper", "measured", "error"]


def table_rows(outdir):
    """(quantity, paper, measured, error) for every paper value of tables.yaml."""
    study = yaml.safe_load((HERE / "tables.yaml").read_text())
    rows = []
    for point in study["points"]:
        with h5py.File(Path(outdir) / f"{point['name']}.h5", "r") as f:
            g = f["observables/profiles/middle/ratios/light_over_heavy"]
            for key, paper in point["paper"].items():
                d = g[key]
                rows.append((f"{point['name']}_{key}", paper, float(d[()]),
                             float(d.attrs["error"])))
    return rows


def write_csv(rows, path):
    """Write comparison rows (quantity, paper, measured, error) to a CSV file, replacing it."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEADER)
        for q, p, m, e in rows:
            w.writerow([q, p, f"{m:.4f}", f"{e:.4f}"])


def plot_tables(rows, path):
    """Measured against published gamma, gamma_x, gamma_rot (Tables I-II) as a PNG."""
    fig, ax = plt.subplots(figsize=(5, 5))
    for marker, key in (("o", "_gamma"), ("s", "_gamma_x"), ("^", "_gamma_rot")):
        sel = [r for r in rows if r[0].endswith(key)]
        ax.errorbar([r[1] for r in sel], [r[2] for r in sel], yerr=[r[3] for r in sel], fmt=marker,
                    label=key.strip("_"))
    ax.plot([0.6, 1.05], [0.6, 1.05], "k--", lw=1, label="measured = paper")
    ax.fill_between([0.6, 1.05], [0.57, 1.02], [0.63, 1.08], color="0.9", label="+-0.03")
    ax.set_xlabel("Barrat & Trizac 2002, Tables I-II")
    ax.set_ylabel("gran, middle of the cell")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    outdir = Path(sys.argv[1] if len(sys.argv) > 1 else "results/barrat-trizac-2002")
    rows = table_rows(outdir)
    write_csv(rows, outdir / "comparison.csv")
    plot_tables(rows, outdir / "tables.png")
    worst = max(abs(m - p) for _, p, m, _ in rows)
    print(f"{len(rows)} rows, largest |measured - paper| = {worst:.3f}; "
          f"{outdir / 'comparison.csv'}, {outdir / 'tables.png'}")


if __name__ == "__main__":
    main()
