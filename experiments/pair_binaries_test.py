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


if __name__ == "__main__":
    unittest.main()
