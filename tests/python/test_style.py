#!/usr/bin/python3
"""gran.style: figures written as PNG files without a display, with the shared helpers.

Run: PYTHONPATH=python /usr/bin/python3 tests/python/test_style.py (make test does).
"""
import math
import tempfile
import unittest
from pathlib import Path

import matplotlib
import numpy as np

from gran import style

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


class StyleTest(unittest.TestCase):
    def test_importing_selects_the_file_only_backend(self):
        self.assertEqual(matplotlib.get_backend().lower(), "agg")

    def test_save_writes_name_png_and_closes_the_figure(self):
        with tempfile.TemporaryDirectory() as tmp:
            fig, ax = style.plt.subplots()
            style.errorbars(ax, (np.arange(3.0), np.ones(3), 0.1 * np.ones(3)), "o", "data")
            style.label(ax, "x", "y", "panel")
            style.save(fig, tmp, "fig1", "title")
            self.assertEqual((Path(tmp) / "fig1.png").read_bytes()[:8], PNG_MAGIC)
            self.assertNotIn(fig.number, style.plt.get_fignums())

    def test_label_names_the_axes_and_adds_a_legend(self):
        fig, ax = style.plt.subplots()
        ax.plot([0, 1], [0, 1], label="line")
        style.label(ax, "time", "temperature T", "cooling")
        self.assertEqual((ax.get_xlabel(), ax.get_ylabel(), ax.get_title()),
                         ("time", "temperature T", "cooling"))
        self.assertIsNotNone(ax.get_legend())
        style.plt.close(fig)

    def test_positive_keeps_what_a_log_axis_shows_with_bars_above_zero(self):
        x, y, e = style.positive((np.arange(4.0), np.array([0.0, 1.0, -1.0, 2.0]),
                                  np.array([1.0, 5.0, 1.0, 0.5])))
        np.testing.assert_array_equal(x, [1.0, 3.0])
        np.testing.assert_array_equal(y, [1.0, 2.0])
        np.testing.assert_array_equal(e, [0.999, 0.5])

    def test_gaussian_reference_is_the_unit_variance_density(self):
        fig, ax = style.plt.subplots()
        style.gaussian(ax, -6, 6)
        c, p = ax.lines[0].get_data()
        self.assertAlmostEqual(float(p.max()), 1 / math.sqrt(2 * math.pi), places=4)
        self.assertAlmostEqual(float(np.trapz(p, c)), 1.0, places=6)
        self.assertAlmostEqual(float(np.trapz(c**2 * p, c)), 1.0, places=5)
        style.plt.close(fig)


if __name__ == "__main__":
    unittest.main()
