"""analysis/provenance.py (reading and checking a record's provenance) and
analysis/provenance_macros.py (the first page's statement of it)."""

import os
import tempfile
import unittest

from analysis import context
from analysis import provenance as pv
from analysis import provenance_macros
from analysis import testdata


def rec(scene="alpha", preset="clipping", **prov):
    return testdata.kdrt_record(scene, preset,
                                provenance=testdata.provenance(**prov))


def old(scene="alpha", preset="clipping", **fields):
    """A record from before kdrt wrote provenance (fields: what it had)."""
    record = testdata.kdrt_record(scene, preset, **fields)
    del record["provenance"]
    return record


class ReadTest(unittest.TestCase):
    def test_a_record_without_provenance_is_unknown(self):
        self.assertIsNone(pv.of(old(git_commit="abc")))
        self.assertIsNone(pv.code_key(pv.of({})))
        self.assertIn("unknown provenance", pv.short(None))

    def test_short_form(self):
        self.assertEqual(pv.short(testdata.provenance()), "0123456789ab, opt")
        self.assertEqual(
            pv.short(testdata.provenance(dirty=True, source_tree="f" * 40,
                                         compilation_mode="dbg"), cpu=True),
            "0123456789ab +dirty ffffffffffff, dbg, Fixture CPU @ 1.00GHz")

    def test_the_code_is_the_source_tree_and_the_mode(self):
        # Another commit with the same tree is the same code (a rebase).
        self.assertEqual(pv.code_key(testdata.provenance(commit="a" * 40)),
                         pv.code_key(testdata.provenance()))
        self.assertNotEqual(pv.code_key(testdata.provenance(source_tree="b" * 40)),
                            pv.code_key(testdata.provenance()))
        self.assertNotEqual(pv.code_key(testdata.provenance(compilation_mode="dbg")),
                            pv.code_key(testdata.provenance()))


class CheckTest(unittest.TestCase):
    def test_one_provenance_passes(self):
        groups = pv.check_one_provenance([rec(), rec("beta")])
        self.assertEqual(len(groups), 1)
        self.assertEqual(len(groups[0][1]), 2)

    def test_two_provenances_are_named_with_the_flag(self):
        records = [rec(), rec("beta", dirty=True, source_tree="e" * 40)]
        with self.assertRaises(pv.ProvenanceError) as cm:
            pv.check_one_provenance(records, what="Table 9")
        self.assertEqual(
            str(cm.exception),
            "Table 9 would mix records of 2 provenances: 0123456789ab, opt "
            "(1 record, e.g. alpha/clipping); 0123456789ab +dirty eeeeeeeeeeee, "
            "opt (1 record, e.g. beta/clipping). Rerun them with one build of "
            "one source tree, or pass --allow_mixed_provenance")
        self.assertEqual(len(pv.check_one_provenance(records, allow_mixed=True)), 2)

    def test_unknown_differs_from_known(self):
        with self.assertRaisesRegex(pv.ProvenanceError, "unknown provenance"):
            pv.check_one_provenance([rec(), old("beta", "x")])
        # Unknown alone is one provenance.
        pv.check_one_provenance([old("a"), old("b")])

    def test_two_cpus_need_their_own_flag(self):
        records = [rec(), rec("beta", cpu_model="Other CPU")]
        with self.assertRaisesRegex(pv.MixedCpuError, "--allow_mixed_cpus"):
            pv.check_one_provenance(records, allow_mixed=True)
        groups = pv.check_one_provenance(records, allow_mixed_cpus=True)
        self.assertEqual(pv.cpus(groups), ["Fixture CPU @ 1.00GHz", "Other CPU"])

    def test_one_model_name_on_two_cpus_is_two_cpus(self):
        # A virtual machine's model name covers several CPUs: its family,
        # model, stepping and caches tell them apart.
        ice = dict(cpu_id="GenuineIntel family 6 model 106 stepping 6",
                   cpu_caches="L2 1280K, L3 49152K")
        sapphire = dict(cpu_id="GenuineIntel family 6 model 143 stepping 8",
                        cpu_caches="L2 2048K, L3 107520K")
        with self.assertRaisesRegex(pv.MixedCpuError, "model 106.*model 143"):
            pv.check_one_provenance([rec(**ice), rec("beta", **sapphire)])
        self.assertEqual(len(pv.check_one_provenance([rec(**ice), rec("beta", **ice)])), 1)
        # A record naming the model only may have come from either.
        with self.assertRaises(pv.MixedCpuError):
            pv.check_one_provenance([rec(**ice), rec("beta")])
        self.assertEqual(pv.cpu_name(testdata.provenance(**ice)),
                         "Fixture CPU @ 1.00GHz (GenuineIntel family 6 model 106 "
                         "stepping 6; L2 1280K, L3 49152K)")
        self.assertIsNone(pv.cpu_name(testdata.provenance(cpu_model=None)))
        self.assertEqual(pv.cpu_name(testdata.provenance(cpu_model=None, **ice)),
                         "GenuineIntel family 6 model 106 stepping 6; L2 1280K, L3 49152K")

    def test_unoptimised_timings_are_refused(self):
        records = [rec(), rec("beta", "pruning", compilation_mode="fastbuild",
                              optimized=False, ndebug=False, timing_build=False)]
        with self.assertRaises(pv.UnoptimizedTimingError) as cm:
            pv.check_timing_builds(records, what="Table 2")
        message = str(cm.exception)
        self.assertIn("Table 2 would show timings of beta/pruning", message)
        self.assertIn("0123456789ab, fastbuild", message)
        self.assertIn("--allow_unoptimized_timings", message)
        pv.check_timing_builds(records, allow=True)
        pv.check_timing_builds([old("old")])  # unknown: not refused

    def test_check_reads_the_context_flags(self):
        ctx = context.Context("r", "m", "o")
        slow = [rec(timing_build=False)]
        with self.assertRaises(pv.UnoptimizedTimingError):
            pv.check(ctx, slow, "x")
        pv.check(ctx, slow, "x", timings=False)
        ctx.allow_unoptimized_timings = True
        pv.check(ctx, slow, "x")


class MacrosTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results = os.path.join(self.tmp.name, "results")
        os.makedirs(self.results)
        self.ctx = context.Context(self.results, "none.json", self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_from_the_records(self):
        emb = testdata.embree(0.2, [0.5, 0.6, 0.7, 0.8, 0.9])
        testdata.write_kdtree(self.results, [
            testdata.kdrt_record(s, "clipping", embree=emb, T_R_runs=[1.0] * 5)
            for s in ("alpha", "beta")])
        m = {k: v[0] for k, v in provenance_macros.generate(self.ctx).items()}
        self.assertEqual(sorted(m), sorted(provenance_macros.MACROS))
        self.assertEqual(m["ProvCommit"], "0123456789ab")
        self.assertEqual(m["ProvSourceTree"], "89abcdef0123")
        self.assertEqual(m["ProvDirty"], "")
        self.assertEqual(m["ProvBuild"], "\\texttt{opt} (optimised, asserts off), "
                         "compiler 12.2.0, AVX2+FMA")
        self.assertEqual(m["ProvCPU"], "Fixture CPU @ 1.00GHz")
        self.assertEqual(m["ProvCores"], "2")
        self.assertEqual(m["ProvRecords"], "2")
        self.assertEqual(m["ProvTiming"],
                         "timed steps alone under a machine-wide lock, 1 "
                         "untimed warm-up per tracer excluded, 5 paired rounds "
                         "(kd-tree and Embree alternating)")

    def test_renders_on_the_quieter_cpu(self):
        records = [testdata.kdrt_record(s, "clipping", T_R_runs=[1.0] * 3)
                   for s in ("alpha", "beta", "gamma")]
        records[0]["timing"] = {"cpu": 1, "cpu_probe_ms": {"0": 4.0, "1": 2.7}}
        records[1]["timing"] = {"cpu": 0, "cpu_probe_ms": {"0": 3.5, "1": 3.9}}
        testdata.write_kdtree(self.results, records)
        m = {k: v[0] for k, v in provenance_macros.generate(self.ctx).items()}
        self.assertTrue(m["ProvTiming"].endswith(
            ", renders on the quieter CPU in 2 of 3 runs (its probe 3.1 ms median, 2.7 to 3.5: "
            "higher is a busier machine)"), m["ProvTiming"])

    def test_unknown_and_unlocked(self):
        old = testdata.kdrt_record("alpha", "clipping")
        del old["provenance"]
        testdata.write_kdtree(self.results, [old, testdata.kdrt_record(
            "beta", "clipping", provenance=testdata.provenance(
                dirty=True, timing_lock=None, timed_beside=None))])
        m = {k: v[0] for k, v in provenance_macros.generate(self.ctx).items()}
        self.assertEqual(m["ProvCommit"], "unknown; 0123456789ab")
        self.assertEqual(m["ProvDirty"], " (with uncommitted changes)")
        self.assertTrue(m["ProvTiming"].startswith(provenance_macros.UNKNOWN_BESIDE))

    def test_other_studies(self):
        testdata.write_kdtree(self.results, [testdata.kdrt_record("a", "clipping")])
        with open(os.path.join(self.results, "accuracy.jsonl"), "w") as f:
            f.write('{"ok": true, "scene": "a", "step": "bins 32"}\n')
        m = provenance_macros.generate(self.ctx)
        self.assertIn("accuracy study comes from other code: unknown",
                      m["ProvStudies"][0])

    def test_no_runs(self):
        m = provenance_macros.generate(self.ctx)
        self.assertEqual(m["ProvRecords"][0], "0")
        self.assertEqual(m["ProvCommit"][0], "unknown")


if __name__ == "__main__":
    unittest.main()
