"""run_matrix.py and compare_results.py with a fake kdrt (a script that
writes a record the way kdrt does), locally and in SLURM task mode."""

import io
import json
import os
import stat
import sys
import tempfile
import unittest
from contextlib import redirect_stderr
from unittest import mock

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import run_accuracy  # noqa: E402
import compare_results  # noqa: E402
import run_matrix  # noqa: E402

# Prints its record on stdout and writes its image to --image, as kdrt does.
FAKE_KDRT = """#!/usr/bin/python3
import json, os, sys, time
args = dict(zip(sys.argv[1::2], sys.argv[2::2]))
if args["--scene"] == "broken":
    print("kdrt: cannot load scene", file=sys.stderr)
    sys.exit(1)
rec = {"scene": args["--scene"], "preset": args["--preset"],
       "T_B": time.time() % 1, "T_R": 0.5, "N_IT": 3.0,
       "tree": {"N_I": len(args["--preset"]), "N_L": 7}, "P_hit": 10,
       "provenance": {"source_tree": os.environ.get("KDTREE_SOURCE_TREE"),
                      "timing_build": True}}
print(json.dumps(rec))
if "--image" in args:
    os.makedirs(os.path.dirname(args["--image"]), exist_ok=True)
    open(args["--image"], "w").write("png")
"""


class RunMatrixTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        d = self.tmp.name
        self.kdrt = os.path.join(d, "kdrt")
        with open(self.kdrt, "w") as f:
            f.write(FAKE_KDRT)
        os.chmod(self.kdrt, os.stat(self.kdrt).st_mode | stat.S_IEXEC)
        self.manifest = os.path.join(d, "manifest.json")
        with open(self.manifest, "w") as f:
            json.dump({"scenes": [
                {"name": "a", "profiles": ["test"]},
                {"name": "broken", "profiles": ["test"]},
                {"name": "b", "profiles": ["quick"]}]}, f)
        self.index = os.path.join(d, "index.json")
        with open(self.index, "w") as f:
            json.dump({"a": os.path.join(d, "a.obj"),
                       "broken": os.path.join(d, "x.obj"),
                       "b": os.path.join(d, "b.obj")}, f)

    def tearDown(self):
        self.tmp.cleanup()

    def run_matrix(self, out, *extra):
        return run_matrix.main([
            "--profile", "test", "--kdrt", self.kdrt, "--out", out,
            "--manifest", self.manifest, "--index", self.index,
            "--variants", "median-16-2,clipping"] + list(extra))

    def records(self, out):
        with open(os.path.join(out, "results", "kdtree.jsonl")) as f:
            return [json.loads(line) for line in f]

    def test_runs_the_profile_records_failures_and_resumes(self):
        out = os.path.join(self.tmp.name, "out")
        self.assertEqual(self.run_matrix(out), 0)
        recs = self.records(out)
        self.assertEqual([(r["scene"], r["preset"], r["ok"]) for r in recs], [
            ("a", "median-16-2", True), ("a", "clipping", True),
            ("broken", "median-16-2", False), ("broken", "clipping", False)])
        self.assertIn("cannot load scene", recs[2]["error"])
        self.assertEqual(recs[0]["profile"], "test")
        self.assertEqual(recs[0]["backend"], "local")
        self.assertTrue(os.path.exists(
            os.path.join(out, "images", "a_clipping.png")))
        # Resumed: only the failed jobs run again.
        self.assertEqual(self.run_matrix(out), 0)
        self.assertEqual(len(self.records(out)), 6)

    def test_resumes_past_a_record_cut_short(self):
        """A run killed (or out of disk) while appending leaves its last line
        cut short: the next run warns, naming the file and line, and runs
        that job again."""
        out = os.path.join(self.tmp.name, "out")
        self.assertEqual(self.run_matrix(out, "--scenes", "a"), 0)
        path = os.path.join(out, "results", "kdtree.jsonl")
        with open(path) as f:
            lines = f.read().splitlines()
        with open(path, "w") as f:
            f.write(lines[0] + "\n" + lines[1][:40])
        err = io.StringIO()
        with redirect_stderr(err):
            self.assertEqual(self.run_matrix(out, "--scenes", "a"), 0)
        self.assertIn("kdtree.jsonl:2 is not a JSON record", err.getvalue())
        with open(path) as f:
            tail = [json.loads(line) for line in f.read().splitlines()[2:]]
        self.assertEqual([(r["scene"], r["preset"]) for r in tail], [("a", "clipping")])

    def test_a_new_source_tree_reruns_every_job(self):
        """Nothing is edited: only the provenance the records carry changes
        (as an edit to the sources would change it), and every job of the
        old code runs again."""
        out = os.path.join(self.tmp.name, "out")
        old, new = "a" * 40, "b" * 40
        with mock.patch.dict(os.environ, {"KDTREE_SOURCE_TREE": old}):
            self.assertEqual(self.run_matrix(out), 0)
            self.assertEqual(self.run_matrix(out), 0)  # only failures rerun
        self.assertEqual(len(self.records(out)), 6)
        with mock.patch.dict(os.environ, {"KDTREE_SOURCE_TREE": new}):
            self.assertEqual(self.run_matrix(out), 0)
        rerun = self.records(out)[6:]
        self.assertEqual([(r["scene"], r["preset"], r["ok"]) for r in rerun], [
            ("a", "median-16-2", True), ("a", "clipping", True),
            ("broken", "median-16-2", False), ("broken", "clipping", False)])
        self.assertEqual({r["job"][-1] for r in rerun}, {new})
        self.assertEqual(rerun[0]["provenance"]["source_tree"], new)

    def test_two_jobs_at_once_record_every_job(self):
        # Records are appended as runs end, so their order depends on which of
        # two concurrent runs ends first (nothing reads that order: jobs are
        # keyed).
        out = os.path.join(self.tmp.name, "out")
        self.assertEqual(self.run_matrix(out, "--jobs", "2"), 0)
        recs = self.records(out)
        self.assertCountEqual([(r["scene"], r["preset"], r["ok"]) for r in recs], [
            ("a", "median-16-2", True), ("a", "clipping", True),
            ("broken", "median-16-2", False), ("broken", "clipping", False)])
        self.assertEqual({r["concurrent_jobs"] for r in recs}, {2})

    def test_repeat_budget_reaches_kdrt_only_when_set(self):
        s = {"repeats": 5, "threads": 1, "embree": "off"}
        self.assertNotIn("--repeat_budget_s",
                         run_matrix.kdrt_command("k", "a", "pruning", s, "o"))
        s["repeat_budget_s"] = 30
        cmd = run_matrix.kdrt_command("k", "a", "pruning", s, "o")
        self.assertEqual(cmd[cmd.index("--repeat_budget_s") + 1], "30")

    def test_fast_render_only_for_the_listed_variants(self):
        s = {"repeats": 1, "threads": 1, "embree": "off", "fast_render": ["sah-packet"]}
        self.assertIn("--fast_render", run_matrix.kdrt_command("k", "a", "sah-packet", s))
        self.assertNotIn("--fast_render", run_matrix.kdrt_command("k", "a", "pruning", s))
        self.assertIn("sah-packet", run_matrix.load_matrix()["fast_render_variants"])

    def test_cost_images_only_for_the_listed_scenes(self):
        s = {"repeats": 1, "threads": 1, "embree": "off", "source_tree": "t",
             "cost_images": ["city"]}
        self.assertTrue(run_matrix.wants_cost_image("city", s))
        self.assertFalse(run_matrix.wants_cost_image("bunny", s))
        cmd = run_matrix.kdrt_command("k", "city", "pruning", s, "i.png", "c.npy.gz")
        self.assertEqual(cmd[cmd.index("--cost_image") + 1], "c.npy.gz")
        self.assertNotIn("--cost_image", run_matrix.kdrt_command("k", "bunny", "pruning", s))
        # A run without the cost image is not the job that writes one.
        self.assertNotEqual(run_matrix.job_key("city", "pruning", s),
                            run_matrix.job_key("city", "pruning", dict(s, cost_images=[])))
        self.assertEqual(run_matrix.job_key("bunny", "pruning", s),
                         run_matrix.job_key("bunny", "pruning", dict(s, cost_images=[])))
        self.assertIn("city", run_matrix.load_matrix()["cost_image_scenes"])

    def test_triangle_bvh_only_in_the_fast_mode_with_embree_timed(self):
        s = {"repeats": 1, "threads": 1, "embree": "medium", "source_tree": "t",
             "fast_render": ["sah-packet", "sah-packet-binned"],
             "embree_timed": ["sah-packet", "sah-packet-binned"], "triangle_bvh": ["sah-packet"]}
        self.assertIn("--triangle_bvh", run_matrix.kdrt_command("k", "a", "sah-packet", s))
        self.assertNotIn("--triangle_bvh",
                         run_matrix.kdrt_command("k", "a", "sah-packet-binned", s))
        for other in (dict(s, embree="off"), dict(s, embree_timed=[]), dict(s, fast_render=[])):
            self.assertNotIn("--triangle_bvh", run_matrix.kdrt_command("k", "a", "sah-packet", other))
        # A run with more timed lanes is another job than one without.
        self.assertNotEqual(run_matrix.job_key("a", "sah-packet", s),
                            run_matrix.job_key("a", "sah-packet", dict(s, triangle_bvh=[])))
        self.assertNotEqual(run_matrix.job_key("a", "sah-packet", s),
                            run_matrix.job_key("a", "sah-packet", dict(s, fast_render=[])))
        self.assertEqual(run_matrix.load_matrix()["triangle_bvh_variants"], ["sah-packet"])

    def test_embree_timed_only_on_the_listed_variants(self):
        s = {"repeats": 1, "threads": 1, "embree": "medium",
             "embree_timed": ["clipping-pruning"], "source_tree": "t"}
        timed = run_matrix.kdrt_command("k", "a", "clipping-pruning", s)
        untimed = run_matrix.kdrt_command("k", "a", "pruning", s)
        self.assertNotIn("--noembree_rounds", timed)
        self.assertIn("--noembree_rounds", untimed)
        # Not the same job: the key says which.
        self.assertEqual(run_matrix.job_key("a", "pruning", s)[4], "medium untimed")
        self.assertEqual(run_matrix.job_key("a", "clipping-pruning", s)[4], "medium")
        s["embree"] = "off"
        self.assertNotIn("--noembree_rounds", run_matrix.kdrt_command("k", "a", "pruning", s))
        self.assertEqual(run_matrix.job_key("a", "pruning", s)[4], "off")

    def test_accuracy_step_records_knob_and_failure(self):
        out = os.path.join(self.tmp.name, "out")
        os.makedirs(out)
        step = {"knob": "bins", "step": "bins 4", "preset": "sah-binned-32",
                "options": {"bins": 4}}
        profile = {"repeats": 3, "repeat_budget_s": 20}
        rec = run_accuracy.run_one(self.kdrt, "a", step, profile, "test", out)
        self.assertTrue(rec["ok"])
        self.assertEqual((rec["scene"], rec["preset"], rec["knob"], rec["step"]),
                         ("a", "sah-binned-32", "bins", "bins 4"))
        bad = run_accuracy.run_one(self.kdrt, "broken", step, profile, "test", out)
        self.assertFalse(bad["ok"])
        self.assertIn("--repeat_budget_s", bad["command"])
        self.assertIn("cannot load scene", bad["error"])
        # Temporary kdrt directories are removed; the env files stay.
        self.assertEqual(sorted(os.listdir(out)), ["accuracy"])

    def test_accuracy_runs_the_profiles_jobs_at_once(self):
        out = os.path.join(self.tmp.name, "out")
        study = os.path.join(self.tmp.name, "accuracy.json")
        steps = [{"knob": "bins", "step": "bins %d" % n, "preset": "sah-binned-32",
                  "options": {"bins": n}} for n in (4, 8, 16)]
        with open(study, "w") as f:
            json.dump({"profiles": {"test": {"scenes": ["a"], "repeats": 1,
                                             "jobs": 2}},
                       "steps": steps}, f)
        args = ["--profile", "test", "--kdrt", self.kdrt, "--out", out,
                "--study", study, "--manifest", self.manifest,
                "--index", self.index]
        self.assertEqual(run_accuracy.main(args), 0)
        with open(os.path.join(out, "results", "accuracy.jsonl")) as f:
            recs = [json.loads(line) for line in f]
        self.assertEqual(sorted(r["step"] for r in recs), ["bins 16", "bins 4", "bins 8"])
        self.assertEqual({r["concurrent_jobs"] for r in recs}, {2})
        self.assertEqual(run_accuracy.main(args), 0)  # all done: nothing reruns
        with open(os.path.join(out, "results", "accuracy.jsonl")) as f:
            self.assertEqual(len(f.readlines()), 3)

    def test_reads_the_index_shape_fetch_py_writes(self):
        with open(self.index, "w") as f:
            json.dump({"scenes": {"a": {"file": "data/cache/scenes/a.obj",
                                        "triangles": 3}}}, f)
        import run_scenes
        index = run_scenes.load_index(self.index)
        self.assertEqual(list(index), ["a"])
        self.assertTrue(index["a"].endswith("data/cache/scenes/a.obj"))

    def test_task_mode_writes_a_part_per_index(self):
        out = os.path.join(self.tmp.name, "out")
        os.makedirs(out)
        jobs = os.path.join(self.tmp.name, "jobs.json")
        with open(jobs, "w") as f:
            json.dump({"profile": "test",
                       "settings": {"repeats": 1, "threads": 1, "embree": "off"},
                       "jobs": [{"scene": "a", "variant": "pruning"}]}, f)
        self.assertEqual(run_matrix.main(["--task", jobs, "--task_index", "0",
                                          "--kdrt", self.kdrt, "--out", out]), 0)
        with open(os.path.join(self.tmp.name, "parts", "0.json")) as f:
            rec = json.load(f)
        self.assertEqual((rec["scene"], rec["preset"], rec["ok"]),
                         ("a", "pruning", True))
        self.assertEqual(rec["job"], ["a", "pruning", 1, 1, "off", None])

    def test_compare_ignores_timings_but_not_statistics(self):
        a = os.path.join(self.tmp.name, "a")
        b = os.path.join(self.tmp.name, "b")
        self.run_matrix(a)
        self.run_matrix(b)
        diffs, common = compare_results.compare(
            os.path.join(a, "results", "kdtree.jsonl"),
            os.path.join(b, "results", "kdtree.jsonl"))
        self.assertEqual(diffs, [])  # T_B differs (time-based), ignored
        self.assertEqual(common, 2)
        path = os.path.join(b, "results", "kdtree.jsonl")
        recs = self.records(b)
        # A SLURM record (run_slurm) has its own backend and no
        # concurrent_jobs: provenance, not a statistic.
        for r in recs:
            r["backend"] = "slurm"
            del r["concurrent_jobs"]
        with open(path, "w") as f:
            for r in recs:
                f.write(json.dumps(r) + "\n")
        diffs, _ = compare_results.compare(
            os.path.join(a, "results", "kdtree.jsonl"), path)
        self.assertEqual(diffs, [])
        recs[0]["tree"]["N_I"] = 999
        with open(path, "w") as f:
            for r in recs:
                f.write(json.dumps(r) + "\n")
        diffs, _ = compare_results.compare(
            os.path.join(a, "results", "kdtree.jsonl"), path)
        self.assertEqual(len(diffs), 1)
        self.assertIn("tree.N_I", diffs[0])


if __name__ == "__main__":
    unittest.main()
