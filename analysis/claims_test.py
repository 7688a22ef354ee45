"""The claims on kdrt records of the real shape: a timing claim whose runs'
ranges overlap, or with a single run, is within noise."""

import os
import unittest

from analysis import claims
from analysis import kdtree_results as kr
from analysis import testdata


class BelowTest(unittest.TestCase):
    def test_ranges_apart_decide(self):
        self.assertIs(claims.below([1.0, 1.1], [1.2, 1.3]), True)
        self.assertIs(claims.below([1.4, 1.5], [1.2, 1.3]), False)

    def test_overlapping_ranges_are_noise(self):
        self.assertIsNone(claims.below([1.0, 1.25], [1.2, 1.3]))

    def test_a_single_run_is_noise(self):
        self.assertIsNone(claims.below([1.0], [5.0, 5.1]))
        self.assertIsNone(claims.below([1.0, 1.0], []))

    def test_factor_scales_the_other_side(self):
        # 1.1-1.2 against 1.15 x 1.0-1.02 = 1.15-1.173: overlap.
        self.assertIsNone(claims.below([1.1, 1.2], [1.0, 1.02], 1.15))
        self.assertIs(claims.below([1.1, 1.12], [1.0, 1.02], 1.15), True)

    def test_three_valued_logic(self):
        self.assertIs(claims.all3(True, None, False), False)
        self.assertIsNone(claims.all3(True, None))
        self.assertIs(claims.any3(False, None, True), True)
        self.assertIsNone(claims.any3(False, None))
        self.assertIsNone(claims.not3(None))


class VerdictTest(unittest.TestCase):
    def test_half_within_noise_is_within_noise(self):
        self.assertEqual(claims.verdict(agree=2, decided=2, noise=2), "within noise")

    def test_otherwise_two_thirds_of_the_decided(self):
        self.assertEqual(claims.verdict(agree=2, decided=3, noise=1), "confirmed")
        self.assertEqual(claims.verdict(agree=1, decided=3, noise=1), "refuted")
        self.assertEqual(claims.verdict(agree=3, decided=5, noise=0), "mixed")
        self.assertEqual(claims.verdict(agree=0, decided=0, noise=0), "not tested")


class ClaimsTest(testdata.KdtreeFixtureTest):
    def evaluate(self):
        df = kr.frame(self.ctx.results(kr.KDTREE_FILE), self.ctx.manifest)
        return {c[0][0]: c[1:] for c in claims.evaluate(df)}

    def test_statistics_claims_are_decided(self):
        by_id = self.evaluate()
        self.assertEqual(by_id["depth"], (3, 3, 0, 0.1, "confirmed"))
        self.assertEqual(by_id["manyclipped"][-1], "confirmed")  # 3000 > 1000
        self.assertEqual(by_id["fewerpruned"][-1], "confirmed")  # 100 < 900
        self.assertEqual(by_id["allaxes"][-1], "refuted")  # equal N_L

    def test_runs_apart_decide_a_timing_claim(self):
        # Clip+prune 0.88-0.92 s against 0.97 x pruning's 0.78-0.82 s.
        agree, decided, noise, _, verdict = self.evaluate()["clipnotbetter"]
        self.assertEqual((agree, decided, noise, verdict), (3, 3, 0, "confirmed"))

    def test_single_runs_are_within_noise(self):
        # binning-32 and binning-8 have one build each.
        agree, decided, noise, ratio, verdict = self.evaluate()["bins"]
        self.assertEqual((agree, decided, noise, verdict), (0, 0, 3, "within noise"))
        self.assertAlmostEqual(ratio, 1.0)

    def test_overlapping_runs_are_within_noise(self):
        for scene in ("alpha", "beta"):
            testdata.write_kdtree(self.ctx.results_dir, [
                testdata.kdrt_record(scene, "pruning", T_R=0.8,
                                     T_R_runs=[0.7, 0.8, 0.95])])
        agree, decided, noise, _, verdict = self.evaluate()["clipnotbetter"]
        self.assertEqual((agree, decided, noise, verdict), (1, 1, 2, "within noise"))

    def test_table_and_macros(self):
        macros = claims.generate(self.ctx)
        self.assertEqual(macros["ClaimsTotal"][0], str(len(claims.CLAIMS)))
        # The six timing claims: all but clipnotbetter have single runs.
        self.assertEqual(macros["ClaimsWithinNoise"][0], "5")
        with open(os.path.join(self.out, "claims.tex")) as f:
            text = f.read()
        self.assertIn("within noise", text)
        self.assertIn("Agree & Noise & Median & Verdict", text)
        self.assertIn("& 3/3 & 0 &", text)
        with open(os.path.join(self.out, "claims_brief.tex")) as f:
            brief = f.read()
        self.assertEqual(brief.count("\\\\"), len(claims.CLAIMS))
        self.assertIn("clipping adds nothing to pruning & \\textbf{confirmed} & 3/3 \\\\", brief)
        self.assertIn("(3 in noise)", brief)
        self.assertEqual(sorted(claims.SHORT), sorted(c[0] for c in claims.CLAIMS))


if __name__ == "__main__":
    unittest.main()
