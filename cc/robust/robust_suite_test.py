"""robust_suite.py on stand-in binaries: shell scripts that print ROBUST_JSON
lines (made-up numbers, for this test only) and exit 0 or 1."""

import json
import os
import stat
import tempfile
import unittest

from cc.robust import robust_suite


def write_script(path, body):
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + body)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)


def read_jsonl(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


class SuiteTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_collects_records_and_exit_status(self):
        write_script(os.path.join(self.dir, "good"),
                     "echo 'noise'\n"
                     "echo 'ROBUST_JSON {\"case\": \"a\", \"preset\": \"p\", "
                     "\"rays\": 5, \"mismatches\": 0}'\n")
        write_script(os.path.join(self.dir, "bad"),
                     "echo 'ROBUST_JSON {\"case\": \"b\", \"rays\": 3, "
                     "\"mismatches\": 1}'\nexit 1\n")
        out = os.path.join(self.dir, "res", "robust.jsonl")
        with open(os.devnull, "w") as log:
            failed = robust_suite.run_suite(
                self.dir, out, cases=[(1, "good", "g"), (2, "bad", "b")],
                log=log)
        self.assertEqual(failed, 1)
        recs = read_jsonl(out)
        self.assertEqual([r.get("case") for r in recs],
                         ["a", None, "b", None])
        self.assertEqual(recs[0]["hard_case"], 1)
        self.assertEqual(recs[0]["binary"], "good")
        self.assertEqual(recs[0]["rays"], 5)
        self.assertEqual(recs[1]["kind"], "binary")
        self.assertTrue(recs[1]["passed"])
        self.assertEqual(recs[1]["records"], 1)
        self.assertFalse(recs[3]["passed"])
        self.assertEqual(recs[3]["exit_code"], 1)
        self.assertFalse(os.path.exists(out + ".new"))

    def test_every_case_binary_is_in_the_runfiles(self):
        here = os.path.dirname(os.path.abspath(robust_suite.__file__))
        for number, binary, _ in robust_suite.CASES:
            self.assertTrue(os.access(os.path.join(here, binary), os.X_OK),
                            "case %d: %s" % (number, binary))
        self.assertEqual([c[0] for c in robust_suite.CASES],
                         list(range(1, 10)))

    def test_cost_runs_profile_scenes_once(self):
        manifest = os.path.join(self.dir, "manifest.json")
        index = os.path.join(self.dir, "index.json")
        with open(manifest, "w") as f:
            json.dump({"scenes": [
                {"name": "s1", "profiles": ["quick"]},
                {"name": "s2", "profiles": ["full"]},
                {"name": "s3", "profiles": ["quick"]}]}, f)
        with open(index, "w") as f:
            json.dump({"scenes": {"s1": {}, "s2": {}}}, f)
        scenes = robust_suite.profile_scenes(manifest, index, "quick")
        self.assertEqual(scenes, ["s1"])
        # Stand-in bench: appends one record for its --scene (or generated).
        calls = os.path.join(self.dir, "calls")
        write_script(os.path.join(self.dir, "bench"),
                     "echo \"$@\" >> %s\n"
                     "scene=generated; out=''\n"
                     "while [ $# -gt 0 ]; do case $1 in\n"
                     "  --scene) scene=$2; shift;; --out) out=$2; shift;;\n"
                     "esac; shift; done\n"
                     "echo \"{\\\"scene\\\": \\\"$scene\\\", "
                     "\\\"preset\\\": \\\"default\\\"}\" >> $out\n" % calls)
        cost = os.path.join(self.dir, "cost.jsonl")
        bench = os.path.join(self.dir, "bench")
        with open(os.devnull, "w") as log:
            self.assertEqual(robust_suite.run_cost(bench, cost, scenes,
                                                   log=log), 0)
            self.assertEqual(robust_suite.run_cost(bench, cost, scenes,
                                                   log=log), 0)
        self.assertEqual(sorted(r["scene"] for r in read_jsonl(cost)),
                         ["generated", "s1"])
        with open(calls) as f:
            lines = f.read().splitlines()
        self.assertEqual(len(lines), 2)
        self.assertIn("--scene s1 --presets default", lines[0])


if __name__ == "__main__":
    unittest.main()
