#!/usr/bin/python3
"""gran.Scene (python/gran/scene.py): scenes from files, dicts and YAML, changed key by key and
validated by gran's own loader, with errors that name the file, line, column and key.

Run: make test (CTest runs it with pytest), or by hand from the repository:
PYTHONPATH=python /usr/bin/python3 -m pytest tests/python/test_scene.py
"""
import unittest
from pathlib import Path

import fixtures
import gran

DEMO = Path(__file__).resolve().parents[2] / "studies" / "demo" / "vibrated-mixture-2d.yaml"
SMALL = {
    "title": "heated mixture from a dict",
    "dimension": 2,
    "particles": 40,
    "species": [{"name": "heavy", "mass": 3, "number_fraction": 0.5},
                {"name": "light", "mass": 1, "number_fraction": 0.5}],
    "box": {"packing_fraction": 0.05},
    "interactions": {"law": "constant_restitution", "alpha": 0.9},
    "drivers": [{"type": "stochastic_thermostat", "strength": 0.02}],
    "observables": [{"type": "temperatures"}],
    "run": {"equilibration": 10, "measurement": 50, "sample_interval": 1},
}


class SceneTest(fixtures.TempDirTest):
    def test_a_scene_file_loads_with_its_facts(self):
        facts = gran.Scene.load(DEMO).check()
        self.assertEqual((facts["dimension"], facts["particles"], facts["species"]), (2, 500, 2))
        self.assertAlmostEqual(facts["packing_fraction"], 0.015, places=12)
        self.assertEqual(facts["engine"], "event_driven")

    def test_set_changes_the_resolved_scene_and_chains(self):
        scene = gran.Scene.load(DEMO).set("species.0.mass", 5).set("run.measurement", 100)
        resolved = scene.resolved
        self.assertEqual(resolved["species"][0]["mass"], 5)
        self.assertEqual(resolved["run"]["measurement"], 100)
        self.assertEqual(scene.overrides, ["species.0.mass=5", "run.measurement=100"])
        scene.set("species.0.mass", 7)  # a key set again replaces its assignment
        self.assertEqual(scene.overrides, ["run.measurement=100", "species.0.mass=7"])
        self.assertEqual(scene.resolved["species"][0]["mass"], 7)

    def test_a_refused_value_names_the_key_and_leaves_the_scene_unchanged(self):
        scene = gran.Scene.load(DEMO)
        with self.assertRaises(gran.SceneError) as caught:
            scene.set("species.0.mass", -1)
        e = caught.exception
        self.assertEqual(e.file, "--set species.0.mass=-1")
        self.assertEqual(e.key, "species[0].mass")
        self.assertIn("expected", e.reason)
        self.assertEqual(scene.overrides, [])
        self.assertEqual(scene.resolved["species"][0]["mass"], 3)

    def test_an_error_in_a_dict_names_its_line_in_the_dicts_yaml(self):
        bad = dict(SMALL, interactions={"law": "constant_restitution", "alpha": 1.5})
        with self.assertRaises(gran.SceneError) as caught:
            gran.Scene.from_dict(bad, name="mine")
        e = caught.exception
        self.assertEqual(e.file, "mine")
        self.assertEqual(e.key, "interactions.alpha")
        line = gran.Scene(__import__("yaml").safe_dump(bad, sort_keys=False)).text.splitlines()
        self.assertIn("alpha: 1.5", line[e.line - 1])
        self.assertTrue(str(e).startswith(f"mine:{e.line}:{e.column}: interactions.alpha: "))

    def test_an_unknown_key_in_a_file_names_file_line_and_column(self):
        path = self.dir / "typo.yaml"
        path.write_text(DEMO.read_text().replace("seed: 2026", "sead: 2026"))
        with self.assertRaises(gran.SceneError) as caught:
            gran.Scene.load(path)
        e = caught.exception
        self.assertEqual((e.file, e.key), (str(path), "sead"))
        self.assertEqual(path.read_text().splitlines()[e.line - 1], "sead: 2026")
        self.assertIn("unknown key", e.reason)

    def test_a_missing_file_or_a_directory_is_a_scene_error(self):
        with self.assertRaisesRegex(gran.SceneError, "cannot read the scene file"):
            gran.Scene.load(self.dir / "absent.yaml")
        with self.assertRaisesRegex(gran.SceneError, "is a directory"):
            gran.Scene.load(self.dir)

    def test_check_refuses_a_scene_whose_particles_cannot_be_placed(self):
        # Packing fraction 0.64: valid (below the densest 0.9069) but beyond random placement.
        scene = gran.Scene.from_dict(dict(SMALL, box={"lengths": [7, 7]}))
        with self.assertRaises(gran.SceneError) as caught:
            scene.check()
        self.assertEqual(caught.exception.key, "box")
        self.assertIn("random placement failed", caught.exception.reason)

    def test_the_resolved_yaml_loads_as_the_same_scene(self):
        scene = gran.Scene.from_dict(SMALL)
        again = gran.Scene.from_yaml(scene.to_yaml())
        self.assertEqual(again.resolved, scene.resolved)


if __name__ == "__main__":
    unittest.main()
