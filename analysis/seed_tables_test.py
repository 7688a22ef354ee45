import copy
import csv
import decimal
import json
import math
import os
import re
import tempfile
import unittest

from analysis import context
from analysis import inputs
from analysis import kdtree_results as kr
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


METRICS = {2: ["T_B", "T_R", "perf", "N_IT", "N_TR"],
           5: ["N_I", "N_L", "N_TP", "N_AP", "mem"],
           8: ["R_E", "D_max", "D_avg", "N_CL", "N_PR"]}


def table_of(variant, metric):
    """The report's table holding (variant, metric): 2-10."""
    first = [t for t, ms in METRICS.items() if metric in ms][0]
    return first + [k for k, g in enumerate(kr.GROUPS) if variant in g][0]


class SeedTables2To10CsvTest(unittest.TestCase):
    """The transcription of the report's Tables 2-10 (tables2_10.csv)."""

    @classmethod
    def setUpClass(cls):
        cls.df = inputs.load_seed_tables2_10()
        cls.cell = {(r.report_scene, r.variant, r.metric): r
                    for r in cls.df.itertuples()}

    def value(self, scene, variant, metric):
        return self.cell[(scene, variant, metric)].value

    def printed(self, scene, variant, metric):
        return self.cell[(scene, variant, metric)].printed

    def test_shape(self):
        # 18 scenes x 9 variants x 15 metrics, minus Table 7 rows 13-18
        # (the seed stops after row 13's first two cells).
        df = self.df
        self.assertEqual(len(df), 18 * 9 * 15 - (6 * 15 - 2))
        self.assertFalse(df.duplicated(["report_scene", "variant",
                                        "metric"]).any())
        self.assertEqual(sorted(df["variant"].unique()), sorted(kr.VARIANTS))
        self.assertEqual(sorted(df["report_scene"].unique()),
                         list(range(1, 19)))
        for (table, variant, metric), n in df.groupby(
                ["table", "variant", "metric"]).size().items():
            self.assertEqual(table, table_of(variant, metric))
            if table != 7:
                self.assertEqual(n, 18, (variant, metric))
        t7 = df[df["table"] == 7]
        self.assertEqual(len(t7), 12 * 15 + 2)
        self.assertEqual(sorted(t7["report_scene"].unique()),
                         list(range(1, 14)))
        row13 = t7[t7["report_scene"] == 13]
        self.assertEqual(sorted(zip(row13["variant"], row13["metric"])),
                         [("clipping", "N_I"), ("clipping", "N_L")])

    def test_dashes_are_empty_values(self):
        empty = self.df[self.df["value"].isna()]
        self.assertEqual(set(empty["printed"]), {"-"})
        self.assertEqual(len(empty), 14)
        self.assertEqual(set(empty["report_scene"]), {16})
        self.assertEqual(set(empty["variant"]), {"median-16-2"})
        self.assertEqual(self.value(16, "median-16-2", "T_B"), 1.963)

    def test_values_are_the_printed_text(self):
        # value = printed without thousands separators; a comma that cannot
        # be one (and every comma's last one in mem) is a decimal comma.
        for r in self.df.itertuples():
            if r.printed == "-":
                continue
            text = r.printed
            if "," in text and (r.metric == "mem" or not re.match(
                    r"^\d{1,3}(,\d{3})+(\.\d+)?$", text)):
                head, tail = text.rsplit(",", 1)
                text = head + "." + tail
            self.assertEqual(r.value, float(text.replace(",", "")),
                             (r.table, r.report_scene, r.variant, r.metric))

    def test_spot_values(self):
        # Checked by hand against the seed text (line numbers in brackets).
        v = self.value
        self.assertEqual(v(1, "median-16-2", "T_B"), 0.045)  # 199
        self.assertEqual(v(3, "median-16-2", "N_IT"), 2404.63)  # 201
        self.assertEqual(v(12, "median-24-2", "T_B"), 2718)  # 210, odd
        self.assertEqual(self.printed(12, "median-24-2", "T_B"), "2,718")
        self.assertEqual(v(4, "binning-8-driving", "perf"), 2207.0)  # 225
        self.assertEqual(v(12, "binning-8", "T_B"), 15.417)  # 233
        self.assertEqual(v(18, "binning-32", "N_IT"), 14.91)  # 239
        self.assertEqual(v(18, "binning-32", "N_TR"), 4.88)  # 239
        self.assertEqual(v(1, "pruning", "perf"), 4923)  # 245
        self.assertEqual(v(15, "clipping", "T_B"), 12.068)  # 259
        self.assertEqual(v(18, "clipping-pruning", "N_IT"), 11.11)  # 262
        self.assertEqual(v(1, "median-16-2", "mem"), 3.031)  # 270
        self.assertEqual(self.printed(1, "median-16-2", "mem"), "3,031")
        self.assertEqual(v(3, "median-16-2", "N_AP"), 1100)  # 272
        self.assertEqual(v(18, "median-24-8", "N_AP"), 7)  # 287
        self.assertEqual(v(3, "binning-32", "N_I"), 1566865)  # 295
        self.assertEqual(v(12, "binning-8-driving", "N_TP"),
                         162446831)  # 304
        self.assertEqual(self.printed(14, "binning-32", "N_TP"),
                         "29,121,159,2")  # 306, odd
        self.assertEqual(v(12, "clipping", "mem"), 1866.848)  # 327
        self.assertEqual(v(13, "clipping", "N_L"), 239811)  # 328
        self.assertEqual(v(7, "median-24-2", "R_E"), 0.026)  # 340
        self.assertEqual(v(18, "median-24-8", "D_avg"), 19)  # 351
        self.assertEqual(v(7, "binning-8-driving", "R_E"), 0.083)  # 363
        self.assertEqual(v(1, "clipping-pruning", "N_PR"), 137257)  # 380
        self.assertEqual(v(12, "pruning", "N_PR"), 65196180)  # 391
        self.assertEqual(v(18, "clipping", "N_CL"), 4983)  # 397
        self.assertEqual(self.cell[(18, "clipping", "N_CL")].seed_line, 397)

    def test_row18_agrees_with_the_separate_transcription(self):
        # data/seed/row18.csv was transcribed independently of this file.
        path = os.path.join(os.path.dirname(os.path.dirname(
            os.path.abspath(inputs.__file__))), "data", "seed", "row18.csv")
        with open(path, encoding="utf-8") as f:
            rows = list(csv.DictReader(
                line for line in f if not line.startswith("#")))
        self.assertEqual(len(rows), 9)
        for row in rows:
            for metric in ("N_I", "N_L", "N_TP", "N_AP", "R_E", "D_max",
                           "D_avg", "N_CL", "N_PR"):
                key = (18, row["preset"], metric)
                if row[metric] == "":
                    self.assertNotIn(key, self.cell)
                else:
                    self.assertEqual(self.value(*key), float(row[metric]),
                                     key)

    def test_perf_is_primary_rays_over_render_time(self):
        # perf [krays/s] = 640,000 primary rays / T_R, within the rounding
        # of both printed numbers (shadow rays are not counted).
        n = 0
        for (scene, variant, metric), r in self.cell.items():
            if metric != "perf" or r.printed == "-":
                continue
            t_r = self.cell[(scene, variant, "T_R")]
            half = 0.5 * 10.0 ** decimal.Decimal(
                t_r.printed).as_tuple().exponent
            lo = 640.0 / (r.value + 0.5)
            hi = 640.0 / (r.value - 0.5)
            self.assertTrue(lo <= t_r.value + half and
                            hi >= t_r.value - half,
                            (scene, variant, r.value, t_r.value))
            n += 1
        self.assertEqual(n, 161)

    def test_leaves_are_internal_nodes_plus_one(self):
        # A binary tree has N_L = N_I + 1; the seed prints N_L = N_I in
        # four cells (README), nowhere else.
        odd = set()
        for (scene, variant, metric), r in self.cell.items():
            if metric != "N_I" or r.printed == "-":
                continue
            n_l = self.value(scene, variant, "N_L")
            if n_l != r.value + 1:
                self.assertEqual(n_l, r.value)
                odd.add((scene, variant))
        self.assertEqual(odd, {(10, "median-24-8"), (12, "median-24-2"),
                               (14, "binning-32"), (4, "pruning")})

    def test_average_leaf_size(self):
        # N_AP = N_TP / N_L to the two significant digits printed, except
        # the two garbled cells of row 10 (README).
        odd = set()
        for (scene, variant, metric), r in self.cell.items():
            if metric != "N_AP" or r.printed == "-":
                continue
            ratio = (self.value(scene, variant, "N_TP") /
                     self.value(scene, variant, "N_L"))
            tol = 0.5 * 10.0 ** (math.floor(math.log10(ratio)) - 1)
            if abs(r.value - ratio) > tol + 1e-9:
                odd.add((scene, variant))
        self.assertEqual(odd, {(10, "median-24-2"),
                               (10, "clipping-pruning")})

    def test_pruning_column_has_the_binning_32_tree(self):
        # Same N_I in all 12 printed rows of Table 7; same N_L too except
        # row 4, where Pruning's N_L is printed equal to its N_I.
        for scene in range(1, 13):
            self.assertEqual(self.value(scene, "pruning", "N_I"),
                             self.value(scene, "binning-32", "N_I"))
            if scene != 4:
                self.assertEqual(self.value(scene, "pruning", "N_L"),
                                 self.value(scene, "binning-32", "N_L"))

    def test_depth_clipping_pruning_columns(self):
        for (scene, variant, metric), r in self.cell.items():
            if r.printed == "-":
                continue
            key = (scene, variant, metric)
            if metric == "D_max":
                self.assertEqual(
                    r.value, 16 if variant == "median-16-2" else 24, key)
            if metric == "D_avg":
                self.assertLessEqual(r.value,
                                     self.value(scene, variant, "D_max"))
            if metric == "R_E":
                self.assertTrue(0 <= r.value <= 1, key)
            if metric == "N_CL":
                self.assertEqual(r.value > 0, variant in (
                    "clipping", "clipping-pruning"), key)
            if metric == "N_PR":
                self.assertEqual(r.value > 0, variant in (
                    "pruning", "clipping-pruning"), key)


class SeedTable1RenderTest(unittest.TestCase):
    def test_render_with_stand_ins(self):
        with tempfile.TemporaryDirectory() as d:
            results, manifest = testdata.write_fixture(d)
            out = os.path.join(d, "gen")
            ctx = context.Context(results, manifest, out)
            macros = seed_tables.generate(ctx)
            self.assertEqual(sorted(macros),
                             sorted(seed_tables.COMPARE_MACROS))
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


def kd_record(scene, preset, n_it, n_tr):
    return testdata.kdrt_record(scene, preset, N_IT=n_it, N_TR=n_tr)


class SeedCompareTest(unittest.TestCase):
    """seed_compare.tex and its scene-18 macros on a small fixture."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        manifest = copy.deepcopy(testdata.MANIFEST)
        roles = {"armadillo": "stand-in", "city_gen": "variant",
                 "suzanne": "original", "not_fetched": "stand-in"}
        for scene in manifest["scenes"]:
            scene["role"] = roles.get(scene["name"], "extra")
        results, manifest_path = testdata.write_fixture(
            self.tmp.name, manifest=manifest)
        recs = []
        for i, v in enumerate(kr.VARIANTS):
            # suzanne: lowest N_IT with pruning (index 7), N_TR tied between
            # clipping and clipping-pruning
            recs.append(kd_record("suzanne", v, 20.0 - i if i <= 7 else 30.0,
                                  3.5 if v.startswith("clipping") else 9.0))
            recs.append(kd_record("bunny", v, 1.0, 1.0))  # no report scene
            recs.append(kd_record("city_gen", v,
                                  7.0 if v == "binning-8" else 8.0, 2.0))
        # armadillo: only three presets ran; a failed record is ignored
        recs.append(kd_record("armadillo", "median-16-2", 40.0, 6.0))
        recs.append(kd_record("armadillo", "median-24-2", 12.5, 9.0))
        recs.append(kd_record("armadillo", "binning-32", 13.0, 5.25))
        recs.append(testdata.kdrt_record("armadillo", "pruning", ok=False,
                                         N_IT=0.1))
        with open(os.path.join(results, kr.KDTREE_FILE), "w") as f:
            for r in recs:
                f.write(json.dumps(r) + "\n")
        self.out = os.path.join(self.tmp.name, "gen")
        self.ctx = context.Context(results, manifest_path, self.out)
        self.macros = seed_tables.generate(self.ctx)
        with open(os.path.join(self.out, "seed_compare.tex"),
                  encoding="utf-8") as f:
            self.text = f.read()

    def tearDown(self):
        self.tmp.cleanup()

    def test_report_best_per_scene(self):
        best = seed_tables.seed_best(inputs.load_seed_tables2_10())
        self.assertEqual(sorted(best), list(range(1, 19)))
        # scene 18: N_IT 10.97 (Pruning), N_TR 4.67 (Clipping pruning)
        self.assertEqual(best[18]["N_IT"], (10.97, "10.97", ["pruning"]))
        self.assertEqual(best[18]["N_TR"], (4.67, "4.67",
                                            ["clipping-pruning"]))
        # scene 4 N_TR: 5.15 in four columns; scene 16 ignores the dashes
        self.assertEqual(best[4]["N_TR"][2], ["binning-32", "clipping",
                                              "pruning", "clipping-pruning"])
        self.assertEqual(best[16]["N_IT"][:2], (132.94, "132.94"))

    def test_table_rows(self):
        self.assertIn("\\label{tab:seedcmp}", self.text)
        self.assertIn(
            "18 & suzanne & 10.97 & Pruning & 4.67 & Clipping pruning & "
            "suzanne & \\textbf{report's mesh} & 13.0 & Pruning & 3.50 & "
            "Clipping, Clipping pruning \\\\", self.text)
        self.assertIn(
            "2 & Armadillo & 9.8 & Pruning & 6.93 & Spatial median 16/2 & "
            "armadillo (3/9) & stand-in & 12.5 & Spatial median 24/2 & 5.25 "
            "& Binning 32 \\\\", self.text)
        # a variant stand-in; a report scene without any of ours
        self.assertIn("5 & city & 15.46 & Pruning & 10.74 & Clipping pruning"
                      " & city\\_gen & variant & 7.00 & Binning 8 & 2.00 & "
                      "Spatial median 16/2, Spatial median 24/2, ", self.text)
        self.assertIn("3 & asianDragon & 21.13 & Pruning & 7.42 & Spatial "
                      "median 16/2 & --- &  & --- & --- & --- & --- \\\\",
                      self.text)
        self.assertNotIn("bunny", self.text)
        self.assertEqual(self.text.count(" \\\\\n"), 18 + 1 + 1)
        self.assertIn("only scene~18 is a like-for-like", self.text)
        self.assertIn("camera and lights differ", self.text)

    def test_scene18_macros(self):
        m = self.macros
        self.assertEqual(m["SeedCmpReportNIT"], ("10.97", False))
        self.assertEqual(m["SeedCmpReportNITBy"], ("Pruning", True))
        self.assertEqual(m["SeedCmpReportNTR"], ("4.67", False))
        self.assertEqual(m["SeedCmpOurNIT"], ("13.0", True))
        self.assertEqual(m["SeedCmpOurNITBy"], ("Pruning", True))
        self.assertEqual(m["SeedCmpOurNTR"], ("3.50", True))
        self.assertEqual(m["SeedCmpOurNTRBy"],
                         ("Clipping, Clipping pruning", True))
        self.assertEqual(m["SeedCmpOurScene"], ("suzanne", False))

    def test_no_kdtree_results(self):
        os.remove(os.path.join(self.ctx.results_dir, kr.KDTREE_FILE))
        ctx = context.Context(self.ctx.results_dir, self.ctx.manifest_path,
                              os.path.join(self.tmp.name, "gen2"))
        macros = seed_tables.generate(ctx)
        self.assertEqual(macros["SeedCmpOurNIT"], ("---", True))
        self.assertEqual(macros["SeedCmpReportNIT"], ("10.97", False))


if __name__ == "__main__":
    unittest.main()
