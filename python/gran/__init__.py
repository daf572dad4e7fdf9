"""gran's Python package: reading, fitting and plotting the results of gran runs and studies.

Found through `PYTHONPATH=<repository>/python` (the Makefile, CTest and `gran tradeoff` set it;
by hand: `export PYTHONPATH=$PWD/python`). Runs with Debian's /usr/bin/python3 (h5py, numpy,
PyYAML; matplotlib for `gran.style`); pandas is optional.

    import gran
    with gran.open("results/demo/vibrated-mixture-2d.h5") as run:
        print(run.scene["title"], run.estimate("observables/temperatures/T_mixture"))
    with gran.open("results/x/sweep.study.h5") as study:
        for row in study.table.runs(point="g_rv"): ...

Modules: `gran.results` (one result file: scene, estimates with errors and units, profiles,
series, histograms, performance, trajectory frames), `gran.study` (the study table with its
`point` column, fits, merged study files, trade-offs), `gran.fits` (power laws, nonlinear least
squares), `gran.comparison` (comparison.csv against a paper), `gran.style` (figures; imports
matplotlib). A later compiled module (pybind11) joins this package.
"""
from pathlib import Path

import h5py

from gran.results import Curve, Estimate, Histogram, NotAResult, Run
from gran.study import Study, StudyFit, StudyFolder, StudyTable, read_fits

# `open` is left out of the star import, which would hide the builtin: call it as gran.open.
__all__ = ["Curve", "Estimate", "Histogram", "NotAResult", "Run", "Study", "StudyFit",
           "StudyFolder", "StudyTable", "read_fits"]


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
