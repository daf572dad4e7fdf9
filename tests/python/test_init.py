#!/usr/bin/python3
"""gran (the package's front door): gran.open picks the reader a file needs.

Run: PYTHONPATH=python /usr/bin/python3 tests/python/test_init.py (make test does).
"""
import unittest

import fixtures
import gran


class OpenTest(fixtures.TempDirTest):
    def test_a_run_file_opens_as_a_run(self):
        with gran.open(fixtures.write_run(self.dir / "run.h5")) as run:
            self.assertIsInstance(run, gran.Run)
            self.assertEqual(run.estimate("observables/temperatures/T_mixture").value, 1.25)

    def test_a_merged_study_opens_as_a_study_and_its_table_as_a_table(self):
        with gran.open(fixtures.write_study(self.dir / "sweep.study.h5")) as study:
            self.assertIsInstance(study, gran.Study)
            self.assertEqual(study.table.points(), ["cold", "hot"])
        csv = self.dir / "sweep.study.csv"
        csv.write_text("run,point,x\nhot_x1,hot,1\n")
        table = gran.open(csv)
        self.assertIsInstance(table, gran.StudyTable)
        self.assertEqual(table.points(), ["hot"])

    def test_anything_else_is_not_a_result(self):
        with self.assertRaisesRegex(gran.NotAResult, "no such file"):
            gran.open(self.dir / "absent.study.h5")
        with self.assertRaisesRegex(gran.NotAResult, "no such file"):
            gran.open(self.dir / "absent.study.csv")
        notes = self.dir / "notes.study.h5"
        notes.write_text("text")
        with self.assertRaisesRegex(gran.NotAResult, "not an HDF5 file"):
            gran.open(notes)


class DocumentationTest(unittest.TestCase):
    def test_every_public_name_and_method_has_a_docstring(self):
        import inspect
        missing = []
        for name in gran.__all__ + ["open", "native"]:
            obj = getattr(gran, name)
            if not obj.__doc__:
                missing.append(name)
            if inspect.isclass(obj):
                for member, value in vars(obj).items():
                    if member.startswith("_"):
                        continue
                    doc = value.fget.__doc__ if isinstance(value, property) else \
                        getattr(value, "__doc__", None)
                    if callable(value) or isinstance(value, property):
                        if not doc:
                            missing.append(f"{name}.{member}")
        self.assertEqual(missing, [])


if __name__ == "__main__":
    unittest.main()
