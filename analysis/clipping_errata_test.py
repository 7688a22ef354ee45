"""analysis/clipping_errata.py: the identities on a made-up report row and
on our records, and the macros on the report's real tables."""

import unittest

import pandas as pd

from analysis import clipping_errata
from analysis import inputs
from analysis import testdata


def long_rows(scene, cells):
    return [{"report_scene": scene, "variant": v, "metric": m, "value": x}
            for (v, m), x in cells.items()]


class ClippingErrataTest(unittest.TestCase):
    def test_a_row_that_stores_two_boxes_per_clip_and_loses_references(self):
        n_tri, n_i, n_l, r_e, n_cl = 1000.0, 300.0, 301.0, 0.1, 500.0
        n_tp = n_tri + n_cl - 50  # 50 references lost: 10 % of N_CL
        formula = 8 * (n_i + n_l) + 4 * (n_tp + n_l - r_e * n_l) + 8 * n_tri
        cells = {("clipping", "N_I"): n_i, ("clipping", "N_L"): n_l,
                 ("clipping", "N_TP"): n_tp, ("clipping", "R_E"): r_e,
                 ("clipping", "N_CL"): n_cl,
                 ("clipping", "mem"): (formula + 56 * n_cl) / 2 ** 20,
                 ("clipping-pruning", "N_TP"): n_tri + 400 - 30,
                 ("clipping-pruning", "N_CL"): 400, ("clipping-pruning", "N_PR"): 30}
        tables = pd.DataFrame(long_rows(7, cells))
        table1 = pd.DataFrame([{"report_scene": 7, "n_tri": n_tri}])
        per_cl, short, holds, tested = clipping_errata.report_numbers(
            clipping_errata.report_rows(tables, table1))
        self.assertAlmostEqual(per_cl[0], 56.0, places=6)
        self.assertAlmostEqual(short[0], 0.1)
        self.assertEqual((holds, tested), (1, 1))

    def test_ours_closes_the_count(self):
        recs = [testdata.kdrt_record("a", "clipping-pruning", N_CL=10, N_PR=2,
                                     N_TP=108, n_tri=100),
                testdata.kdrt_record("b", "clipping", N_CL=10, N_TP=111, n_tri=100),
                testdata.kdrt_record("b", "pruning", N_TP=5, n_tri=100)]
        runs, worst = clipping_errata.our_excess(recs)
        self.assertEqual(runs, 2)
        self.assertAlmostEqual(worst, 1 / 111)

    def test_the_report_s_own_tables(self):
        rows = clipping_errata.report_rows(inputs.load_seed_tables2_10(),
                                           inputs.load_seed_table1())
        per_cl, short, holds, tested = clipping_errata.report_numbers(rows)
        self.assertTrue(per_cl)
        self.assertTrue(all(abs(x - 56) < 0.5 for x in per_cl))
        self.assertTrue(all(0 < x < 1 for x in short))
        self.assertGreater(holds, tested // 2)


if __name__ == "__main__":
    unittest.main()
