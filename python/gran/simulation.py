"""Running scenes from Python, with the command line's code (the numbers are bit for bit those of
`gran run` for the same scene and seed):

    result = gran.run(gran.Scene.load("studies/demo/vibrated-mixture-2d.yaml"))
    print(result.summary["gamma"])            # 0.8795 ± 0.0022 (the headline of `gran run`)
    with result.open() as run: t, T, _ = run.series("observables/temperatures/series/T_mixture")

    sim = gran.Simulation(scene)              # stepwise
    sim.advance(time=10)
    sim.positions, sim.velocities, sim.species   # NumPy arrays in placement order
    sim.sample(); sim.results().estimate("observables/temperatures/T_mixture")

Ctrl-C stops a run or an advance cleanly: a run writes what it measured and raises Interrupted
(a KeyboardInterrupt that carries the Result); an advance stops at the current state.
"""
from __future__ import annotations

import math
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Callable, Optional, Union

import numpy as np
import yaml

from gran.results import Estimate, Run
from gran.scene import Scene, SceneError, _scene_errors


def _native():
    from gran import native  # noqa: PLC0415

    return native()


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped `gran.run`; what was measured is written. `result` is the Result (status
    `interrupted`), and `gran run --resume <result.path>` continues the run."""

    def __init__(self, result: "Result"):
        super().__init__(f"interrupted: the data measured so far is in {result.path}")
        self.result = result


class WatchdogStop(RuntimeError):
    """The run's watchdog stopped a simulation (stalled time, exploding event rate, non-finite
    state); the message says what happened and which key to change."""


def _estimate(node: Any) -> Any:
    if isinstance(node, Mapping) and "value" in node and "error" in node:
        return Estimate(value=float(node["value"]), error=float(node["error"]),
                        unit=str(node.get("unit", "")),
                        n_eff=float(node.get("n_eff", math.nan)),
                        converged=node.get("converged"))
    return node


class Summary(Mapping):
    """A run's summary (OUT.summary.yaml) as a read-only mapping.

    `summary["status"]` and the other top-level keys as written; a dotted path
    (`summary["observables.temperatures.T_mixture"]`) walks the sections, and a key holding a
    value with its error bar comes back as an Estimate. A short name that is not a top-level key
    is looked up in the `headline` section (`summary["gamma"]`: the temperature ratio `gran run`
    prints last; libgran/run/headline.hpp says which one).
    """

    def __init__(self, data: dict):
        self._data = data or {}

    def __getitem__(self, key: str) -> Any:
        if key in self._data:
            return _estimate(self._data[key])
        headline = self._data.get("headline") or {}
        if key in headline:
            return _estimate(headline[key])
        node: Any = self._data
        parts = key.split(".")
        i = 0
        while i < len(parts):
            # Summary keys may themselves hold dots or slashes ("middle/T"): longest match first.
            for j in range(len(parts), i, -1):
                part = ".".join(parts[i:j])
                if isinstance(node, Mapping) and part in node:
                    node, i = node[part], j
                    break
            else:
                raise KeyError(f"{key!r}: not in the summary (top-level keys: "
                               f"{', '.join(self._data)}; headline: {', '.join(headline) or '-'})")
        return _estimate(node)

    def __iter__(self):
        return iter(self._data)

    def __len__(self):
        return len(self._data)

    def as_dict(self) -> dict:
        """The summary as nested dicts, as in the YAML file."""
        return self._data

    def __repr__(self) -> str:
        return f"<gran.Summary status={self._data.get('status')!r}>"


class Result:
    """What `gran.run` wrote: the result file (`path`), its summary (`summary`, a Summary) and
    how the run ended (`status`: completed, interrupted, stopped by the watchdog, unreliable)."""

    def __init__(self, path: str, summary_path: str, summary: dict, error: str = ""):
        self.path = path
        self.summary_path = summary_path
        self.summary = Summary(summary)
        self.error = error

    @property
    def status(self) -> str:
        """completed, interrupted, stopped by the watchdog, or unreliable (a non-finite error)."""
        return str(self.summary._data.get("status", ""))

    @property
    def completed(self) -> bool:
        """True when the status is `completed`."""
        return self.status == "completed"

    def open(self) -> Run:
        """The result file through the reader (gran.results.Run; a context manager)."""
        return Run.open(self.path)

    def estimate(self, path: str) -> Estimate:
        """An estimate of the result file by its HDF5 path ("observables/temperatures/T_mixture")."""
        with self.open() as run:
            return run.estimate(path)

    def __repr__(self) -> str:
        return f"<gran.Result {self.path} status={self.status!r}>"


def _default_output(scene: Scene) -> str:
    stem = Path(scene.path).stem if not scene.path.startswith("<") else "scene"
    return str(Path("results") / f"{stem}.h5")


def _result(report: dict) -> Result:
    summary = yaml.safe_load(report["summary"]) or {}
    return Result(report["output"], report["summary_file"], summary, report["error"])


def run(scene: Union[Scene, str, os.PathLike], output: Optional[Union[str, os.PathLike]] = None,
        progress: bool = False, callback: Optional[Callable[[int, float], Any]] = None,
        every: int = 1) -> Result:
    """Runs a scene as `gran run` does and returns its Result.

    scene:    a Scene, or the path of a scene file.
    output:   the result file (.h5); default results/<scene file stem>.h5 as `gran run`; the
              summary goes beside it (.summary.yaml).
    progress: the progress line on stderr, as `gran run` prints it.
    callback: called as callback(samples, time) after every `every` measurement samples, with
              the simulation paused; an exception it raises stops the run (the data measured so
              far is written) and propagates with the Result as its `result` attribute (a
              KeyboardInterrupt becomes Interrupted).
    Raises SceneError (invalid scene), OSError (an output that cannot be written), Interrupted
    (Ctrl-C; the result holds the data measured so far) and WatchdogStop (the watchdog stopped
    the run; its data is written, at `e.result`)."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    output = str(output) if output is not None else _default_output(scene)
    try:
        with _scene_errors():
            report = _native().run(scene.native(), output, bool(progress), callback, int(every))
    except BaseException as error:  # the callback's exception, with the data written
        report = getattr(error, "gran_report", None)
        if report is None:
            raise
        result = _result(report)
        if isinstance(error, KeyboardInterrupt):
            raise Interrupted(result) from error
        error.result = result
        raise
    result = _result(report)
    if report["interrupted"]:
        raise Interrupted(result)
    if report["error"]:
        error = WatchdogStop(report["error"])
        error.result = result
        raise error
    return result


class Simulation:
    """One simulation of a scene, advanced step by step from Python; the engine, drivers and
    observables are those of `gran run` (an advance to a time, a number of collisions or of the
    engine's events or steps gives the same state as the command line's run at that point)."""

    def __init__(self, scene: Union[Scene, str, os.PathLike]):
        if not isinstance(scene, Scene):
            scene = Scene.load(scene)
        self.scene = scene
        with _scene_errors():
            self._sim = _native().Simulation(scene.native())

    def advance(self, time: Optional[float] = None, collisions: Optional[int] = None,
                events: Optional[int] = None, steps: Optional[int] = None) -> "Simulation":
        """Advances to the simulated time `time` (absolute), or by `collisions` collisions, or by
        `events` events (event-driven engine) / `steps` time steps (DEM), whichever comes first;
        returns the simulation. Ctrl-C stops at the current state and raises KeyboardInterrupt;
        the watchdog raises WatchdogStop."""
        if events is not None and steps is not None:
            raise ValueError("give events (event_driven) or steps (dem), not both")
        work = events if events is not None else steps
        if work is not None and self.work_unit != ("events" if events is not None else "steps"):
            raise ValueError(f"this engine counts {self.work_unit}, not "
                             f"{'events' if events is not None else 'steps'}")
        if time is None and collisions is None and work is None:
            raise ValueError("advance: give time, collisions, events or steps")
        for name, v in (("collisions", collisions), ("events/steps", work)):
            if v is not None and v < 0:
                raise ValueError(f"advance: {name} must be >= 0, not {v}")
        outcome = self._sim.advance(math.inf if time is None else float(time),
                                    int(collisions or 0), int(work or 0))
        if outcome == "interrupted":
            raise KeyboardInterrupt(f"gran.Simulation.advance interrupted at t = {self.time:g}")
        if outcome in ("stalled", "watchdog"):
            raise WatchdogStop(self._sim.failure or f"the simulation {outcome} at t = {self.time}")
        return self

    @property
    def time(self) -> float:
        """The simulated time."""
        return self._sim.time

    @property
    def collisions(self) -> int:
        """Collisions so far (pair collisions; wall hits are not counted)."""
        return self._sim.collisions

    @property
    def work(self) -> int:
        """Events (event_driven) or steps (dem) done so far; see work_unit."""
        return self._sim.work

    @property
    def work_unit(self) -> str:
        """"events" (event_driven engine) or "steps" (dem)."""
        return self._sim.work_unit

    @property
    def dimension(self) -> int:
        """2 or 3."""
        return self._sim.dimension

    @property
    def positions(self) -> np.ndarray:
        """N x D positions (a copy), particle k being the k-th placed."""
        return self._sim.positions()

    @property
    def velocities(self) -> np.ndarray:
        """N x D velocities (a copy), in placement order."""
        return self._sim.velocities()

    @property
    def angular_velocities(self) -> np.ndarray:
        """N x 1 (2D) or N x 3 (3D) angular velocities; N x 0 when the grains do not rotate."""
        return self._sim.angular_velocities()

    @property
    def species(self) -> np.ndarray:
        """The species index of every particle (the order of the scene's `species` list)."""
        return self._sim.species()

    def sample(self, measuring: bool = True, expected: int = 0) -> None:
        """Samples every observable at the current state. `expected`: how many samples the
        measurement will take (histogram and profile blocks are sized by it); 0: the scene's
        run.measurement / run.sample_interval."""
        self._sim.sample(bool(measuring), int(expected))

    def results(self) -> Run:
        """What the observables and drivers have measured so far, as a result file read by
        gran.results (a Run over a temporary file, removed when the Run is closed)."""
        fd, path = tempfile.mkstemp(suffix=".h5", prefix="gran-measurements-")
        os.close(fd)
        try:
            self._sim.write_measurements(path)
            run_ = Run.open(path)
        finally:
            os.unlink(path)  # the open file stays readable until it is closed
        return run_

    def __repr__(self) -> str:
        return (f"<gran.Simulation {self.scene.path} t={self.time:g} "
                f"{self.work} {self.work_unit}>")


def study(path: Union[str, os.PathLike], output: Optional[Union[str, os.PathLike]] = None,
          jobs: int = 0, progress: bool = False, reuse_any_version: bool = False):
    """Runs a study file as `gran study` does (each run a `gran run` process of this build; `jobs`
    at once, 0: all cores; completed runs are reused) and returns the merged study
    (gran.open(<output>/<study>.study.h5): a Study with its table and fits)."""
    from gran.studies import Study  # noqa: PLC0415

    with _scene_errors():
        report = _native().study(str(path), "" if output is None else str(output), int(jobs),
                                 bool(progress), bool(reuse_any_version))
    if report["interrupted"]:
        raise KeyboardInterrupt(f"gran.study interrupted: completed runs are kept under "
                                f"{Path(report['merged']).parent}; a rerun reuses them")
    if report["failed"]:
        raise RuntimeError(f"gran.study: {report['failed']} runs failed "
                           f"(see {Path(report['merged']).parent})")
    import h5py  # noqa: PLC0415

    return Study(h5py.File(report["merged"], "r"))


__all__ = ["Interrupted", "Result", "SceneError", "Simulation", "Summary", "WatchdogStop", "run",
           "study"]
