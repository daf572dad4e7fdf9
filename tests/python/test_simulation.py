#!/usr/bin/python3
"""gran.run, gran.Simulation, gran.study (python/gran/simulation.py, over the compiled module):
the numbers are bit for bit those of `gran run`; stepwise advances, NumPy views, observables
read mid-run, callbacks, Ctrl-C, errors.

Run: make test (CTest runs it with pytest and sets GRAN_BINARY and GRAN_BUILD_DIR), or by hand:
PYTHONPATH=python GRAN_BINARY=build/gran /usr/bin/python3 -m pytest tests/python/test_simulation.py
"""
import os
import signal
import subprocess
import sys
import time
import unittest
from pathlib import Path

import fixtures
import gran
import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
GRAN = os.environ.get("GRAN_BINARY", str(ROOT / "build" / "gran"))
DEMO = ROOT / "studies" / "demo" / "vibrated-mixture-2d.yaml"
BED = ROOT / "studies" / "bhateja-2016" / "canonical-2d.yaml"
# Short versions of the two engines' scenes (a few seconds each).
DEMO_SHORT = ["run.equilibration=20", "run.measurement=400", "output.frames=4"]
BED_SHORT = ["run.equilibration=5", "run.measurement=20", "output.frames=3"]


def datasets(path):
    """Every dataset and attribute under /observables, /drivers and /particles, by path."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
            for a, v in obj.attrs.items():
                out[f"{name}@{a}"] = v
        for top in ("observables", "drivers", "particles"):
            if top in f:
                f[top].visititems(lambda n, o, top=top: visit(f"{top}/{n}", o))
    return out


def assert_identical(test, a, b):
    da, db = datasets(a), datasets(b)
    test.assertEqual(sorted(da), sorted(db))
    for key in da:
        va, vb = np.asarray(da[key]), np.asarray(db[key])
        if va.dtype == object:  # variable-length strings
            test.assertEqual(va.tolist(), vb.tolist(), key)
        else:
            test.assertEqual((va.dtype, va.tobytes()), (vb.dtype, vb.tobytes()), key)


def cli_run(scene, overrides, output):
    cmd = [GRAN, "run", str(scene), "-o", str(output), "--quiet"]
    for o in overrides:
        cmd += ["--set", o]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


class RunTest(fixtures.TempDirTest):
    def test_event_driven_run_is_bit_identical_to_the_command_line(self):
        cli_run(DEMO, DEMO_SHORT, self.dir / "cli.h5")
        result = gran.run(gran.Scene.load(DEMO, DEMO_SHORT), output=self.dir / "py.h5")
        self.assertEqual(result.status, "completed")
        assert_identical(self, self.dir / "cli.h5", result.path)

    def test_dem_run_is_bit_identical_to_the_command_line(self):
        cli_run(BED, BED_SHORT, self.dir / "cli.h5")
        result = gran.run(gran.Scene.load(BED, BED_SHORT), output=self.dir / "py.h5")
        assert_identical(self, self.dir / "cli.h5", result.path)

    def test_summary_gamma_is_the_headline_the_command_line_prints(self):
        out = subprocess.run([GRAN, "run", str(DEMO), "-o", str(self.dir / "cli.h5"), "--quiet"]
                             + sum((["--set", o] for o in DEMO_SHORT), []),
                             check=True, capture_output=True, text=True).stdout
        result = gran.run(gran.Scene.load(DEMO, DEMO_SHORT), output=self.dir / "py.h5")
        gamma = result.summary["gamma"]
        self.assertIsInstance(gamma, gran.Estimate)
        self.assertIn(f"gamma = {gamma.value:.4f} +- {gamma.error:.4f}", out)
        middle = result.summary["observables.profiles.middle/ratios/light_over_heavy/gamma"]
        self.assertEqual(gamma.value, middle.value)
        whole = result.summary["gamma_whole_system"]
        self.assertEqual(whole.value,
                         result.estimate("observables/temperatures/ratios/light_over_heavy/gamma")
                         .value)
        with self.assertRaisesRegex(KeyError, "headline: gamma, gamma_whole_system"):
            result.summary["no_such_thing"]

    def test_callback_sees_every_nth_sample_and_its_exception_stops_the_run(self):
        seen = []
        gran.run(gran.Scene.load(DEMO, DEMO_SHORT), output=self.dir / "a.h5",
                 callback=lambda n, t: seen.append((n, t)), every=50)
        self.assertEqual([n for n, _ in seen], [50, 100, 150, 200])
        self.assertTrue(all(t2 > t1 for (_, t1), (_, t2) in zip(seen, seen[1:])))

        def stop(n, t):
            raise ValueError(f"enough at {n}")
        with self.assertRaisesRegex(ValueError, "enough at 10") as caught:
            gran.run(gran.Scene.load(DEMO, DEMO_SHORT), output=self.dir / "b.h5", callback=stop,
                     every=10)
        self.assertEqual(caught.exception.result.status, "interrupted")
        self.assertEqual(caught.exception.result.path, str(self.dir / "b.h5"))
        summary = (self.dir / "b.summary.yaml").read_text()
        self.assertIn("status: interrupted", summary)

        def ctrl_c(n, t):
            raise KeyboardInterrupt
        with self.assertRaises(gran.Interrupted) as caught:
            gran.run(gran.Scene.load(DEMO, DEMO_SHORT), output=self.dir / "c.h5", callback=ctrl_c)
        self.assertEqual(caught.exception.result.status, "interrupted")

    def test_log_lines_go_to_stderr_never_to_stdout(self):
        # A run stopped by its callback logs a warning (and where its data went).
        script = ("import gran\n"
                  "def stop(n, t):\n"
                  "    raise ValueError('stop')\n"
                  "try:\n"
                  f"    gran.run(gran.Scene.load({str(DEMO)!r}, {DEMO_SHORT!r}), "
                  f"output={str(self.dir / 'log.h5')!r}, callback=stop)\n"
                  "except ValueError:\n"
                  "    pass\n")
        env = dict(os.environ, PYTHONPATH=str(ROOT / "python"))
        done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                              text=True, check=True)
        self.assertEqual(done.stdout, "")
        self.assertIn("[warning] interrupted", done.stderr)

    def test_an_output_that_cannot_be_written_is_refused_before_running(self):
        with self.assertRaisesRegex(OSError, "ending in .h5"):
            gran.run(gran.Scene.load(DEMO), output=DEMO)
        (self.dir / "taken.h5").mkdir()
        with self.assertRaisesRegex(OSError, "directory"):
            gran.run(gran.Scene.load(DEMO), output=self.dir / "taken.h5")

    def test_ctrl_c_writes_the_data_and_raises_interrupted(self):
        script = (
            "import gran, sys\n"
            "try:\n"
            f"    gran.run(gran.Scene.load({str(DEMO)!r}).set('run.measurement', 1e7),\n"
            f"             output={str(self.dir / 'long.h5')!r})\n"
            "except gran.Interrupted as e:\n"
            "    print('interrupted', e.result.status, e.result.path)\n"
            "    sys.exit(3)\n")
        env = dict(os.environ, PYTHONPATH=str(ROOT / "python"))
        proc = subprocess.Popen([sys.executable, "-c", script], env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        time.sleep(4)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
        self.assertEqual(proc.returncode, 3, err)
        self.assertIn(f"interrupted interrupted {self.dir / 'long.h5'}", out)
        with gran.open(self.dir / "long.h5") as run:
            self.assertEqual(run.performance["completed"], 0)


class SimulationTest(fixtures.TempDirTest):
    def test_arrays_have_the_shapes_and_species_of_the_scene(self):
        sim = gran.Simulation(gran.Scene.load(DEMO))
        self.assertEqual(sim.positions.shape, (500, 2))
        self.assertEqual(sim.velocities.shape, (500, 2))
        self.assertEqual(np.bincount(sim.species).tolist(), [250, 250])
        self.assertEqual(sim.angular_velocities.shape, (500, 0))
        self.assertEqual(sim.time, 0.0)

    def test_advance_reaches_the_time_and_the_collision_count_asked_for(self):
        sim = gran.Simulation(gran.Scene.load(DEMO))
        sim.advance(time=2.5)
        self.assertEqual(sim.time, 2.5)
        before = sim.collisions
        sim.advance(collisions=1000)
        self.assertEqual(sim.collisions, before + 1000)
        work = sim.work
        sim.advance(events=500)
        self.assertEqual(sim.work, work + 500)
        with self.assertRaisesRegex(ValueError, "counts events, not steps"):
            sim.advance(steps=10)
        with self.assertRaisesRegex(ValueError, "give time"):
            sim.advance()

    def test_stepwise_frames_are_the_command_lines_bit_for_bit(self):
        # The command line's frames are taken at measurement samples (time units); advancing the
        # stepwise simulation to the same times gives the same particles.
        overrides = ["run.unit=time", "run.equilibration=0", "run.measurement=4",
                     "run.sample_interval=1", "output.frames=4"]
        cli_run(DEMO, overrides, self.dir / "cli.h5")
        with gran.open(self.dir / "cli.h5") as run:
            times = [run.frame_time(k) for k in range(4)]
            cli = [run.positions(k) for k in range(4)]
        sim = gran.Simulation(gran.Scene.load(DEMO, overrides))
        for t, r in zip(times, cli):
            sim.advance(time=t)
            np.testing.assert_array_equal(sim.positions, r)

    def test_observables_are_read_mid_run(self):
        sim = gran.Simulation(gran.Scene.load(DEMO))
        for k in range(1, 21):
            sim.advance(time=0.5 * k)
            sim.sample()
        with sim.results() as run:
            t = run.estimate("observables/temperatures/T_mixture")
            self.assertEqual(t.samples, 20)
            self.assertTrue(0 < t.value < 10)
            series = run.series("observables/temperatures/series/T_mixture")
            self.assertEqual(len(series.value), 20)
            np.testing.assert_array_equal(series.x, 0.5 * np.arange(1, 21))
            steps = run.series_steps("observables/temperatures/series/T_mixture")
            self.assertTrue(np.all(np.diff(steps) > 0))

    def test_a_scene_error_comes_before_any_simulation(self):
        with self.assertRaises(gran.SceneError):
            gran.Simulation(gran.Scene.load(DEMO).set("box.packing_fraction", 0.95))


class StudyAndVersionTest(fixtures.TempDirTest):
    def test_a_study_runs_and_returns_its_table(self):
        study = self.dir / "sweep.yaml"
        study.write_text(f"scene: {DEMO}\n"
                         "points:\n  - {name: a, set: {run.measurement: 100}}\n"
                         "  - {name: b, set: {run.measurement: 100, interactions.alpha: 0.9}}\n")
        with gran.study(study, output=self.dir / "out", jobs=2) as merged:
            self.assertEqual(merged.table.points(), ["a", "b"])

    def test_version_is_the_command_lines(self):
        out = subprocess.run([GRAN, "--version"], check=True, capture_output=True,
                             text=True).stdout
        v = gran.version()
        self.assertIn(v["commit"], out)
        self.assertIn(v["build_type"], out)


if __name__ == "__main__":
    unittest.main()
