"""robust_cost_bench end to end on a small mesh: the record of each preset
(warm-ups apart, every round of both tests, ratios paired per round and their
median, provenance with the timing lock), and rounds that wait for the lock
another process holds."""

import fcntl
import json
import os
import shutil
import statistics
import subprocess
import tempfile
import time
import unittest

BENCH = os.path.join(os.environ.get("TEST_SRCDIR", ""),
                     os.environ.get("TEST_WORKSPACE", ""),
                     "cc", "robust", "robust_cost_bench")

# A closed octahedron above a ground quad (shared with kdrt's and the benches' tests).
OBJ = os.path.join(os.environ.get("TEST_SRCDIR", ""), os.environ.get("TEST_WORKSPACE", ""),
                   "cc", "tools", "testdata", "octahedron.obj")


class CostBenchTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(dir=os.environ.get("TEST_TMPDIR"))
        self.dir = self.tmp.name
        self.mesh = os.path.join(self.dir, "scene.obj")
        shutil.copy(OBJ, self.mesh)
        self.lock = os.path.join(self.dir, "timing.lock")
        self.env = dict(os.environ, KDTREE_TIMING_LOCK=self.lock,
                        KDTREE_SOURCE_TREE="fixture-tree",
                        KDTREE_GIT_COMMIT="fixture-commit")

    def tearDown(self):
        self.tmp.cleanup()

    def bench(self, *args, **kwargs):
        return subprocess.Popen(
            [BENCH, "--mesh", self.mesh, "--cache_dir=", "--width", "24",
             "--height", "16"] + list(args), env=self.env, cwd=self.dir,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            universal_newlines=True, **kwargs)

    def run_bench(self, *args):
        proc = self.bench(*args)
        out, err = proc.communicate(timeout=120)
        return proc.returncode, out, err

    def records(self, path):
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]

    def test_record_per_preset_with_paired_rounds(self):
        out = os.path.join(self.dir, "cost.jsonl")
        rc, stdout, err = self.run_bench("--presets", "default,median-16-2",
                                         "--repeats", "3", "--out", out)
        self.assertEqual(rc, 0, err)
        self.assertIn("cost: paired median", stdout)
        recs = self.records(out)
        self.assertEqual([r["preset"] for r in recs],
                         ["default", "median-16-2"])
        for r in recs:
            self.assertEqual(r["scene"], "scene.obj")
            self.assertEqual(r["triangles"], 10)
            self.assertEqual(r["primary_rays"], 24 * 16)
            self.assertEqual(r["rays"], r["primary_rays"] + r["shadow_rays"])
            self.assertEqual(r["threads"], 1)
            self.assertEqual(r["repeats"], 3)
            self.assertEqual(r["timing"]["rounds"], 3)
            for mode in ("fast", "watertight"):
                lane = r[mode]
                self.assertEqual(len(lane["seconds_runs"]), 3)
                self.assertGreater(lane["warmup_seconds"], 0)
                self.assertAlmostEqual(lane["seconds"],
                                       statistics.median(lane["seconds_runs"]))
                self.assertAlmostEqual(lane["rays_per_s"],
                                       r["rays"] / lane["seconds"], places=3)
            paired = [w / f for w, f in zip(r["watertight"]["seconds_runs"],
                                            r["fast"]["seconds_runs"])]
            self.assertEqual(len(r["paired_ratio_runs"]), 3)
            for got, want in zip(r["paired_ratio_runs"], paired):
                self.assertAlmostEqual(got, want)
            self.assertAlmostEqual(r["paired_ratio"], statistics.median(paired))
            self.assertAlmostEqual(r["paired_ratio_min"], min(paired))
            self.assertAlmostEqual(r["paired_ratio_max"], max(paired))
            self.assertGreaterEqual(r["mismatches_between_modes"], 0)
            prov = r["provenance"]
            self.assertEqual(prov["source_tree"], "fixture-tree")
            self.assertEqual(prov["commit"], "fixture-commit")
            self.assertEqual(prov["timing_lock"], self.lock)
            self.assertEqual(prov["timed_beside"], 0)
            for key in ("compilation_mode", "timing_build", "cpu_model",
                        "cores", "compiler"):
                self.assertIn(key, prov)

    def test_records_to_stdout_table_to_stderr(self):
        rc, stdout, err = self.run_bench("--presets", "default",
                                         "--repeats", "1")
        self.assertEqual(rc, 0, err)
        lines = stdout.splitlines()
        self.assertEqual(len(lines), 1)
        rec = json.loads(lines[0])
        self.assertEqual(len(rec["paired_ratio_runs"]), 1)
        self.assertIn("cost: paired median", err)

    def test_rounds_wait_for_the_timing_lock(self):
        out = os.path.join(self.dir, "cost.jsonl")
        with open(self.lock, "w") as held:
            fcntl.flock(held, fcntl.LOCK_EX)
            proc = self.bench("--presets", "default", "--repeats", "2",
                              "--out", out)
            time.sleep(1.0)
            self.assertIsNone(proc.poll(), "the rounds ran beside a held lock")
            fcntl.flock(held, fcntl.LOCK_UN)
        _, err = proc.communicate(timeout=120)
        self.assertEqual(proc.returncode, 0, err)
        (rec,) = self.records(out)  # it waited, then ran
        self.assertEqual(rec["provenance"]["timed_beside"], 0)

    def test_lists_presets_and_refuses_unknown_ones(self):
        rc, stdout, _ = self.run_bench("--list_presets")
        self.assertEqual(rc, 0)
        presets = stdout.strip().split(",")
        self.assertEqual(presets[0], "default")
        self.assertIn("clipping-pruning", presets)
        self.assertIn("sah-packet", presets)
        rc, _, err = self.run_bench("--presets", "bogus", "--out",
                                    os.path.join(self.dir, "x.jsonl"))
        self.assertNotEqual(rc, 0)
        self.assertIn("bogus", err)


if __name__ == "__main__":
    unittest.main()
