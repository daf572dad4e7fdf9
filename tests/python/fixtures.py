"""Small synthetic gran files for the tests of python/gran: a run result and a merged study, laid
out as gran writes them (docs/studies.md), with known numbers."""
import math
import tempfile
import unittest
from pathlib import Path

import h5py
import numpy as np

SCENE = """title: 'synthetic: heated mixture'
dimension: 2
particles: 4
species:
  - name: heavy
    mass: 3
    count: 2
  - name: light
    mass: 1
    count: 2
box:
  lengths: [10, 20]
"""
TIME = np.linspace(1.0, 5.0, 5)
T_HEAVY = np.array([1.0, 1.1, 0.9, 1.05, 0.95])
EDGES = np.linspace(-4.0, 4.0, 9)
POSITION = np.array([2.5, 7.5, 12.5, 17.5])
FRAMES = np.arange(2 * 4 * 2, dtype=float).reshape(2, 4, 2)


class TempDirTest(unittest.TestCase):
    """A test with a fresh directory `self.dir`, removed afterwards."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()


def estimate(group, name, value, error, unit="energy", n_eff=40.0, tau_int=1.5, samples=100,
             converged=1):
    """A scalar estimate with the attributes gran writes."""
    ds = group.create_dataset(name, data=value)
    for key, v in (("error", error), ("unit", unit), ("n_eff", n_eff), ("tau_int", tau_int),
                   ("samples", samples), ("converged", converged)):
        ds.attrs[key] = v
    return ds


def fill_run(root, scene=SCENE):
    """Fill an h5py group with a run result: temperatures (estimates, series), a rescaled velocity
    histogram, a profile with errors, performance counters and two trajectory frames."""
    root.create_group("h5md/creator").attrs["name"] = "gran"
    root.create_dataset("parameters/scene", data=scene, dtype=h5py.string_dtype())
    temps = root.create_group("observables/temperatures")
    temps.attrs["type"] = "temperatures"
    temps.create_dataset("time", data=TIME)
    estimate(temps, "T_mixture", 1.25, 0.02)
    heavy = temps.create_group("heavy")
    estimate(heavy, "T", 1.0, 0.01)
    heavy.create_dataset("series/T", data=T_HEAVY)
    pdf = root.create_group("observables/velocity_pdf/heavy/x")
    root["observables/velocity_pdf"].attrs["type"] = "velocity_pdf"
    c = 0.5 * (EDGES[1:] + EDGES[:-1])
    density = np.exp(-0.5 * c**2) / math.sqrt(2 * math.pi)
    pdf.create_dataset("scaled_edges", data=EDGES)
    pdf.create_dataset("scaled_density", data=density)
    pdf.create_dataset("scaled_error", data=0.1 * density)
    prof = root.create_group("observables/profiles")
    prof.attrs["type"] = "profiles"
    prof.create_dataset("position", data=POSITION)
    prof.create_dataset("heavy/T", data=[1.0, 2.0, 3.0, 4.0])
    prof.create_dataset("heavy/T_error", data=[0.1, 0.2, 0.3, 0.4])
    perf = root.create_group("performance")
    perf.create_dataset("events_per_second", data=2.5e6)
    perf.create_dataset("completed", data=np.int64(1))
    perf.create_dataset("equilibration/shift_z", data=0.3)
    root.create_dataset("particles/all/position/value", data=FRAMES)
    root.create_dataset("particles/all/position/time", data=[0.5, 1.5])
    root.create_dataset("particles/all/box/edges", data=[10.0, 20.0])
    root.create_dataset("drivers/vibrating_wall/amplitude", data=0.025)


def write_run(path, scene=SCENE):
    """A run result file at `path`."""
    with h5py.File(path, "w") as f:
        fill_run(f, scene)
    return path


STUDY_RUNS = ("hot_alpha0.8", "hot_alpha0.9", "cold_alpha0.8")
STUDY_POINTS = ("hot", "hot", "cold")


def write_study(path, with_points=True, tradeoff=False):
    """A merged study file: three runs of two points swept over interactions.alpha, the summary
    table (T_mixture with errors, a NaN), one fit and optionally a /tradeoff group."""
    strings = h5py.string_dtype()
    with h5py.File(path, "w") as f:
        f.create_dataset("study/study", data="scene: scene.yaml\n", dtype=strings)
        f["study"].attrs["file"] = "studies/x/sweep.yaml"
        for name in STUDY_RUNS:
            fill_run(f.create_group(f"points/{name}"))
        summary = f.create_group("summary")
        summary.create_dataset("runs", data=list(STUDY_RUNS), dtype=strings)
        if with_points:
            summary.create_dataset("points", data=list(STUDY_POINTS), dtype=strings)
        summary.create_dataset("parameters/interactions.alpha", data=["0.8", "0.9", "0.8"],
                               dtype=strings)
        q = summary.create_group("quantities/observables.temperatures.T_mixture")
        q.create_dataset("value", data=[1.5, 1.25, math.nan])
        q.create_dataset("error", data=[0.01, 0.02, math.nan])
        q = summary.create_group("quantities/observables.profiles.middle/heavy/T")
        q.create_dataset("value", data=[2.0, 3.0, 4.0])
        q.create_dataset("error", data=[math.nan, math.nan, math.nan])
        fit = f.create_group("fits/T_alpha_hot")
        fit.attrs.update({"x": "interactions.alpha", "y": "observables.temperatures.T_mixture",
                          "group": "hot"})
        fit.create_dataset("x", data=[0.8, 0.9])
        fit.create_dataset("theta", data=-1.5).attrs["error"] = 0.1
        fit.create_dataset("log_prefactor", data=0.2)
        fit.create_dataset("max_deviation", data=0.01)
        fit.create_dataset("valid", data=np.int64(1))
        perf = f.create_group("performance")
        perf.create_dataset("ran", data=np.int64(3))
        if tradeoff:
            write_tradeoff(f.create_group("tradeoff"))
    return path


def write_tradeoff(g):
    """A /tradeoff group of two runs and one quantity."""
    strings = h5py.string_dtype()
    for key, values in (("runs", ["base", "reference"]), ("knobs", ["base", "reference"]),
                        ("levels", ["1", "best"]), ("quantity_names", ["q"])):
        g.create_dataset(key, data=values, dtype=strings)
    g.create_dataset("cost", data=[1.0, 4.0])
    g.create_dataset("worst_accuracy", data=[0.1, 0.01])
    g.create_dataset("pareto", data=[1, 1])
    g.create_dataset("reference", data=[0, 1])
    q = g.create_group("quantities/q")
    for key, values in (("accuracy", [0.1, 0.01]), ("deviation", [0.08, 0.0]),
                        ("deviation_error", [0.02, 0.01]), ("pareto", [1, 1])):
        q.create_dataset(key, data=values)
    q.create_dataset("reference", data=2.0)
    q.attrs["reference_kind"] = "runs"
