"""Tests of analysis/table_scale.py on log lines as pdflatex writes them."""

import io
import os
import sys
import tempfile
import unittest
from contextlib import redirect_stdout

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from analysis import table_scale  # noqa: E402

LOG = """This is pdfTeX
FITTABLE tab:rays font 9 natural 283.92401pt line 472.31595pt
FITTABLE tab:embree font 8 natural 973.31702pt line 472.31
595pt
FITTABLE tab:wide font 11 natural 500pt line 500pt
FITTABLE tab:rays font 9 natural 283.92401pt line 472.31595pt
FITFIGURE fig1_build.pdf natural 453.6pt set 472.31595pt
FITFIGURE cost/city.png natural 1353.6pt set 6
76.8pt
"""


class TableScaleTest(unittest.TestCase):
    def test_parse_joins_wrapped_lines_and_keeps_each_label_once(self):
        tables = table_scale.parse(LOG)
        self.assertEqual([t[0] for t in tables], ["tab:rays", "tab:embree", "tab:wide"])
        self.assertAlmostEqual(tables[1][3], 472.31595)

    def test_figures_scale_is_set_over_natural_width(self):
        self.assertEqual(table_scale.parse_figures(LOG),
                         [("fig1_build.pdf", 472.31595 / 453.6), ("cost/city.png", 0.5)])

    def test_effective_size(self):
        # footnotesize in an 11 pt body, not shrunk: 9 / 11
        self.assertAlmostEqual(table_scale.effective(9, 283.9, 472.3, 11), 9 / 11)
        # 8 pt shrunk to the line: 8 / 11 * 472.3 / 973.3
        self.assertAlmostEqual(table_scale.effective(8, 973.3, 472.3, 11), 8 / 11 * 472.3 / 973.3)

    def test_strict_fails_on_a_small_table(self):
        with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as f:
            f.write(LOG)
        try:
            out = io.StringIO()
            with redirect_stdout(out):
                self.assertEqual(table_scale.main([f.name, "--strict"]), 1)
                self.assertEqual(table_scale.main([f.name]), 0)
            self.assertIn("tab:embree", out.getvalue())
            self.assertIn("1 of 3 tables below 80 %", out.getvalue())  # 9 pt: 82 %
            self.assertIn("figure cost/city.png", out.getvalue())
            self.assertIn("1 of 2 figures below 80 %", out.getvalue())
            with redirect_stdout(io.StringIO()):
                self.assertEqual(table_scale.main([f.name, "--strict", "--limit", "0.3"]), 0)
        finally:
            os.unlink(f.name)


if __name__ == "__main__":
    unittest.main()
