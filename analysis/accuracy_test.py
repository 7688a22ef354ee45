"""analysis/accuracy.py on a small fixture (made-up numbers, tests only)."""

import json
import os
import tempfile
import unittest

from analysis import accuracy
from analysis import context
from analysis import provenance
from analysis import testdata

STEPS = [("report", "report clipping-pruning"), ("bins", "bins 32"),
         ("bins", "exact sweep"), ("clipping", "box clipping"),
         ("clipping", "perfect splits")]


def rec(scene, knob, step, t_b, t_r, sah, ok=True, **over):
    """A kdrt record (analysis/testdata.py) with experiments/run_accuracy.py's
    fields (knob, step, ...)."""
    return testdata.kdrt_record(
        scene, "sah-hybrid", added=testdata.accuracy_fields(scene, knob, step),
        ok=ok, T_B=t_b, T_R=t_r,
        sah_cost=sah, N_IT=sah / 10.0, N_TR=sah / 20.0, mem_report_mb=2.0,
        **over)


# Fixture: on both scenes the exact sweep doubles T_B of bins 32 and lowers
# its SAH cost to 0.9 of it; perfect splits cost 1.5x box clipping's T_B.
RECORDS = []
for scene, scale in (("bunny", 1.0), ("city", 4.0)):
    RECORDS += [
        rec(scene, "report", "report clipping-pruning", 1.0 * scale, 2.0 * scale, 100.0),
        rec(scene, "bins", "bins 32", 0.5 * scale, 1.0 * scale, 80.0),
        rec(scene, "bins", "exact sweep", 1.0 * scale, 1.0 * scale, 72.0),
        rec(scene, "clipping", "box clipping", 2.0 * scale, 0.5 * scale, 60.0),
        rec(scene, "clipping", "perfect splits", 3.0 * scale, 0.5 * scale, 57.0),
    ]
RECORDS.append(rec("bunny", "bins", "bins 32", 9.0, 9.0, 1.0, ok=False))


class AccuracyTest(unittest.TestCase):

    def run_generate(self, records):
        tmp = tempfile.mkdtemp()
        results = os.path.join(tmp, "results")
        out = os.path.join(tmp, "out")
        os.makedirs(results)
        os.makedirs(out)
        with open(os.path.join(results, accuracy.RESULTS_FILE), "w") as f:
            for r in records:
                f.write(json.dumps(r) + "\n")
        ctx = context.Context(results, os.path.join(tmp, "none.json"), out)
        return ctx, accuracy.generate(ctx), out

    def test_table_figure_and_macros(self):
        ctx, macros, out = self.run_generate(RECORDS)
        self.assertEqual(set(macros), set(accuracy.MACROS))
        self.assertEqual(macros["AccuracyScenes"][0], "2")
        self.assertEqual(macros["AccuracySteps"][0], "5")
        self.assertEqual(macros["AccuracyExactBuildRatio"][0], "2.00")
        self.assertEqual(macros["AccuracyExactSahRatio"][0], "0.900")
        self.assertEqual(macros["AccuracyPerfectBuildRatio"][0], "1.50")
        self.assertEqual(macros["AccuracyBestSahStep"][0], "perfect splits")
        # Totals relative to the report: bins 32 is 1.5 / 3 = 0.5 on both.
        self.assertEqual(macros["AccuracyFastestStep"][0], "bins 32")
        table = open(os.path.join(out, "accuracy_table.tex")).read()
        self.assertIn("perfect splits", table)
        self.assertIn("\\label{tab:accuracy}", table)
        row = [l for l in table.splitlines() if l.startswith("bins & exact sweep")]
        self.assertEqual(len(row), 1)
        # T_B ratio to the report 1.0, T_R 0.5, total 2/3, SAH 0.72.
        self.assertIn("& 1.00 & 0.500 & 0.667 & 0.720 &", row[0])
        self.assertTrue(os.path.getsize(os.path.join(out, "accuracy_pareto.pdf")) > 1000)
        self.assertIn("accuracy_pareto.pdf",
                      open(os.path.join(out, "accuracy_figure.tex")).read())

    def test_two_provenances_are_refused(self):
        other = testdata.provenance(source_tree="d" * 40)
        records = RECORDS + [rec("city", "bins", "bins 32", 2.0, 4.0, 80.0,
                                 provenance=other)]
        with self.assertRaisesRegex(provenance.ProvenanceError,
                                    "accuracy study.*city/sah-hybrid/bins 32"):
            self.run_generate(records)

    def test_unoptimised_timings_are_refused(self):
        slow = testdata.provenance(timing_build=False)
        with self.assertRaises(provenance.UnoptimizedTimingError):
            self.run_generate([rec("bunny", "report", "report clipping-pruning",
                                   1.0, 2.0, 100.0, provenance=slow)])

    def test_pareto_front(self):
        pts = [(1.0, 10.0), (2.0, 5.0), (3.0, 6.0), (0.5, 20.0), (2.0, 5.0)]
        self.assertEqual(accuracy.pareto(pts), [3, 0, 1, 4])

    def test_no_results(self):
        _, macros, out = self.run_generate([])
        self.assertEqual(macros["AccuracyScenes"][0], "---")
        self.assertIn("not run", open(os.path.join(out, "accuracy_table.tex")).read())


if __name__ == "__main__":
    unittest.main()
