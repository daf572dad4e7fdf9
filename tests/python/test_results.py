#!/usr/bin/python3
"""gran.results: one result file read as a physicist expects (scene, estimates with errors and
units, profiles, series, histograms, performance, frames), and clear refusals.

Run: PYTHONPATH=python /usr/bin/python3 tests/python/test_results.py (make test does).
"""
import math
import unittest

import h5py
import numpy as np

import fixtures
from gran.results import (Estimate, NotAResult, Run, array_at, estimate_at, observables_of_type,
                          with_error)


class ResultFileTest(fixtures.TempDirTest):
    def setUp(self):
        super().setUp()
        self.run = Run.open(fixtures.write_run(self.dir / "run.h5"))

    def tearDown(self):
        self.run.close()
        super().tearDown()

    def test_estimate_carries_value_error_unit_and_sampling_attributes(self):
        t = self.run.estimate("observables/temperatures/T_mixture")
        self.assertEqual((t.value, t.error, t.unit), (1.25, 0.02, "energy"))
        self.assertEqual((t.n_eff, t.tau_int, t.samples, t.converged), (40.0, 1.5, 100, True))

    def test_estimate_unpacks_as_value_and_error_and_prints_with_its_unit(self):
        value, error = self.run.estimate("observables/temperatures/heavy/T")
        self.assertEqual((value, error), (1.0, 0.01))
        self.assertEqual(str(self.run.estimate("observables/temperatures/heavy/T")),
                         "1.000 ± 0.010 energy")
        self.assertEqual(float(self.run.estimate("observables/temperatures/T_mixture")), 1.25)

    def test_scene_is_the_resolved_scene_as_a_dict_with_species_in_order(self):
        self.assertEqual(self.run.scene["title"], "synthetic: heated mixture")
        self.assertEqual(self.run.scene["box"]["lengths"], [10, 20])
        self.assertEqual(self.run.species, ["heavy", "light"])
        self.assertEqual(self.run.dimension, 2)
        self.assertEqual(self.run.name, "run")

    def test_profile_is_position_value_and_error(self):
        y, t, e = self.run.profile("observables/profiles/heavy/T")
        np.testing.assert_array_equal(y, fixtures.POSITION)
        np.testing.assert_array_equal(t, [1, 2, 3, 4])
        np.testing.assert_array_equal(e, [0.1, 0.2, 0.3, 0.4])

    def test_series_takes_the_time_axis_of_its_observable(self):
        time, t, error = self.run.series("observables/temperatures/heavy/series/T")
        np.testing.assert_array_equal(time, fixtures.TIME)
        np.testing.assert_array_equal(t, fixtures.T_HEAVY)
        self.assertIsNone(error)

    def test_histogram_reads_prefixed_bins_and_gives_their_centres(self):
        h = self.run.histogram("observables/velocity_pdf/heavy/x", "scaled_")
        np.testing.assert_array_equal(h.edges, fixtures.EDGES)
        np.testing.assert_allclose(h.centres, np.arange(-3.5, 4.0, 1.0))
        c, density, error = h.curve()
        np.testing.assert_allclose(error, 0.1 * density)
        self.assertAlmostEqual(float(np.sum(density * np.diff(h.edges))), 1.0, delta=0.01)

    def test_performance_flattens_nested_counters_keeping_integers(self):
        perf = self.run.performance
        self.assertEqual(perf["completed"], 1)
        self.assertIsInstance(perf["completed"], int)
        self.assertEqual(perf["events_per_second"], 2.5e6)
        self.assertEqual(perf["equilibration/shift_z"], 0.3)

    def test_trajectory_frames_positions_times_and_box(self):
        self.assertEqual(self.run.frames, 2)
        np.testing.assert_array_equal(self.run.positions(1), fixtures.FRAMES[1])
        self.assertEqual(self.run.frame_time(1), 1.5)
        np.testing.assert_array_equal(self.run.box_lengths, [10.0, 20.0])
        self.assertEqual(self.run.number("drivers/vibrating_wall/amplitude"), 0.025)

    def test_missing_path_is_a_key_error_naming_the_run_and_the_path(self):
        with self.assertRaisesRegex(KeyError, "run: no 'observables/temperatures/T_rot'"):
            self.run.estimate("observables/temperatures/T_rot")

    def test_group_readers_return_none_for_what_is_absent(self):
        temps = self.run.observable("temperatures")
        self.assertEqual(estimate_at(temps, "T_mixture").value, 1.25)
        self.assertIsNone(estimate_at(temps, "sonine_a2"))
        self.assertIsNone(estimate_at(None, "T"))
        self.assertIsNone(array_at(temps, "absent"))
        self.assertIsNone(self.run.observable("wall_pressure"))
        self.assertEqual(len(observables_of_type(self.run.root, "profiles")), 1)


class RefusalTest(fixtures.TempDirTest):
    def test_missing_file_not_hdf5_and_foreign_hdf5_are_refused_clearly(self):
        with self.assertRaisesRegex(NotAResult, "no such file"):
            Run.open(self.dir / "absent.h5")
        text = self.dir / "notes.h5"
        text.write_text("not hdf5")
        with self.assertRaisesRegex(NotAResult, "not an HDF5 file"):
            Run.open(text)
        other = self.dir / "other.h5"
        with h5py.File(other, "w") as f:
            f.create_dataset("data", data=[1, 2, 3])
        with self.assertRaisesRegex(NotAResult, "not a gran result"):
            Run.open(other)

    def test_a_scene_that_is_not_a_mapping_is_a_value_error(self):
        path = fixtures.write_run(self.dir / "bad.h5", scene="- just\n- a list\n")
        with Run.open(path) as run, self.assertRaisesRegex(ValueError, "not a YAML mapping"):
            run.scene


class FormattingTest(unittest.TestCase):
    def test_error_rounded_to_two_significant_digits_and_value_to_match(self):
        self.assertEqual(with_error(2.9008790, 0.0114561), "2.901 ± 0.011")
        self.assertEqual(with_error(123.4, 5.6), "123.4 ± 5.6")
        self.assertEqual(with_error(0.5, math.nan), "0.5")
        self.assertEqual(str(Estimate(3.0, 0.0)), "3")


if __name__ == "__main__":
    unittest.main()
