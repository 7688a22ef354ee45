import os
import tempfile
import unittest

from analysis import context
from analysis import inputs
from analysis import seed_tables
from analysis import testdata


class SeedTable1CsvTest(unittest.TestCase):
    """The transcription of the report's Table 1 is self-consistent."""

    @classmethod
    def setUpClass(cls):
        cls.df = inputs.load_seed_table1()

    def test_eighteen_scenes_numbered_in_order(self):
        self.assertEqual(list(self.df["report_scene"]), list(range(1, 19)))

    def test_primary_rays_sum_to_image(self):
        for _, r in self.df.iterrows():
            self.assertEqual(r["p_hit"] + r["p_miss"], 800 * 800, r["name"])

    def test_shadow_rays_sum_to_primary_hits(self):
        for _, r in self.df.iterrows():
            self.assertEqual(r["s_hit"] + r["s_miss"], r["p_hit"], r["name"])

    def test_spot_values(self):
        # A few cells checked by hand against the seed text.
        df = self.df
        self.assertEqual(df.loc[1, "name"], "A10")
        self.assertEqual(df.loc[2, "n_tri"], 345944)
        self.assertEqual(df.loc[13, "name"], "lost.empire")
        self.assertEqual(df.loc[14, "n_tri"], 12759246)
        self.assertEqual(df.loc[15, "s_hit"], 359704)
        self.assertEqual(df.loc[16, "p_miss"], 0)
        self.assertEqual(df.loc[18, "n_tri"], 968)
        self.assertEqual(int(df["n_tri"].sum()), 42612619)


class SeedTable1RenderTest(unittest.TestCase):
    def test_render_with_stand_ins(self):
        with tempfile.TemporaryDirectory() as d:
            results, manifest = testdata.write_fixture(d)
            out = os.path.join(d, "gen")
            ctx = context.Context(results, manifest, out)
            self.assertEqual(seed_tables.generate(ctx), {})
            with open(os.path.join(out, "seed_table1.tex"),
                      encoding="utf-8") as f:
                text = f.read()
        self.assertIn("\\label{tab:seed1}", text)
        self.assertIn("\\multicolumn{5}{c}{The report}", text)
        self.assertIn("2 & Armadillo & 345,944 & 149,572 & 490,428 & "
                      "32,053 & 117,519 & 2 armadillo & 345,944 \\\\", text)
        self.assertIn("5 & city & 68,497 & 377,970 & 262,030 & 202,140 & "
                      "175,830 & 4 city\\_gen & 68,010 \\\\", text)
        # no stand-in: dashes; a failed stand-in does not count
        self.assertIn("16 & san-miguel & 9,980,699 & 640,000 & 0 & 391,277 "
                      "& 248,723 & --- & --- \\\\", text)
        self.assertIn("3 & asianDragon", text)
        self.assertIn("13 & lost.empire", text)


if __name__ == "__main__":
    unittest.main()
