#!/usr/bin/python3
"""gran.studies: the study table with its `point` column (from CSV and from .study.h5), fits,
merged study files and trade-offs; a real `gran study` read both ways.

Run: PYTHONPATH=python GRAN_BINARY=build/gran /usr/bin/python3 tests/python/test_studies.py
"""
import math
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

import h5py
import numpy as np

import fixtures
from gran.fits import power_law
from gran.studies import NoPointColumn, Study, StudyFolder, StudyTable, read_fits

TABLE = """run,point,interactions.alpha,box.lengths,observables.temperatures.T_mixture,observables.temperatures.T_mixture.error
hot_alpha0.8,hot,0.8,"[0.2, 0.04]",1.5,0.01
cold_alpha0.8,cold,0.8,"[0.2, 0.04]",0.5,
hot_alpha0.9,hot,0.9,"[0.2, 0.05]",,
"""
FITS = """fit,x,y,group,points,theta,theta_error,log_prefactor,max_deviation,valid
T_alpha_hot,interactions.alpha,observables.temperatures.T_mixture,hot,2,-1.5,0.1,0.2,0.3,0
T_alpha,interactions.alpha,observables.temperatures.T_mixture,,3,-1.25,nan,0.1,0.01,1
"""
T = "observables.temperatures.T_mixture"


class StudyTableTest(fixtures.TempDirTest):
    def setUp(self):
        super().setUp()
        (self.dir / "sweep.study.csv").write_text(TABLE)
        (self.dir / "sweep.fits.csv").write_text(FITS)
        self.table = StudyTable.read_csv(self.dir / "sweep.study.csv")

    def test_runs_are_grouped_by_the_point_column_in_table_order(self):
        self.assertEqual(self.table.points(), ["cold", "hot"])
        self.assertEqual([r["run"] for r in self.table.runs("hot")],
                         ["hot_alpha0.8", "hot_alpha0.9"])
        self.assertEqual(len(self.table.runs()), 3)
        self.assertEqual(self.table.run("cold_alpha0.8")["point"], "cold")

    def test_empty_cells_are_nan_values_and_errors(self):
        rows = self.table.runs()
        self.assertEqual(self.table.value_and_error(rows[0], T), (1.5, 0.01))
        value, error = self.table.value_and_error(rows[1], T)
        self.assertEqual(value, 0.5)
        self.assertTrue(math.isnan(error))
        self.assertTrue(all(math.isnan(x) for x in self.table.value_and_error(rows[2], T)))
        np.testing.assert_array_equal(self.table.column("interactions.alpha"), [0.8, 0.8, 0.9])

    def test_records_have_number_columns_and_text_columns(self):
        rec = self.table.records()
        self.assertEqual(rec.dtype["interactions.alpha"], np.dtype("f8"))
        self.assertEqual(rec.dtype["box.lengths"].kind, "U")
        self.assertEqual(list(rec["point"]), ["hot", "cold", "hot"])
        self.assertTrue(math.isnan(rec[T][2]))

    def test_dataframe_with_pandas_or_a_clear_import_error_without(self):
        try:
            import pandas  # noqa: F401
        except ImportError:
            with self.assertRaisesRegex(ImportError, "records"):
                self.table.dataframe()
        else:
            self.assertEqual(list(self.table.dataframe()["point"]), ["hot", "cold", "hot"])

    def test_a_table_without_point_column_is_refused_with_the_remedy(self):
        old = self.dir / "old.study.csv"
        old.write_text("run,interactions.alpha\nhot_alpha0.8,0.8\n")
        with self.assertRaisesRegex(NoPointColumn, "no `point` column.*rerun `gran study"):
            StudyTable.read_csv(old)

    def test_fits_csv_gives_typed_fits_in_file_order(self):
        fits = read_fits(self.dir / "sweep.fits.csv")
        self.assertEqual(list(fits), ["T_alpha_hot", "T_alpha"])
        hot = fits["T_alpha_hot"]
        self.assertEqual((hot.group, hot.points, hot.theta, hot.theta_error), ("hot", 2, -1.5, 0.1))
        self.assertFalse(hot.valid)
        self.assertTrue(fits["T_alpha"].valid)
        self.assertTrue(math.isnan(fits["T_alpha"].theta_error))

    def test_folder_reads_table_fits_and_names_the_missing_study(self):
        folder = StudyFolder(self.dir, "sweep")
        self.assertEqual(len(folder.table), 3)
        self.assertEqual(folder.fit("T_alpha").theta, -1.25)
        with self.assertRaisesRegex(KeyError, "no fit absent in sweep.fits.csv"):
            folder.fit("absent")
        with self.assertRaisesRegex(FileNotFoundError, "other.study.csv is missing"):
            StudyFolder(self.dir, "other")


class MergedStudyTest(fixtures.TempDirTest):
    def test_summary_table_has_runs_points_parameters_and_quantities(self):
        with Study.open(fixtures.write_study(self.dir / "s.study.h5")) as study:
            table = study.table
            self.assertEqual(table.columns[:3], ["run", "point", "interactions.alpha"])
            self.assertEqual([r["point"] for r in table], list(fixtures.STUDY_POINTS))
            row = table.run("hot_alpha0.9")
            self.assertEqual(table.value_and_error(row, T), (1.25, 0.02))
            self.assertEqual(table.number(row, "observables.profiles.middle/heavy/T"), 3.0)
            self.assertEqual(table.rows[2][T], "")

    def test_runs_fits_and_performance_of_a_merged_study(self):
        with Study.open(fixtures.write_study(self.dir / "s.study.h5")) as study:
            run = study.run("cold_alpha0.8")
            self.assertEqual(run.name, "cold_alpha0.8")
            self.assertEqual(run.species, ["heavy", "light"])
            fit = study.fits["T_alpha_hot"]
            self.assertEqual((fit.theta, fit.theta_error, fit.points, fit.valid),
                             (-1.5, 0.1, 2, True))
            self.assertEqual(study.performance["ran"], 3)
            self.assertEqual(study.source, "studies/x/sweep.yaml")

    def test_merged_study_without_points_is_refused(self):
        with Study.open(fixtures.write_study(self.dir / "s.study.h5", with_points=False)) as study:
            with self.assertRaises(NoPointColumn):
                study.table

    def test_tradeoff_group_is_read_and_its_absence_named(self):
        with Study.open(fixtures.write_study(self.dir / "t.study.h5", tradeoff=True)) as study:
            t = study.tradeoff()
            self.assertEqual(t["runs"], ["base", "reference"])
            np.testing.assert_array_equal(t["reference"], [False, True])
            self.assertEqual(t["panels"][0]["kind"], "runs")
            self.assertEqual(t["panels"][0]["reference"], 2.0)
        with Study.open(fixtures.write_study(self.dir / "s.study.h5")) as study:
            with self.assertRaisesRegex(KeyError, "no /tradeoff group"):
                study.tradeoff()


SCENE = """dimension: 2
species: [{name: a, count: 60}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.01}]
observables: [{type: temperatures}]
run: {equilibration: 5, measurement: 60}
"""
STUDY = """scene: scene.yaml
points: [{name: hot, set: {drivers.0.strength: 0.02}}, {name: cold}]
grid: {interactions.alpha: [0.7, 0.8, 0.9]}
fits: [{name: T_alpha, x: interactions.alpha, y: observables.temperatures.T_mixture,
        group_by: point, tolerance: 5}]
"""


@unittest.skipUnless(os.environ.get("GRAN_BINARY"), "GRAN_BINARY (build/gran) not given")
class RealStudyTest(unittest.TestCase):
    """`gran study` on a tiny sweep: the CSV and the merged file hold the same table."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = Path(cls.tmp.name)
        (d / "scene.yaml").write_text(SCENE)
        (d / "sweep.yaml").write_text(STUDY)
        cls.out = d / "out"
        subprocess.run([os.environ["GRAN_BINARY"], "-q", "study", str(d / "sweep.yaml"), "-o",
                        str(cls.out)], check=True, capture_output=True, timeout=300)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_csv_and_merged_file_hold_the_same_table_with_points(self):
        folder = StudyFolder(self.out, "sweep")
        with Study.open(self.out / "sweep.study.h5") as study:
            self.assertEqual(study.table.columns, folder.table.columns)
            self.assertEqual(study.table.rows, folder.table.rows)
        self.assertEqual(folder.table.points(), ["cold", "hot"])
        self.assertEqual([r["run"] for r in folder.table.runs("hot")],
                         ["hot_alpha0.7", "hot_alpha0.8", "hot_alpha0.9"])

    def test_power_law_reproduces_the_fits_of_gran_study(self):
        folder = StudyFolder(self.out, "sweep")
        for point in ("hot", "cold"):
            rows = folder.table.runs(point)
            fit = power_law(folder.table.column("interactions.alpha", rows),
                            folder.table.column(T, rows))
            study_fit = folder.fit(f"T_alpha_{point}")
            self.assertAlmostEqual(fit.exponent, study_fit.theta, delta=1e-5 * abs(fit.exponent))
            self.assertAlmostEqual(fit.exponent_error, study_fit.theta_error,
                                   delta=1e-2 * fit.exponent_error)

    def test_a_run_of_the_folder_holds_its_resolved_scene(self):
        with StudyFolder(self.out, "sweep").run("hot_alpha0.8") as run:
            self.assertEqual(run.scene["interactions"]["alpha"], 0.8)
            self.assertGreater(run.estimate("observables/temperatures/T_mixture").n_eff, 1)
        with h5py.File(self.out / "sweep.study.h5") as f:
            self.assertEqual(f["points/hot_alpha0.8"].attrs["point"], "hot")


if __name__ == "__main__":
    unittest.main()
