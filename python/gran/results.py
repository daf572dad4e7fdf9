"""Reading one gran result file (`gran run ... -o RUN.h5`, or one run inside a `.study.h5`).

A result file is HDF5 with H5MD metadata (`/h5md`), the fully resolved scene as YAML text
(`/parameters/scene`), the observables (`/observables/<name>`, each group with a `type`
attribute), the drivers' counters (`/drivers`), optional trajectory frames (`/particles/all`) and
the run's performance counters (`/performance`). Scalar estimates are datasets with the attributes
`error` (one standard error), `unit`, `n_eff` (effectively independent samples), `tau_int`
(integrated autocorrelation time, in samples), `samples` and `converged`; profiles are arrays with
a sibling `<name>_error`; histograms are `edges`, `density`, `error` (optionally prefixed, e.g.
`scaled_edges`). See docs/physics.md ("Error bars") and docs/studies.md.

The module-level functions take an h5py group and return None for what is absent (a figure skips
what a result does not hold); `Run` names what it cannot find in a KeyError.
"""
import math
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple, Optional

import h5py
import numpy as np

AXES = ("x", "y", "z")


class NotAResult(Exception):
    """The input is missing or is not a gran result file."""


# --- values with errors --------------------------------------------------------------------------


def with_error(value, error):
    """'value ± error' with the error rounded to two significant digits ('value' alone when the
    error is not a positive number)."""
    if not math.isfinite(error) or error <= 0:
        return f"{value:.4g}"
    decimals = max(0, 1 - math.floor(math.log10(error)))
    return f"{value:.{decimals}f} ± {error:.{decimals}f}"


@dataclass(frozen=True)
class Estimate:
    """A measured scalar with its one-standard-error bar and how that error was obtained.

    Unpacks as `(value, error)`: `value, error = run.estimate(...)`. `n_eff` is the number of
    effectively independent samples, `tau_int` the integrated autocorrelation time (in samples),
    `converged` whether the error estimate reached its plateau; NaN / None when not recorded.
    """

    value: float
    error: float = math.nan
    unit: str = ""
    n_eff: float = math.nan
    tau_int: float = math.nan
    samples: Optional[int] = None
    converged: Optional[bool] = None

    @classmethod
    def from_dataset(cls, dataset):
        """The estimate stored in a scalar HDF5 dataset and its attributes."""
        attrs = dataset.attrs
        samples = attrs.get("samples")
        converged = attrs.get("converged")
        return cls(value=float(dataset[()]), error=float(attrs.get("error", math.nan)),
                   unit=as_text(attrs.get("unit", "")),
                   n_eff=float(attrs.get("n_eff", math.nan)),
                   tau_int=float(attrs.get("tau_int", math.nan)),
                   samples=None if samples is None else int(samples),
                   converged=None if converged is None else bool(converged))

    def __iter__(self):
        yield self.value
        yield self.error

    def __float__(self):
        return self.value

    def __str__(self):
        text = with_error(self.value, self.error)
        return f"{text} {self.unit}" if self.unit else text


class Curve(NamedTuple):
    """y(x) with one-standard-error bars (error None when there are none); unpacks as
    `x, value, error`."""

    x: np.ndarray
    value: np.ndarray
    error: Optional[np.ndarray]


def bin_centres(edges):
    """Centres of the bins of a histogram from its edges."""
    edges = np.asarray(edges, dtype=float)
    return 0.5 * (edges[:-1] + edges[1:])


class Histogram(NamedTuple):
    """A normalised histogram (probability density) with one-standard-error bars per bin."""

    edges: np.ndarray
    density: np.ndarray
    error: Optional[np.ndarray]

    @property
    def centres(self):
        """Bin centres."""
        return bin_centres(self.edges)

    def curve(self):
        """The density against the bin centres, as a Curve."""
        return Curve(self.centres, self.density, self.error)


# --- reading from an h5py group (None when absent) ------------------------------------------------


def as_text(value):
    """A string dataset's or attribute's value as str (h5py returns bytes for variable-length
    strings)."""
    return value.decode() if isinstance(value, bytes) else str(value)


def texts(dataset):
    """A 1D string dataset as a list of str."""
    return [as_text(s) for s in dataset[()]]


def estimate_at(group, name):
    """The Estimate of a scalar dataset `name` below `group`, or None when absent."""
    if group is None or name not in group or not isinstance(group[name], h5py.Dataset):
        return None
    return Estimate.from_dataset(group[name])


def array_at(group, name):
    """A dataset below `group` as a float array, or None when absent."""
    if group is None or name not in group:
        return None
    return np.asarray(group[name][()], dtype=float)


def observables_of_type(root, type_name):
    """The observable groups (below root/observables) whose `type` attribute is `type_name`."""
    if "observables" not in root:
        return []
    return [g for g in root["observables"].values()
            if isinstance(g, h5py.Group) and as_text(g.attrs.get("type", "")) == type_name]


def species_groups(group, required):
    """{species: subgroup} of an observable's per-species subgroups (those holding `required`)."""
    return {name: sub for name, sub in group.items()
            if isinstance(sub, h5py.Group) and required in sub}


def numbers(group):
    """Every scalar dataset below `group` as {path: number}, nested groups as 'a/b' paths (e.g.
    /performance: events_per_second, wall_time, equilibration/shift_z)."""
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.shape == () and obj.dtype.kind in "iuf":
            value = obj[()]
            out[name] = int(value) if obj.dtype.kind in "iu" else float(value)

    group.visititems(visit)
    return out


def parse_scene(text):
    """The resolved scene (YAML text of /parameters/scene) as a dict (needs PyYAML: Debian's
    python3-yaml). Raises ValueError when the text is not a YAML mapping."""
    import yaml

    try:
        scene = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise ValueError(f"the stored scene is not valid YAML: {e}") from None
    if not isinstance(scene, dict):
        raise ValueError("the stored scene is not a YAML mapping")
    return scene


# --- one run --------------------------------------------------------------------------------------


class Run:
    """One gran result: a run file, or the group of one run inside a `.study.h5` file.

    Paths are relative to the run's root, e.g. `run.estimate("observables/temperatures/T_mixture")`.
    Use `gran.open(path)` (or `Run.open`) for a file, as a context manager to close it.
    """

    def __init__(self, group, name=None):
        """Wrap an open h5py group holding a result (`/h5md`-less groups of a study file too)."""
        self.root = group
        self.name = name or Path(group.file.filename).stem
        self._scene = None

    @classmethod
    def open(cls, path):
        """Open a run file read-only; NotAResult when it is missing or not a gran result."""
        path = Path(path)
        if not path.is_file():
            raise NotAResult(f"no such file: {path}")
        try:
            f = h5py.File(path, "r")
        except OSError as e:
            raise NotAResult(f"{path} is not an HDF5 file ({e})") from None
        if "h5md" not in f or "observables" not in f:
            f.close()
            raise NotAResult(f"{path} is not a gran result (no /h5md or /observables group)")
        return cls(f, path.stem)

    def close(self):
        """Close the file (only when this Run opened it)."""
        if isinstance(self.root, h5py.File):
            self.root.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return f"Run({self.name!r})"

    # --- the scene ---

    @property
    def scene_text(self):
        """The resolved scene as stored (YAML text); '' when the result has none."""
        if "parameters/scene" not in self.root:
            return ""
        return as_text(self.root["parameters/scene"][()])

    @property
    def scene(self):
        """The resolved scene (every default filled in) as a dict."""
        if self._scene is None:
            self._scene = parse_scene(self.scene_text)
        return self._scene

    @property
    def species(self):
        """Species names in scene order (the first is the reference of the temperature ratios)."""
        return [s["name"] for s in self.scene["species"]]

    @property
    def dimension(self):
        """2 or 3."""
        return int(self.scene["dimension"])

    # --- observables ---

    def _node(self, path):
        if path not in self.root:
            raise KeyError(f"{self.name}: no '{path}' in the result")
        return self.root[path]

    def estimate(self, path):
        """The Estimate (value, error, unit, n_eff, ...) of a scalar dataset."""
        return Estimate.from_dataset(self._node(path))

    def array(self, path):
        """A dataset as a float array."""
        return np.asarray(self._node(path)[()], dtype=float)

    def number(self, path):
        """A scalar dataset (a counter or a parameter such as drivers/vibrating_wall/amplitude)."""
        return float(self._node(path)[()])

    def observable(self, type_name):
        """The first observable group of type `type_name` (h5py group), or None."""
        groups = observables_of_type(self.root, type_name)
        return groups[0] if groups else None

    def profile(self, path):
        """A profile across the cell, e.g. 'observables/profiles/grain/T': Curve(position, value,
        error), position from the observable's `position` (or `z`) dataset."""
        observable = "/".join(path.split("/")[:2])
        group = self._node(observable)
        axis = "position" if "position" in group else "z"
        return Curve(self.array(f"{observable}/{axis}"), self.array(path),
                     array_at(self.root, path + "_error"))

    def series(self, path):
        """A time series, e.g. 'observables/temperatures/grain/series/T': Curve(time, value,
        None). Since issue 14 an H5MD element {step, time, value}; in older files a dataset
        whose times are the observable's `time` dataset."""
        node = self._node(path)
        if isinstance(node, h5py.Group):
            return Curve(np.asarray(node["time"][()], dtype=float), np.asarray(node["value"][()]),
                         None)
        observable = "/".join(path.split("/")[:2])
        return Curve(self.array(f"{observable}/time"), self.array(path), None)

    def series_steps(self, path):
        """The engine's events or steps at each sample of an H5MD time series."""
        return np.asarray(self._node(path)["step"][()])

    def histogram(self, path, kind=""):
        """The histogram in group `path` (datasets `<kind>edges`, `<kind>density`, `<kind>error`;
        kind e.g. 'scaled_' for the rescaled velocity distributions)."""
        group = self._node(path)
        return Histogram(np.asarray(group[kind + "edges"][()], dtype=float),
                         np.asarray(group[kind + "density"][()], dtype=float),
                         array_at(group, kind + "error"))

    @property
    def performance(self):
        """The run's performance counters: {name: number}, e.g. 'events_per_second',
        'wall_time' [s], 'completed', 'equilibration/shift_z'."""
        return numbers(self.root["performance"]) if "performance" in self.root else {}

    # --- trajectory frames (scenes with a `trajectory` output) ---

    @property
    def frames(self):
        """Number of stored trajectory frames."""
        return self._node("particles/all/position/value").shape[0]

    def positions(self, k, unwrapped=False):
        """Particle positions of frame k, shape (N, dimension), wrapped into the box; with
        `unwrapped`, plus image * L on periodic axes (the distance actually travelled)."""
        r = self._node("particles/all/position/value")[k]
        if not unwrapped or "image" not in self.root["particles/all"]:
            return r
        return r + self.images(k) * self.box_lengths

    def velocities(self, k):
        """Particle velocities of frame k, shape (N, dimension)."""
        return self._node("particles/all/velocity/value")[k]

    def images(self, k):
        """Periodic images of frame k (N, dimension): crossings of each periodic axis (+1 out
        through L); zeros when no axis is periodic."""
        if "image" not in self.root["particles/all"]:
            return np.zeros_like(self.positions(k), dtype=np.int64)
        return self._node("particles/all/image/value")[k]

    def angular_velocities(self, k):
        """Angular velocities of frame k: (N, 1) in 2D, (N, 3) in 3D; None when grains do not
        rotate."""
        if "angular_velocity" not in self.root["particles/all"]:
            return None
        return self._node("particles/all/angular_velocity/value")[k]

    def frame_step(self, k):
        """The engine's events (event_driven) or steps (dem) at frame k."""
        return int(self._node("particles/all/position/step")[k])

    @property
    def particle_species(self):
        """Species index of every particle of the trajectory (N,)."""
        return self._node("particles/all/species")[()]

    def frame_time(self, k):
        """Time of frame k."""
        return float(self._node("particles/all/position/time")[k])

    @property
    def box_lengths(self):
        """Box edge lengths of the trajectory (H5MD /particles/all/box/edges: a D x D matrix of
        edge vectors per frame, or a vector in older files)."""
        edges = self.root["particles/all/box/edges"]
        if isinstance(edges, h5py.Group):  # time-dependent: the box of the first frame
            edges = edges["value"][0]
        else:
            edges = edges[()]
        edges = np.asarray(edges, dtype=float)
        return np.diag(edges) if edges.ndim == 2 else edges
