"""robust_suite.py on stand-in binaries: shell scripts that print ROBUST_JSON
lines or cost records (made-up numbers, for this test only) and exit 0 or 1.
The code identity is given, not read from git."""

import contextlib
import io
import json
import os
import stat
import tempfile
import unittest
import unittest.mock

from cc.robust import robust_cost_runs, robust_suite

TREE = "a" * 40
IDENT = {"commit": "c" * 40, "dirty": False, "source_tree": TREE}


def write_script(path, body):
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + body)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)


def read_jsonl(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


# A stand-in cost bench: appends one record per preset of --presets for its
# --scene (or the generated scene), of source tree $TREE, with $ROUNDS paired
# rounds; logs its arguments to $CALLS.
BENCH = r"""echo "$@" >> "$CALLS"
scene=generated; out=''; presets=''
while [ $# -gt 0 ]; do case $1 in
  --scene) scene=$2; shift;; --out) out=$2; shift;;
  --presets) presets=$2; shift;;
esac; shift; done
for p in $(echo "$presets" | tr ',' ' '); do
  runs=$(seq -s, 1 "$ROUNDS" | sed 's/[0-9]*/1.0/g')
  echo "{\"scene\": \"$scene\", \"preset\": \"$p\", \"paired_ratio_runs\": [$runs], \"provenance\": {\"source_tree\": \"$TREE\", \"timing_build\": true}}" >> "$out"
done
"""


class SuiteTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.log = open(os.devnull, "w")

    def tearDown(self):
        self.log.close()
        self.tmp.cleanup()

    def good_and_bad(self):
        write_script(os.path.join(self.dir, "good"),
                     "echo 'noise'\n"
                     "echo 'ROBUST_JSON {\"case\": \"a\", \"preset\": \"p\", "
                     "\"rays\": 5, \"mismatches\": 0}'\n")
        write_script(os.path.join(self.dir, "bad"),
                     "echo 'ROBUST_JSON {\"case\": \"b\", \"rays\": 3, "
                     "\"mismatches\": 1}'\nexit 1\n")

    def test_collects_records_exit_status_and_provenance(self):
        self.good_and_bad()
        out = os.path.join(self.dir, "res", "robust.jsonl")
        prov = robust_suite.suite_provenance(IDENT, "opt")
        failed = robust_suite.run_suite(
            self.dir, out, cases=[(1, "good", "g"), (2, "bad", "b")],
            log=self.log, provenance=prov, profile="quick", jobs=2)
        self.assertEqual(failed, 1)
        recs = read_jsonl(out)
        self.assertEqual([r.get("case") for r in recs],
                         ["a", None, "b", None, None])
        self.assertEqual(recs[0]["hard_case"], 1)
        self.assertEqual(recs[0]["binary"], "good")
        self.assertEqual(recs[0]["rays"], 5)
        self.assertEqual(recs[1]["kind"], "binary")
        self.assertTrue(recs[1]["passed"])
        self.assertEqual(recs[1]["records"], 1)
        self.assertFalse(recs[3]["passed"])
        self.assertEqual(recs[3]["exit_code"], 1)
        suite = recs[4]
        self.assertEqual(suite["kind"], "suite")
        self.assertEqual(suite["profile"], "quick")
        self.assertTrue(suite["complete"])
        self.assertFalse(suite["passed"])
        self.assertEqual(suite["failed"], 1)
        for rec in recs:
            self.assertEqual(rec["provenance"]["source_tree"], TREE)
            self.assertEqual(rec["provenance"]["compilation_mode"], "opt")
            for key in ("cpu_model", "cpu_id", "cpu_caches", "cores"):
                self.assertIn(key, rec["provenance"])  # as the C++ records name the CPU
        self.assertFalse(os.path.exists(out + ".new"))

    def test_suite_done_only_for_a_passing_run_of_the_same_code(self):
        self.good_and_bad()
        out = os.path.join(self.dir, "robust.jsonl")
        cases = [(1, "good", "g")]
        prov = robust_suite.suite_provenance(IDENT, "opt")
        self.assertIsNone(robust_suite.suite_done(out, TREE, "quick", cases))
        robust_suite.run_suite(self.dir, out, cases=cases, log=self.log,
                               provenance=prov, profile="quick")
        self.assertIsNotNone(robust_suite.suite_done(out, TREE, "quick",
                                                     cases))
        self.assertIsNone(robust_suite.suite_done(out, "b" * 40, "quick",
                                                  cases))
        self.assertIsNone(robust_suite.suite_done(out, TREE, "full", cases))
        self.assertIsNone(robust_suite.suite_done(out, None, "quick", cases))
        # A case missing from the file, or a failing run: not done.
        self.assertIsNone(robust_suite.suite_done(
            out, TREE, "quick", cases + [(2, "bad", "b")]))
        robust_suite.run_suite(self.dir, out,
                               cases=cases + [(2, "bad", "b")], log=self.log,
                               provenance=prov, profile="quick")
        self.assertIsNone(robust_suite.suite_done(out, TREE, "quick", cases))

    def test_the_ray_stride_reaches_the_cases_and_keys_the_run(self):
        write_script(os.path.join(self.dir, "stride"),
                     "echo \"ROBUST_JSON {\\\"stride\\\": "
                     "\"$KDTREE_ROBUST_RAY_STRIDE\"}\"\n")
        out = os.path.join(self.dir, "robust.jsonl")
        cases = [(1, "stride", "s")]
        prov = robust_suite.suite_provenance(IDENT, "opt")
        robust_suite.run_suite(self.dir, out, cases=cases, log=self.log,
                               provenance=prov, profile="quick", ray_stride=4)
        recs = read_jsonl(out)
        self.assertEqual(recs[0]["stride"], 4)
        self.assertEqual(recs[-1]["ray_stride"], 4)
        self.assertIsNotNone(robust_suite.suite_done(out, TREE, "quick", cases,
                                                     ray_stride=4))
        # Every ray was not checked: a run asking for every ray reruns it.
        self.assertIsNone(robust_suite.suite_done(out, TREE, "quick", cases))

    def test_longest_case_of_the_last_run_starts_first(self):
        started = os.path.join(self.dir, "started")
        for name in ("quick", "slow"):
            write_script(os.path.join(self.dir, name),
                         "echo %s >> %s\n" % (name, started))
        out = os.path.join(self.dir, "robust.jsonl")
        cases = [(1, "quick", "q"), (2, "slow", "s")]
        with open(out, "w") as f:
            for binary, seconds in (("quick", 1.0), ("slow", 9.0)):
                f.write(json.dumps({"kind": "binary", "binary": binary,
                                    "seconds": seconds}) + "\n")
        robust_suite.run_suite(self.dir, out, cases=cases, log=self.log,
                               jobs=1)
        with open(started) as f:
            self.assertEqual(f.read().split(), ["slow", "quick"])
        recs = read_jsonl(out)
        self.assertEqual([r.get("binary") for r in recs],
                         ["quick", "slow", None])

    def test_every_case_binary_is_in_the_runfiles(self):
        here = os.path.dirname(os.path.abspath(robust_suite.__file__))
        for number, binary, _ in robust_suite.CASES:
            self.assertTrue(os.access(os.path.join(here, binary), os.X_OK),
                            "case %d: %s" % (number, binary))
        self.assertEqual([c[0] for c in robust_suite.CASES],
                         list(range(1, 10)))

    def test_compilation_mode_from_the_output_path(self):
        guess = robust_suite.guess_compilation_mode
        self.assertEqual(guess("/x/execroot/w/bazel-out/k8-opt/bin/cc/robust"),
                         "opt")
        self.assertEqual(guess("/x/bazel-out/k8-fastbuild/bin/cc"),
                         "fastbuild")
        self.assertEqual(guess("/somewhere/else"), "unknown")

    def scenes_files(self):
        manifest = os.path.join(self.dir, "manifest.json")
        index = os.path.join(self.dir, "index.json")
        matrix = os.path.join(self.dir, "matrix.json")
        with open(manifest, "w") as f:
            json.dump({"scenes": [
                {"name": "s1", "profiles": ["quick"]},
                {"name": "s2", "profiles": ["full"]},
                {"name": "s3", "profiles": ["quick"]}]}, f)
        with open(index, "w") as f:
            json.dump({"scenes": {"s1": {}, "s2": {}}}, f)
        with open(matrix, "w") as f:
            json.dump({"variants": ["v1", "v2"], "beyond_variants": ["b1"]},
                      f)
        return manifest, index, matrix

    def bench(self, tree=TREE, rounds=3):
        calls = os.path.join(self.dir, "calls")
        os.environ.update(CALLS=calls, TREE=tree, ROUNDS=str(rounds))
        bench = os.path.join(self.dir, "bench")
        write_script(bench, BENCH)
        return bench, calls

    def calls(self):
        path = os.path.join(self.dir, "calls")
        if not os.path.exists(path):
            return []
        with open(path) as f:
            lines = f.read().splitlines()
        os.remove(path)
        return lines

    def test_cost_runs_what_this_code_has_not_run(self):
        manifest, index, matrix = self.scenes_files()
        scenes = robust_cost_runs.profile_scenes(manifest, index, "quick")
        self.assertEqual(scenes, ["s1"])
        presets = robust_cost_runs.generated_presets(matrix)
        self.assertEqual(presets, ["default", "v1", "v2", "b1"])
        cost = os.path.join(self.dir, "cost.jsonl")
        bench, _ = self.bench()

        def run(repeats=3):
            return robust_cost_runs.run_cost(bench, cost, scenes, repeats=repeats,
                                         log=self.log,
                                         presets_generated=presets,
                                         source_tree=TREE)
        self.assertEqual(run(), 0)
        calls = self.calls()
        self.assertEqual(len(calls), 2)
        self.assertIn("--scene s1 --presets default", calls[0])
        self.assertIn("--presets default,v1,v2,b1", calls[1])
        self.assertIn("--repeats 3", calls[1])
        self.assertEqual(run(), 0)
        self.assertEqual(self.calls(), [])  # all done
        # More rounds asked than recorded: rerun.
        self.assertEqual(run(repeats=5), 0)
        self.assertEqual(len(self.calls()), 2)
        # Other code: only its own records count.
        recs = read_jsonl(cost)
        with open(cost, "w") as f:
            for r in recs:
                if r["preset"] == "v2":
                    r["provenance"]["source_tree"] = "b" * 40
                if r["scene"] == "s1":
                    r["provenance"]["timing_build"] = False
                f.write(json.dumps(r) + "\n")
        self.assertEqual(run(), 0)
        calls = self.calls()
        self.assertEqual(len(calls), 2)
        self.assertIn("--scene s1 --presets default", calls[0])
        self.assertIn("--presets v2 ", calls[1])

    def test_old_unpaired_records_do_not_count(self):
        cost = os.path.join(self.dir, "cost.jsonl")
        with open(cost, "w") as f:
            f.write(json.dumps({"scene": "s1", "preset": "default",
                                "mode": "fast", "seconds": 1.0}) + "\n")
        self.assertEqual(robust_cost_runs.done_runs(cost, TREE), set())

    def test_a_record_cut_short_is_passed_over_with_a_warning(self):
        cost = os.path.join(self.dir, "cost.jsonl")
        with open(cost, "w") as f:
            f.write(json.dumps({"scene": "s1"}) + '\n{"scene": ')
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            self.assertEqual(robust_cost_runs.read_records(cost), [{"scene": "s1"}])
        self.assertIn("cost.jsonl:2 is not a JSON record", err.getvalue())

    def main(self, *args):
        manifest, index, matrix = self.scenes_files()
        err = io.StringIO()
        out = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            rc = robust_suite.main(
                ["--out", os.path.join(self.dir, "robust.jsonl"),
                 "--cost_out", os.path.join(self.dir, "cost.jsonl"),
                 "--manifest", manifest, "--index", index, "--matrix", matrix,
                 "--bin_dir", self.dir, "--repeats", "3"] + list(args),
                identity=IDENT)
        return rc, out.getvalue(), err.getvalue()

    def test_main_skips_what_the_results_hold(self):
        bench, _ = self.bench()
        with unittest.mock.patch.object(robust_suite, "CASES",
                                        [(1, "good", "g")]):
            self.good_and_bad()
            rc, out, _ = self.main("--cost", "--print_targets")
            self.assertEqual(rc, 0)
            self.assertEqual(out.split(), [robust_suite.SUITE_TARGET,
                                           robust_suite.COST_TARGET])
            rc, _, _ = self.main("--cost_bench", bench,
                                 "--compilation_mode", "opt")
            self.assertEqual(rc, 0)
            self.assertEqual(len(self.calls()), 2)
            rc, out, err = self.main("--cost", "--print_targets")
            self.assertEqual((rc, out.strip()), (0, ""))
            self.assertIn("complete, passing suite run of source tree "
                          + TREE[:12], err)
            self.assertIn("not rebuilt or rerun", err)
            self.assertIn("every cost run of profile quick", err)
            rc, _, err = self.main("--cost_bench", bench)
            self.assertEqual(rc, 0)
            self.assertEqual(self.calls(), [])
            # Another profile: the suite again.
            rc, out, _ = self.main("--profile", "full", "--print_targets")
            self.assertEqual(out.split(), [robust_suite.SUITE_TARGET])
            recs = read_jsonl(os.path.join(self.dir, "robust.jsonl"))
            self.assertEqual(recs[-1]["kind"], "suite")
            self.assertEqual(recs[-1]["provenance"]["compilation_mode"],
                             "opt")


if __name__ == "__main__":
    unittest.main()
