"""comparison.csv: the numbers a paper states against the numbers measured.

One row per number: `quantity` (a name saying what was measured and where), `paper` (the
paper's number, or a text such as '7-10'; empty where the paper gives none), `measured` and
`error` (one standard error of `measured`; empty when there is none). Every reproduced paper
writes this file, rewritten from scratch, with `write`.
"""
import csv
import math
from typing import NamedTuple, Optional, Union

import numpy as np

HEADER = ("quantity", "paper", "measured", "error")


class Row(NamedTuple):
    """One number of a paper against the measurement."""

    quantity: str
    paper: Optional[Union[float, str]]
    measured: Optional[float]
    error: Optional[float]


def cell(x, fmt):
    """A number formatted with `fmt` ('{:.6g}'), a text as is, '' for None and NaN."""
    if x is None or (isinstance(x, (float, np.floating)) and math.isnan(x)):
        return ""
    return fmt.format(x) if isinstance(x, (int, float, np.floating, np.integer)) else str(x)


def write(rows, path, measured="{:.6g}", error="{:.3g}", paper="{:g}"):
    """Write rows (quantity, paper, measured, error) to `path`, replacing it. The formats give
    each column's precision; None and NaN become empty cells."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEADER)
        for q, p, m, e in rows:
            w.writerow((q, cell(p, paper), cell(m, measured), cell(e, error)))


def _number_or_text(text):
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


def read(path):
    """The rows of a comparison.csv: paper as a float (or its text when not a number), measured
    and error as floats; None for empty cells."""
    with open(path, newline="") as f:
        return [Row(r["quantity"], _number_or_text(r["paper"]),
                    None if r["measured"] == "" else float(r["measured"]),
                    None if r["error"] == "" else float(r["error"]))
                for r in csv.DictReader(f)]


def deviation(row):
    """measured - paper in units of the error (NaN when the paper gives no number or there is no
    error): how many standard errors the measurement lies from the paper."""
    if not isinstance(row.paper, float) or row.measured is None or not row.error:
        return math.nan
    return (row.measured - row.paper) / row.error
