#!/usr/bin/python3
"""Tests of studies/plot_result.py on small synthetic result files.

Run: PYTHONPATH=python /usr/bin/python3 tests/studies/test_plot_result.py (make test does).
"""

import math
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import h5py
import numpy as np

SCRIPT = Path(__file__).resolve().parents[2] / "studies" / "plot_result.py"

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def scalar(group, name, value, error):
    group.create_dataset(name, data=value).attrs["error"] = error


def write_mono_3d(path):
    """A 3D mono-species result with temperatures and velocity_pdf only (no performance)."""
    rng = np.random.default_rng(1)
    with h5py.File(path, "w") as f:
        f.create_group("h5md/creator").attrs["name"] = "gran"
        f.create_dataset("parameters/scene", data="title: 'synthetic: spheres'\ndimension: 3\n",
                         dtype=h5py.string_dtype())
        temps = f.create_group("observables/temperatures")
        temps.attrs["type"] = "temperatures"
        temps.create_dataset("time", data=np.linspace(1.0, 10.0, 50))
        g = temps.create_group("grains")
        for key in ("T", "T_x", "T_y", "T_z"):
            scalar(g, key, 1.0, 0.01)
            g.create_dataset(f"series/{key}", data=1.0 + 0.05 * rng.standard_normal(50))
        scalar(g, "sonine_a2", 0.02, 0.005)
        pdf = f.create_group("observables/velocity_pdf")
        pdf.attrs["type"] = "velocity_pdf"
        edges = np.linspace(-5.0, 5.0, 41)
        c = 0.5 * (edges[1:] + edges[:-1])
        density = np.exp(-0.5 * c**2) / math.sqrt(2 * math.pi)
        density[0] = 0.0  # an empty bin must not break the log axis
        for axis in "xyz":
            a = pdf.create_group(f"grains/{axis}")
            a.create_dataset("scaled_edges", data=edges)
            a.create_dataset("scaled_density", data=density)
            a.create_dataset("scaled_error", data=0.05 * density)
            scalar(a, "kurtosis", 3.0, 0.01)


class PlotResultTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def run_script(self, *args):
        return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)],
                              capture_output=True, text=True, timeout=120)

    def test_plots_a_partial_3d_mono_species_result(self):
        result = self.dir / "mono.h5"
        write_mono_3d(result)
        done = self.run_script(result)
        self.assertEqual(done.returncode, 0, done.stderr)
        png = result.with_suffix(".png")
        self.assertEqual(done.stdout.strip(), str(png))
        self.assertEqual(png.read_bytes()[:8], PNG_MAGIC)

    def test_output_option(self):
        result = self.dir / "mono.h5"
        write_mono_3d(result)
        out = self.dir / "figures" / "out.png"
        done = self.run_script(result, "-o", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(out.read_bytes()[:8], PNG_MAGIC)

    def test_missing_file_fails_clearly(self):
        done = self.run_script(self.dir / "absent.h5")
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("no such file", done.stderr)

    def test_other_files_are_rejected(self):
        text = self.dir / "notes.h5"
        text.write_text("not hdf5")
        other = self.dir / "other.h5"
        with h5py.File(other, "w") as f:
            f.create_dataset("data", data=[1, 2, 3])
        for path in (text, other):
            done = self.run_script(path)
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("not", done.stderr)


if __name__ == "__main__":
    unittest.main()
