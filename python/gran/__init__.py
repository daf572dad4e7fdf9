"""gran's Python package: scenes, runs and simulations (the compiled module), and reading,
fitting and plotting the results of gran runs and studies.

Found through `PYTHONPATH=<repository>/python` (the Makefile, CTest and `gran tradeoff` set it;
by hand: `export PYTHONPATH=$PWD/python`). Runs with Debian's /usr/bin/python3 (h5py, numpy,
PyYAML; matplotlib for `gran.style`); pandas is optional. The compiled module `gran._native`
is built by `make` into <build>/python/gran/ and found there (the build folder `build` beside
`python/`, or the folder named by the environment variable GRAN_BUILD_DIR).

    import gran
    result = gran.run(gran.Scene.load("studies/demo/vibrated-mixture-2d.yaml"))
    print(result.summary["gamma"])

    import gran
    with gran.open("results/demo/vibrated-mixture-2d.h5") as run:
        print(run.scene["title"], run.estimate("observables/temperatures/T_mixture"))
    with gran.open("results/x/sweep.study.h5") as study:
        for row in study.table.runs(point="g_rv"): ...

Modules: `gran.results` (one result file: scene, estimates with errors and units, profiles,
series, histograms, performance, trajectory frames), `gran.studies` (the study table with its
`point` column, fits, merged study files, trade-offs), `gran.fits` (power laws, nonlinear least
squares), `gran.comparison` (comparison.csv against a paper), `gran.style` (figures; imports
matplotlib), `gran.scene` (Scene, SceneError) and `gran.simulation` (run, Simulation, Result,
study) over the compiled module. docs/python.md is the guide.
"""
import os
from pathlib import Path

import h5py

from gran.results import Curve, Estimate, Histogram, NotAResult, Run
from gran.scene import Scene, SceneError
from gran.simulation import Interrupted, Result, Simulation, Summary, WatchdogStop, run
from gran.simulation import study as run_study
from gran.studies import Study, StudyFit, StudyFolder, StudyTable, read_fits

# `open` is left out of the star import, which would hide the builtin: call it as gran.open.
__all__ = ["Curve", "Estimate", "Histogram", "Interrupted", "NotAResult", "Result", "Run",
           "Scene", "SceneError", "Simulation", "Study", "StudyFit", "StudyFolder", "StudyTable",
           "Summary", "WatchdogStop", "read_fits", "run", "run_study", "version"]

# The compiled module lives in the build tree: <build>/python/gran/_native*.so.
_BUILD = Path(os.environ.get("GRAN_BUILD_DIR", Path(__file__).resolve().parents[2] / "build"))
__path__.append(str(_BUILD / "python" / "gran"))  # noqa: F821  (the package's search path)


def native():
    """The compiled module gran._native; ImportError saying how to build it when it is absent."""
    try:
        from gran import _native  # noqa: PLC0415
    except ImportError as e:
        raise ImportError(
            f"gran's compiled module is not built ({e}); run `make build` (or `make test`) in the "
            f"repository, or point GRAN_BUILD_DIR at the build folder (looked in {_BUILD})") from e
    return _native


def version():
    """The compiled code's version: version, commit, dirty, build_type, compiler, code_id."""
    return dict(native().version())


def study(path, output=None, jobs=0, progress=False, reuse_any_version=False):
    """Runs a study file as `gran study` does and returns the merged Study (see
    gran.simulation.study)."""
    return run_study(path, output, jobs, progress, reuse_any_version)


def open(path):  # noqa: A001  (gran.open, as h5py.File or tarfile.open)
    """Open a gran result: a run file (`.h5`, returns a Run), a merged study (`.study.h5`, returns
    a Study) or a study table (`.study.csv`, returns a StudyTable). Run and Study are context
    managers that close the file. NotAResult when the file is missing or none of these."""
    path = Path(path)
    if path.suffix == ".csv":
        if not path.is_file():
            raise NotAResult(f"no such file: {path}")
        return StudyTable.read_csv(path)
    if path.is_file() and path.name.endswith(".study.h5"):
        try:
            f = h5py.File(path, "r")
        except OSError as e:
            raise NotAResult(f"{path} is not an HDF5 file ({e})") from None
        if "study" in f and "summary" in f:
            return Study(f)
        f.close()
    return Run.open(path)
