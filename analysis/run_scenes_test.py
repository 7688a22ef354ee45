"""Tests of experiments/run_scenes.py (the runner that feeds table1), with a fake
scene_info written to a temp dir. Lives here because experiments/ holds only
runners; the fake binary never touches real results."""

import io
import json
import os
import stat
import tempfile
import unittest
from unittest import mock
from contextlib import redirect_stdout, redirect_stderr

from experiments import run_scenes

FAKE_SCENE_INFO = """#!/usr/bin/python3
import argparse, json, os, sys
p = argparse.ArgumentParser()
p.add_argument("--mesh"); p.add_argument("--name"); p.add_argument("--cache_dir")
a = p.parse_args()
with open(os.path.join(os.path.dirname(sys.argv[0]), "calls.log"), "a") as f:
    f.write(a.name + "\\n")
if "bad" in a.name:
    print("scene_info: cannot read " + a.mesh, file=sys.stderr)
    sys.exit(1)
n = sum(1 for line in open(a.mesh) if line.startswith("f "))
print("loading...")
print(json.dumps({"scene": a.name, "mesh": a.mesh, "n_tri": n,
                  "skipped_faces": 0, "dropped_degenerate": 0,
                  "dropped_nonfinite": 0, "load_s": 0.001,
                  "from_cache": False, "bounds": [[0, 0, 0], [1, 1, 1]]}))
"""


class ScenesRunnerTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = self.tmp.name
        self.bin = os.path.join(d, "scene_info")
        with open(self.bin, "w") as f:
            f.write(FAKE_SCENE_INFO)
        os.chmod(self.bin, os.stat(self.bin).st_mode | stat.S_IXUSR)
        os.makedirs(os.path.join(d, "scenes"))
        for name, n in (("a", 3), ("b", 5), ("bad", 1), ("c", 2)):
            self.mesh(name, n)
        self.manifest = os.path.join(d, "manifest.json")
        with open(self.manifest, "w") as f:
            json.dump({"scenes": [
                {"name": "a", "profiles": ["test", "quick"]},
                {"name": "b", "profiles": ["quick"]},
                {"name": "bad", "profiles": ["quick"]},
                {"name": "c", "profiles": ["full"]},
                {"name": "missing", "profiles": ["quick"]},
            ]}, f)
        self.index = os.path.join(d, "scenes", "index.json")
        # mixed: absolute path, path relative to the index's directory
        self.write_index({"a": os.path.join(d, "scenes", "a.obj"),
                          "b": "b.obj", "bad": "bad.obj", "c": "c.obj",
                          "stray": "a.obj"})
        self.out = os.path.join(d, "out")

    def tearDown(self):
        self.tmp.cleanup()

    def mesh(self, name, n):
        with open(os.path.join(self.tmp.name, "scenes", name + ".obj"),
                  "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * n)

    def write_index(self, data):
        with open(self.index, "w") as f:
            json.dump(data, f)

    def run_profile(self, profile="quick", **kw):
        with redirect_stdout(io.StringIO()), redirect_stderr(io.StringIO()):
            return run_scenes.run(profile, self.out, manifest=self.manifest,
                              index=self.index, scene_info=self.bin,
                              soup_cache=os.path.join(self.tmp.name, "soups"),
                              progress=False, **kw)

    def records(self):
        path = os.path.join(self.out, "results", "scenes.jsonl")
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]

    def calls(self):
        with open(os.path.join(self.tmp.name, "calls.log")) as f:
            return f.read().split()

    def test_profile_selection_and_records(self):
        self.assertEqual(self.run_profile(), (3, 0, 1))
        recs = self.records()
        self.assertEqual([r["scene"] for r in recs], ["a", "b", "bad"])
        a, b, bad = recs
        self.assertTrue(a["ok"])
        self.assertEqual(a["n_tri"], 3)
        self.assertEqual(b["n_tri"], 5)
        self.assertEqual(b["mesh"], os.path.join(self.tmp.name, "scenes",
                                                 "b.obj"))
        self.assertEqual(b["mesh_bytes"], os.path.getsize(b["mesh"]))
        self.assertEqual(b["profile"], "quick")
        self.assertFalse(bad["ok"])
        self.assertEqual(bad["returncode"], 1)
        self.assertIn("cannot read", bad["error"])

    def test_machine_recorded(self):
        self.run_profile()
        with open(os.path.join(self.out, "results", "machine.json")) as f:
            machine = json.load(f)
        for key in ("cpu_model", "cpu_id", "cpu_caches", "compiler", "git_commit", "cpu_count",
                    "recorded_at", "scene_info_sha256"):
            self.assertIn(key, machine)
        self.assertEqual(machine["profile"], "quick")
        self.run_profile()
        with open(os.path.join(self.out, "results", "machines.jsonl")) as f:
            self.assertEqual(len(f.read().splitlines()), 2)

    def test_machine_names_the_code_as_the_records_do(self):
        # provenance.code_identity: a pinned identity (as SLURM tasks have)
        # is the one machine.json names.
        pin = "%s true %s" % ("c" * 40, "d" * 40)
        with mock.patch.dict(os.environ, {"KDTREE_SOURCE_ID": pin}):
            for override in ("KDTREE_GIT_COMMIT", "KDTREE_SOURCE_TREE"):
                os.environ.pop(override, None)
            self.run_profile()
        with open(os.path.join(self.out, "results", "machine.json")) as f:
            machine = json.load(f)
        self.assertEqual(machine["git_commit"], "c" * 40)
        self.assertTrue(machine["git_dirty"])
        self.assertEqual(machine["source_tree"], "d" * 40)

    def test_resume_skips_done_retries_failed(self):
        self.run_profile()
        self.assertEqual(self.run_profile(), (1, 2, 1))
        self.assertEqual(self.calls(), ["a", "b", "bad", "bad"])
        # raw file only grows
        self.assertEqual([r["scene"] for r in self.records()],
                         ["a", "b", "bad", "bad"])

    def test_changed_mesh_is_measured_again(self):
        self.run_profile()
        self.mesh("b", 7)  # different size
        self.run_profile()
        recs = [r for r in self.records() if r["scene"] == "b"]
        self.assertEqual([r["n_tri"] for r in recs], [5, 7])

    def test_force(self):
        self.run_profile()
        self.assertEqual(self.run_profile(force=True), (3, 0, 1))

    def test_list_index_shape(self):
        d = self.tmp.name
        self.write_index([{"name": "a", "path": os.path.join(d, "scenes",
                                                             "a.obj")}])
        self.assertEqual(self.run_profile(), (1, 0, 0))

    def test_missing_index_or_binary(self):
        os.unlink(self.index)
        with self.assertRaises(run_scenes.SetupError):
            self.run_profile()
        with self.assertRaises(run_scenes.SetupError):
            run_scenes.run("quick", self.out, manifest=self.manifest,
                       index=self.index, scene_info="/nonexistent/scene_info",
                       progress=False)

    def test_no_manifest_takes_whole_index(self):
        os.unlink(self.manifest)
        self.assertEqual(self.run_profile(), (5, 0, 1))

    def test_main_exit_codes(self):
        with redirect_stdout(io.StringIO()), redirect_stderr(io.StringIO()):
            ok = run_scenes.main(["--profile", "test", "--out", self.out,
                              "--manifest", self.manifest,
                              "--index", self.index,
                              "--scene_info", self.bin, "--no_progress",
                              "--cache_dir",
                              os.path.join(self.tmp.name, "soups")])
            missing = run_scenes.main(["--profile", "test", "--out", self.out,
                                   "--index", self.index + ".nope",
                                   "--scene_info", self.bin])
        self.assertEqual((ok, missing), (0, 2))

    def test_last_json_line(self):
        self.assertEqual(run_scenes.last_json_line('x\n{"a": 1}\n{bad\n'),
                         {"a": 1})
        self.assertIsNone(run_scenes.last_json_line("nothing"))


if __name__ == "__main__":
    unittest.main()
