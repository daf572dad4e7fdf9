#!/usr/bin/python3
"""studies/run_study.py: points x grid expand as documented, runs go to both cores, and a second
invocation of the same study recomputes nothing (resume).

Usage: /usr/bin/python3 tests/studies/test_run_study.py PATH_TO_GRAN
"""
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies"))
import run_study  # noqa: E402

GRAN = sys.argv.pop(1) if len(sys.argv) > 1 else str(ROOT / "build" / "gran")

SCENE = """
dimension: 2
species: [{name: a, count: 50}]
interactions: {alpha: 0.9}
box: {packing_fraction: 0.05}
drivers: [{type: stochastic_thermostat, strength: 0.01}]
observables: [{type: temperatures}]
run: {measurement: 20}
"""

STUDY = """
scene: scene.yaml
points:
  - {name: p1, set: {interactions.alpha: 0.8}}
  - {name: p2, set: {interactions.alpha: 0.7}}
grid: {species.0.mass: [1, 2]}
"""


class RunStudy(unittest.TestCase):
    def test_points_times_grid_expand_to_named_runs(self):
        import yaml

        runs = run_study.expand(yaml.safe_load(STUDY))
        self.assertEqual([r["name"] for r in runs], ["p1_mass1", "p1_mass2", "p2_mass1", "p2_mass2"])
        self.assertEqual(runs[3]["set"], {"interactions.alpha": 0.7, "species.0.mass": 2})

    def test_second_run_of_a_study_recomputes_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            d = Path(tmp)
            (d / "scene.yaml").write_text(SCENE)
            (d / "study.yaml").write_text(STUDY)
            cmd = ["/usr/bin/python3", str(ROOT / "studies" / "run_study.py"), str(d / "study.yaml"), "-o",
                   str(d / "out"), "-j", "2", "--gran", GRAN]
            first = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
            self.assertIn("4 run, 0 reused", first)
            second = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
            self.assertIn("0 run, 4 reused", second)
            self.assertTrue((d / "out" / "runs.csv").exists())


if __name__ == "__main__":
    unittest.main()
