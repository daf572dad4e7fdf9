#!/usr/bin/python3
"""Trajectories that other tools open (libgran/run/trajectory.hpp): a 3D periodic run's
OUT.trajectory.h5 read by MDAnalysis (Debian's python3-mdanalysis) and its OUT.trajectory.xdmf
read by ParaView's XDMF reader (pvpython, Debian's paraview), with counts, fields and numbers
checked against the file; and gran.results reading the same frames through the result file.

Run: make test (CTest sets GRAN_BINARY), or by hand:
PYTHONPATH=python GRAN_BINARY=build/gran /usr/bin/python3 -m pytest tests/python/test_trajectory_tools.py
"""
import json
import os
import shutil
import subprocess
import unittest
import warnings
from pathlib import Path

import fixtures
import gran
import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
GRAN = os.environ.get("GRAN_BINARY", str(ROOT / "build" / "gran"))
SCENE = """title: periodic 3D heated gas
dimension: 3
seed: 5
particles: 200
species:
  - {name: big, diameter: 1.2, mass: 2, number_fraction: 0.5}
  - {name: small, number_fraction: 0.5}
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.05}]
observables: [{type: temperatures}]
run: {equilibration: 5, measurement: 50, sample_interval: 1}
output: {frames: 10}
"""
PVPYTHON = shutil.which("pvpython")
# pvpython: open the XDMF, report per frame time, point count, arrays and one point.
PV_SCRIPT = """
import json, sys
from paraview.simple import XDMFReader, servermanager
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
times = list(r.TimestepValues)
r.UpdatePipeline(times[3])
d = servermanager.Fetch(r)
pd = d.GetPointData()
arrays = {pd.GetArrayName(i): pd.GetArray(i).GetNumberOfComponents()
          for i in range(pd.GetNumberOfArrays())}
print(json.dumps({"times": times, "points": d.GetNumberOfPoints(), "arrays": arrays,
                  "point7": list(d.GetPoint(7)),
                  "species7": pd.GetArray("species").GetValue(7)}))
"""


class TrajectoryToolsTest(fixtures.TempDirTest):
    def setUp(self):
        super().setUp()
        (self.dir / "gas.yaml").write_text(SCENE)
        subprocess.run([GRAN, "run", str(self.dir / "gas.yaml"), "-o", str(self.dir / "gas.h5"),
                        "--quiet"], check=True, stdout=subprocess.DEVNULL)
        self.trajectory = self.dir / "gas.trajectory.h5"
        with h5py.File(self.trajectory, "r") as f:
            all_ = f["particles/all"]
            self.positions = all_["position/value"][()]
            self.times = all_["position/time"][()]
            self.steps = all_["position/step"][()]
            self.species = all_["species"][()]
            self.box = np.diag(all_["box/edges/value"][0])

    def test_mdanalysis_reads_the_periodic_3d_trajectory(self):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import MDAnalysis as mda
        # MDAnalysis 2.4 has no H5MD topology reader: an empty universe of N atoms takes it.
        u = mda.Universe.empty(200, trajectory=False)
        u.load_new(str(self.trajectory), format="H5MD", convert_units=False)
        self.assertEqual(u.trajectory.n_frames, 10)
        ts = u.trajectory[4]
        np.testing.assert_allclose(ts.dimensions[:3], self.box, rtol=1e-6)
        np.testing.assert_allclose(ts.dimensions[3:], [90, 90, 90])
        np.testing.assert_allclose(ts.positions, self.positions[4], rtol=1e-6)
        self.assertEqual(ts.time, self.times[4])
        self.assertEqual(ts.data["step"], self.steps[4])

    @unittest.skipIf(PVPYTHON is None, "pvpython (Debian's paraview) is not installed; "
                                       "make test installs it")
    def test_paraview_reads_the_xdmf_with_species_and_velocities_as_point_data(self):
        out = subprocess.run([PVPYTHON, "-c", PV_SCRIPT, str(self.dir / "gas.trajectory.xdmf")],
                             check=True, capture_output=True, text=True, timeout=300).stdout
        got = json.loads(out.strip().splitlines()[-1])
        np.testing.assert_allclose(got["times"], self.times)
        self.assertEqual(got["points"], 200)
        self.assertEqual(got["arrays"], {"velocity": 3, "species": 1, "diameter": 1, "mass": 1,
                                         "image": 3})
        np.testing.assert_allclose(got["point7"], self.positions[3][7])
        self.assertEqual(got["species7"], self.species[7])

    def test_the_result_file_reads_the_frames_through_its_link(self):
        with gran.open(self.dir / "gas.h5") as run:
            self.assertEqual(run.frames, 10)
            np.testing.assert_array_equal(run.positions(2), self.positions[2])
            np.testing.assert_allclose(run.box_lengths, self.box)
            self.assertEqual(run.frame_step(2), self.steps[2])
            # Unwrapped: plus image * L (tests/libgran/run/test_trajectory.cpp checks that the
            # images make the motion continuous).
            images = run.images(9)
            self.assertGreater(np.abs(images).sum(), 0)
            np.testing.assert_array_equal(run.positions(9, unwrapped=True),
                                          self.positions[9] + images * self.box)


if __name__ == "__main__":
    unittest.main()
