"""experiments/pair_binaries.py's arithmetic (the runs themselves need kdrt)."""

import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_binaries  # noqa: E402


class PairBinariesTest(unittest.TestCase):
    def test_ratios_are_paired_per_round(self):
        new = [(1.0, 0.5, 4.0), (2.0, 0.6, 1.0), (1.5, 0.9, 3.0)]
        old = [(2.0, 0.5, 2.0), (2.0, 0.3, 1.0), (1.0, 0.9, 3.0)]
        self.assertEqual(pair_binaries.ratios(new, old),
                         [(0.5, 1.0, 2.0), (1.0, 2.0, 1.0), (1.5, 1.0, 1.0)])

    def test_summary_is_median_min_max_per_column(self):
        got = pair_binaries.summary([(0.5, 1.0), (1.0, 2.0), (1.5, 1.0)])
        self.assertEqual(got, [(1.0, 0.5, 1.5), (1.0, 1.0, 2.0)])

    def test_a_column_some_records_lack(self):
        # The BVH packets' time: absent from an older binary's records.
        self.assertEqual(pair_binaries.ratios([(1.0, None), (2.0, 3.0)], [(2.0, 1.0), (2.0, 1.5)]),
                         [(0.5, None), (1.0, 2.0)])
        got = pair_binaries.summary([(0.5, None), (1.0, 2.0)])
        self.assertEqual(got, [(0.75, 0.5, 1.0), (2.0, 2.0, 2.0)])
        self.assertEqual(pair_binaries.summary([(1.0, None)]), [(1.0, 1.0, 1.0), None])

    def test_row_reads_the_bvh_packets_when_present(self):
        rec = {"T_B": 1.0, "T_R": 2.0, "fast_render": {"T_R": 3.0}}
        self.assertEqual(pair_binaries.row(rec), (1.0, 2.0, 3.0, None))
        rec["fast_render"]["packets_bvh"] = {"T_R": 4.0}
        self.assertEqual(pair_binaries.row(rec), (1.0, 2.0, 3.0, 4.0))


if __name__ == "__main__":
    unittest.main()
