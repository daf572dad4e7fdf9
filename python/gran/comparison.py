"""comparison.csv: the numbers a paper states against the numbers measured.

One row per number: `quantity` (a name saying what was measured and where), `paper` (the
paper's number, or a text such as '7-10'; empty where the paper gives none), `measured` and
`error` (one standard error of `measured`; empty when there is none). Every reproduced paper
writes this file, rewritten from scratch, with `write`.

With the paper's verdicts (`Verdicts.load(studies/<paper>/verdicts.yaml)`), `write` adds two
columns: `status` (`agrees`: within the tolerance of the paper's number, `differs`, or empty
when the paper gives no number to compare) and `cause`, the written reason of a row that
differs (a gran defect, a modelling difference, an ambiguity of the paper, ...). `uncaused`
lists the rows that differ with no reason written: there should be none.
"""
import csv
import math
import re
from pathlib import Path
from typing import NamedTuple, Optional, Union

import yaml

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


def write(rows, path, measured="{:.6g}", error="{:.3g}", paper="{:g}", verdicts=None):
    """Write rows (quantity, paper, measured, error) to `path`, replacing it. The formats give
    each column's precision; None and NaN become empty cells. With `verdicts` (a Verdicts), the
    columns `status` and `cause` follow."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(HEADER + (("status", "cause") if verdicts else ()))
        for q, p, m, e in rows:
            out = (q, cell(p, paper), cell(m, measured), cell(e, error))
            if verdicts:
                status = verdicts.status(Row(q, p, m, e))
                out += (status or "", verdicts.cause(q) if status == "differs" else "")
            w.writerow(out)


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


def paper_interval(paper):
    """The paper's number as an interval (lo, hi): a number x gives (x, x), a text 'a-b' (a
    printed range) gives (a, b), '> x' and '< x' (a bound) give (x, inf) and (-inf, x); None for
    anything else (no number, a sentence)."""
    if isinstance(paper, bool) or paper is None:
        return None
    if isinstance(paper, (int, float, np.floating, np.integer)):
        return None if math.isnan(paper) else (float(paper), float(paper))
    bound = re.fullmatch(r"\s*([<>])\s*(-?[0-9.eE+]+)\s*", str(paper))
    if bound:
        try:
            x = float(bound.group(2))
        except ValueError:
            return None
        return (x, math.inf) if bound.group(1) == ">" else (-math.inf, x)
    m = re.fullmatch(r"\s*(-?[0-9.eE+]+)\s*-\s*(-?[0-9.eE+]+)\s*", str(paper))
    if m:
        try:
            return float(m.group(1)), float(m.group(2))
        except ValueError:
            return None
    return None


def agrees(row, sigmas=2.0, relative=0.1, absolute=0.0):
    """Whether `measured` lies within max(sigmas x error, relative x |paper|, absolute) of the
    paper's number (or of its printed range); None when there is nothing to compare (no paper
    number, no measurement). `absolute` serves a paper's 0 (no relative slack there)."""
    interval = paper_interval(row.paper)
    if interval is None or row.measured is None or math.isnan(row.measured):
        return None
    lo, hi = interval
    err = row.error if row.error is not None and not math.isnan(row.error) else 0.0
    # The relative part scales with the paper's number (a bound's finite end): a bound has no
    # relative slack, only the measurement's error.
    finite = [abs(x) for x in interval if math.isfinite(x)]
    rel = relative if lo == hi or all(math.isfinite(x) for x in interval) else 0.0
    slack = max(sigmas * err, rel * max(finite), absolute)
    return lo - slack <= row.measured <= hi + slack


class Verdicts:
    """A paper's tolerance and the written causes of the rows that differ from it.

    The file (YAML): `tolerance: {sigmas: 2, relative: 0.1}` (the default tolerance of every
    row; optional `absolute`) and `verdicts:`, a list of `{match: REGEX, cause: TEXT}` with
    optional `sigmas`, `relative` and `absolute` (those rows' own tolerance) and `kind` (what the cause is: gran defect, modelling
    difference, paper ambiguity, definition, not measurable here, statistics, or unexplained: a
    difference whose cause was looked for and not found, the cause then saying what was ruled
    out). A row takes the first entry whose `match` matches its whole quantity name."""

    KINDS = ("gran defect", "modelling difference", "paper ambiguity", "definition",
             "not measurable here", "statistics", "unexplained")

    def __init__(self, tolerance=None, entries=()):
        tolerance = tolerance or {}
        self.sigmas = float(tolerance.get("sigmas", 2.0))
        self.relative = float(tolerance.get("relative", 0.1))
        self.absolute = float(tolerance.get("absolute", 0.0))
        self.entries = []
        for e in entries:
            if "match" not in e or "cause" not in e:
                raise ValueError(f"a verdict needs `match` and `cause`: {e}")
            if "kind" in e and e["kind"] not in self.KINDS:
                raise ValueError(f"verdict kind {e['kind']!r} is not one of {self.KINDS}")
            self.entries.append(dict(e, pattern=re.compile(e["match"])))

    @classmethod
    def load(cls, path):
        data = yaml.safe_load(Path(path).read_text()) or {}
        return cls(data.get("tolerance"), data.get("verdicts") or ())

    def entry(self, quantity):
        return next((e for e in self.entries if e["pattern"].fullmatch(quantity)), None)

    def cause(self, quantity):
        """The written cause of a row (with its kind), or ''."""
        e = self.entry(quantity)
        if e is None:
            return ""
        return f"{e['kind']}: {e['cause']}" if "kind" in e else e["cause"]

    def status(self, row):
        """'agrees', 'differs', or None (nothing to compare), with the row's tolerance."""
        e = self.entry(row.quantity) or {}
        ok = agrees(row, float(e.get("sigmas", self.sigmas)),
                    float(e.get("relative", self.relative)),
                    float(e.get("absolute", self.absolute)))
        return None if ok is None else ("agrees" if ok else "differs")


def uncaused(rows, verdicts):
    """The rows that differ from the paper with no written cause."""
    out = []
    for r in rows:
        row = r if isinstance(r, Row) else Row(*r[:4])
        if verdicts.status(row) == "differs" and not verdicts.cause(row.quantity):
            out.append(row)
    return out


def report(rows, verdicts, path):
    """One line on the verdicts of a written comparison.csv, then each row that differs without
    a cause; returns how many such rows there are."""
    rows = [r if isinstance(r, Row) else Row(*r[:4]) for r in rows]
    status = [verdicts.status(r) for r in rows]
    missing = uncaused(rows, verdicts)
    print(f"{path}: {len(rows)} rows, {status.count('agrees')} agree with the paper, "
          f"{status.count('differs')} differ ({status.count('differs') - len(missing)} with a "
          f"written cause, {len(missing)} without)")
    for r in missing:
        print(f"  differs, no cause written: {r.quantity} paper {r.paper} measured {r.measured} "
              f"error {r.error}")
    return len(missing)
