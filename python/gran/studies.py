"""Reading the results of `gran study` (docs/studies.md, "What it writes").

- `StudyTable`: one row per completed run, from `<study>.study.csv` or the /summary group of
  `<study>.study.h5`: the run's name (`run`), its study point (`point`), the swept scene keys, then
  every number of the run summaries (value and `<quantity>.error` columns).
- `read_fits`: the power-law fits of `<study>.fits.csv` (gran's fits over the runs).
- `StudyFolder`: a result folder as the study left it (table, fits, one `<run>.h5` per run).
- `Study`: a merged `<study>.study.h5` (table, fits, every run, the trade-off analysis).
"""
import csv
import math
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from gran.results import Run, as_text, numbers, texts


class NoPointColumn(ValueError):
    """A study table written before gran recorded each run's point."""


def number(text):
    """A table cell as a float: NaN for an empty cell (a quantity a run does not report, or the
    error of a plain counter)."""
    return float(text) if text not in ("", None) else math.nan


class StudyTable:
    """The study table: `columns` (names in file order) and `rows` (one dict per run, cells as
    text). Numbers are read with `number`, `value_and_error` or `column`; `records()` gives a
    NumPy structured array and `dataframe()` a pandas DataFrame (when pandas is installed)."""

    def __init__(self, columns, rows, source=""):
        """A table from its column names and rows ({column: text}); `source` names it in errors."""
        if "point" not in columns:
            raise NoPointColumn(
                f"{source}: the study table has no `point` column (written by a gran from before "
                "the column existed): rerun `gran study STUDY.yaml -o DIR` to rewrite it "
                "(completed runs are reused, nothing is recomputed)")
        self.columns, self.rows, self.source = list(columns), list(rows), str(source)

    @classmethod
    def read_csv(cls, path):
        """Read `<study>.study.csv`."""
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            return cls(reader.fieldnames or [], rows, path)

    @classmethod
    def from_h5(cls, root, source=""):
        """The table held by the /summary group of an open `.study.h5` file."""
        summary = root["summary"]
        if "points" not in summary:
            cls([], [], source or root.file.filename)  # raises NoPointColumn
        columns = {"run": texts(summary["runs"]), "point": texts(summary["points"])}
        for key, values in _leaves(summary, "parameters"):
            columns[key] = texts(values)
        for key, group in _quantities(summary):
            columns[key] = [_cell(v) for v in group["value"][()]]
            columns[key + ".error"] = [_cell(e) for e in group["error"][()]]
        rows = [dict(zip(columns, cells)) for cells in zip(*columns.values())]
        return cls(list(columns), rows, source or root.file.filename)

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def points(self):
        """The distinct points, sorted by name."""
        return sorted({row["point"] for row in self.rows})

    def runs(self, point=None):
        """The rows of one point (every row when point is None), in table order."""
        return [row for row in self.rows if point is None or row["point"] == point]

    def run(self, name):
        """The row of the run named `name`."""
        for row in self.rows:
            if row["run"] == name:
                return row
        raise KeyError(f"{self.source}: no run named {name}")

    @staticmethod
    def number(row, column):
        """One cell of a row as a float (NaN when empty or absent)."""
        return number(row.get(column))

    @staticmethod
    def value_and_error(row, quantity):
        """(value, error) of a summary quantity of one run, NaN when not reported."""
        return number(row.get(quantity)), number(row.get(quantity + ".error"))

    def column(self, name, rows=None):
        """One column as a float array (over `rows`, default every row)."""
        return np.array([number(row.get(name)) for row in (self.rows if rows is None else rows)])

    def records(self):
        """The table as a NumPy structured array: float columns where every cell is a number or
        empty, text columns otherwise (run, point, list-valued swept keys)."""
        fields, data = [], []
        for name in self.columns:
            cells = [row.get(name, "") for row in self.rows]
            try:
                values = [number(c) for c in cells]
                fields.append((name, "f8"))
            except ValueError:
                values = cells
                fields.append((name, f"U{max((len(c) for c in cells), default=1) or 1}"))
            data.append(values)
        return np.array(list(zip(*data)), dtype=fields)

    def dataframe(self):
        """The table as a pandas DataFrame (ImportError when pandas is not installed)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("StudyTable.dataframe() needs pandas; records() gives a NumPy "
                              "structured array without it") from None
        return pandas.DataFrame(self.records())


def _cell(x):
    """A number as a table cell (empty for NaN), with the precision of the CSV (10 digits)."""
    return "" if math.isnan(x) else f"{x:.10g}"


def _leaves(group, name):
    """(dotted key, dataset) of the datasets below group/name: the swept keys contain dots and
    no slashes, so each is one dataset."""
    if name not in group:
        return []
    return [(key, dataset) for key, dataset in group[name].items()]


def _quantities(summary):
    """(quantity, group) of /summary/quantities: a quantity name may hold slashes
    ('observables.profiles.middle/mixture/T'), so its group is the one holding `value`."""
    out = []

    def visit(name, obj):
        if isinstance(obj, h5py.Group) and "value" in obj and "error" in obj:
            out.append((name, obj))

    if "quantities" in summary:
        summary["quantities"].visititems(visit)
    return out


@dataclass(frozen=True)
class StudyFit:
    """One power-law fit of a study, y = exp(log_prefactor) x^theta over `points` runs; `valid`
    is False when a run deviates from it by |log y - log y_fit| >= the fit's tolerance (then the
    paper's rule says there is no exponent)."""

    name: str
    x: str
    y: str
    group: str
    points: int
    theta: float
    theta_error: float
    log_prefactor: float
    max_deviation: float
    valid: bool


def read_fits(path):
    """The fits of `<study>.fits.csv`: {fit name: StudyFit}, in file order."""
    with open(path, newline="") as f:
        return {r["fit"]: StudyFit(name=r["fit"], x=r["x"], y=r["y"], group=r["group"],
                                   points=int(r["points"]), theta=number(r["theta"]),
                                   theta_error=number(r["theta_error"]),
                                   log_prefactor=number(r["log_prefactor"]),
                                   max_deviation=number(r["max_deviation"]),
                                   valid=r["valid"] == "1")
                for r in csv.DictReader(f)}


class StudyFolder:
    """The result folder of one study: `<name>.study.csv`, `<name>.fits.csv` (when the study has
    fits) and one `<run>.h5` per run."""

    def __init__(self, directory, name):
        """FileNotFoundError when the study table is not there (the study has not run)."""
        self.directory, self.name = Path(directory), name
        path = self.directory / f"{name}.study.csv"
        if not path.exists():
            raise FileNotFoundError(f"{path} is missing: run the study first")
        self.table = StudyTable.read_csv(path)
        fits = self.directory / f"{name}.fits.csv"
        self.fits = read_fits(fits) if fits.exists() else {}

    def run(self, row_or_name):
        """Open the result file of a run (a table row or a run name); close it after use."""
        name = row_or_name["run"] if isinstance(row_or_name, dict) else row_or_name
        return Run.open(self.directory / f"{name}.h5")

    def fit(self, name):
        """The fit named `name` (KeyError naming the fits file when absent)."""
        if name not in self.fits:
            raise KeyError(f"no fit {name} in {self.name}.fits.csv")
        return self.fits[name]


class Study:
    """A merged `<study>.study.h5`: the study file, the table, the fits, every run's result and,
    for trade-off studies, the speed-versus-accuracy analysis. Use as a context manager."""

    def __init__(self, file):
        """Wrap an open h5py file holding a merged study."""
        self.file = file
        self._table = None

    @classmethod
    def open(cls, path):
        """Open a merged study file read-only (OSError when it is missing or not HDF5)."""
        return cls(h5py.File(path, "r"))

    def close(self):
        """Close the file."""
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def table(self):
        """The study table (/summary), one row per completed run."""
        if self._table is None:
            self._table = StudyTable.from_h5(self.file)
        return self._table

    @property
    def text(self):
        """The study file as written (YAML)."""
        return as_text(self.file["study/study"][()])

    @property
    def source(self):
        """The path of the study file that made this result."""
        return as_text(self.file["study"].attrs.get("file", self.file.filename))

    def run(self, name):
        """The result of one run (a Run on the /points/<name> group)."""
        return Run(self.file[f"points/{name}"], name)

    @property
    def fits(self):
        """{fit name: StudyFit} from /fits."""
        out = {}
        for name, g in self.file.get("fits", {}).items():
            theta = g["theta"]
            out[name] = StudyFit(name=name, x=as_text(g.attrs["x"]), y=as_text(g.attrs["y"]),
                                 group=as_text(g.attrs.get("group", "")), points=len(g["x"]),
                                 theta=float(theta[()]), theta_error=float(theta.attrs["error"]),
                                 log_prefactor=float(g["log_prefactor"][()]),
                                 max_deviation=float(g["max_deviation"][()]),
                                 valid=bool(g["valid"][()]))
        return out

    @property
    def performance(self):
        """Runs made, reused and failed, and the study's wall time [s]."""
        return numbers(self.file["performance"])

    def tradeoff(self):
        """The speed-versus-accuracy analysis (/tradeoff, docs/studies.md "Trade-off") as a dict:
        per run `runs`, `knobs`, `levels`, `cost` [CPU s], `worst` (accuracy of the worst
        quantity), `pareto`, `reference`; `quantities` (names) and `panels`, one per quantity
        with its `accuracy`, `deviation`, `error`, `pareto`, `kind` and `reference` value."""
        if "tradeoff" not in self.file:
            raise KeyError(f"{self.file.filename}: no /tradeoff group (run `gran tradeoff` or give "
                           "the study a `tradeoff:` key)")
        g = self.file["tradeoff"]
        out = {"runs": texts(g["runs"]), "knobs": texts(g["knobs"]), "levels": texts(g["levels"]),
               "cost": g["cost"][()], "worst": g["worst_accuracy"][()],
               "pareto": g["pareto"][()].astype(bool),
               "reference": g["reference"][()].astype(bool),
               "quantities": texts(g["quantity_names"]), "study": self.source, "panels": []}
        for q in out["quantities"]:
            qg = g["quantities"][q]
            out["panels"].append({
                "name": q, "accuracy": qg["accuracy"][()], "deviation": qg["deviation"][()],
                "error": qg["deviation_error"][()], "pareto": qg["pareto"][()].astype(bool),
                "kind": as_text(qg.attrs.get("reference_kind", "")),
                "reference": qg["reference"][()]})
        return out
