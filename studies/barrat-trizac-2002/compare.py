#!/usr/bin/python3
"""Compare the Barrat & Trizac 2002 study results with the paper's Tables I and II.

Usage: /usr/bin/python3 studies/barrat-trizac-2002/compare.py [RESULTS_DIR]
Writes RESULTS_DIR/comparison.csv (quantity,paper,measured,error; table rows only) and
RESULTS_DIR/tables.png. figures.py calls the same functions and rewrites comparison.csv with the
rows of the figures added (`make reproduce-barrat-trizac-2002` runs figures.py).
"""
import sys
from pathlib import Path

import yaml

from analysis import Results
from gran import comparison
from gran.style import DPI, plt

HERE = Path(__file__).resolve().parent


def table_rows(res):
    """(quantity, paper, measured, error) for every paper value of tables.yaml (gamma, gamma_x,
    gamma_rot of light over heavy in the middle of the cell)."""
    study = yaml.safe_load((HERE / "tables.yaml").read_text())
    rows = []
    for point in study["points"]:
        run = res[point["name"]]
        for key, paper in point["paper"].items():
            measured, error = run.middle(f"ratios/light_over_heavy/{key}")
            rows.append((f"{point['name']}_{key}", paper, measured, error))
    return rows


def write_csv(rows, path):
    """comparison.csv of this paper: the paper's numbers as the study files give them, measured
    values and errors with four decimals, with each row's status against the paper and the
    written cause of a difference (verdicts.yaml); prints the rows that differ without one."""
    verdicts = comparison.Verdicts.load(Path(__file__).resolve().parent / "verdicts.yaml")
    comparison.write(rows, path, paper="{}", measured="{:.4f}", error="{:.4f}",
                     verdicts=verdicts)
    comparison.report(rows, verdicts, path)


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
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def main():
    outdir = Path(sys.argv[1] if len(sys.argv) > 1 else "results/barrat-trizac-2002")
    rows = table_rows(Results(outdir))
    write_csv(rows, outdir / "comparison.csv")
    plot_tables(rows, outdir / "tables.png")
    worst = max(abs(m - p) for _, p, m, _ in rows)
    print(f"{len(rows)} rows, largest |measured - paper| = {worst:.3f}; "
          f"{outdir / 'comparison.csv'}, {outdir / 'tables.png'}")


if __name__ == "__main__":
    main()
