import json
import os
import tempfile
import unittest

from analysis import context
from analysis import inputs
from analysis import table1
from analysis import testdata


class Table1Test(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results, self.manifest = testdata.write_fixture(self.tmp.name)
        self.out = os.path.join(self.tmp.name, "generated")
        self.ctx = context.Context(self.results, self.manifest, self.out)

    def tearDown(self):
        self.tmp.cleanup()

    def generate(self):
        macros = table1.generate(self.ctx)
        with open(os.path.join(self.out, "table1.tex"), encoding="utf-8") as f:
            return f.read(), macros

    def body_lines(self, text):
        body = text.split("\\midrule\n", 1)[1].split("\\bottomrule", 1)[0]
        return [line for line in body.splitlines() if line.strip()]

    def test_generator_source_is_short(self):
        # The full profile's power plant places packaged parts; the table
        # names how many, not their paths (which made Table 1 unreadable).
        parts = [{"role": "tower", "height": 145.1, "package": "flightgear-data-base",
                  "path": "usr/share/games/flightgear/Scenery/Models/x%d.ac" % i}
                 for i in range(7)]
        plant = {"kind": "generator",
                 "generator": {"kind": "plant", "triangles": 12759246, "seed": 14,
                               "parts": parts}}
        self.assertEqual(table1.source_label(plant),
                         "generator \\texttt{plant, seed 14, 7 parts}")
        teapots = {"kind": "generator",
                   "generator": {"kind": "teapots", "seed": 10, "input": "teapot"}}
        self.assertEqual(table1.source_label(teapots),
                         "generator \\texttt{teapots, seed 10, from teapot}")
        self.assertEqual(table1.source_label({"kind": "package", "package": "torcs-data"}),
                         "Debian \\texttt{torcs-data}")

    def test_licence_stops_before_its_parenthesis(self):
        self.assertEqual(table1.licence_label(
            "CC0-1.0 (libcgal-demo's /usr/share/doc/libcgal-demo links to debian/copyright)"),
            "CC0-1.0")
        self.assertEqual(table1.licence_label(
            "no licence field in the npm package; Stanford terms (free for research use)"),
            "no licence field in the npm package; Stanford terms")
        self.assertEqual(table1.licence_label("Public Domain"), "Public Domain")
        self.assertEqual(table1.licence_label(None), "")

    def test_one_row_per_obtained_scene_in_manifest_order(self):
        text, _ = self.generate()
        rows = self.body_lines(text)
        self.assertEqual([r.split(" & ")[0] for r in rows],
                         ["1", "2", "4", "5", "6"])
        self.assertNotIn("not\\_fetched", text)

    def test_row_contents(self):
        text, _ = self.generate()
        rows = {r.split(" & ")[1]: r.split(" & ") for r in
                self.body_lines(text)}
        bunny = rows["bunny"]
        self.assertEqual(bunny[2:6], ["---", "69,666", "69,666",
                                      "\\checkmark"])
        self.assertEqual(bunny[6], "Debian \\\\")
        arm = rows["armadillo"]
        self.assertEqual(arm[2], "2 Armadillo")
        self.assertEqual(arm[6], "npm \\\\")
        # report_name missing: taken from the report's own table
        city = rows["city\\_gen"]
        self.assertEqual(city[2], "5 city")
        self.assertEqual(city[3:6], ["68,010", "68,000", "+10"])
        suz = rows["suzanne"]
        self.assertEqual(suz[3:7], ["968", "---", "---", "Blender \\\\"])
        # The packages and licences are in the appendix's table.
        with open(os.path.join(self.out, "table1_sources.tex"), encoding="utf-8") as f:
            sources = {r.split(" & ")[1]: r.split(" & ") for r in self.body_lines(f.read())}
        self.assertEqual(sources["bunny"][2:], ["Debian \\texttt{fixture-meshes}", "CC0 \\& free \\\\"])
        self.assertEqual(sources["armadillo"][2:],
                         ["npm \\texttt{fixture\\_armadillo}", "Stanford 100\\% research \\\\"])
        self.assertEqual(sources["city\\_gen"][3], "MIT \\#2 \\\\")

    def test_failure_is_a_row_with_a_note(self):
        text, macros = self.generate()
        rows = {r.split(" & ")[1]: r.split(" & ") for r in
                self.body_lines(text)}
        broken = rows["broken\\_scene"]
        self.assertEqual(broken[3:6], ["failed$^{1}$", "10", "---"])
        # last line of the error, escaped
        self.assertIn("$^{1}$ broken\\_scene failed to load: "
                      "scene\\_info: bad\\_file \\#3 at 100\\%", text)
        self.assertNotIn("warning: x", text)
        self.assertEqual(macros["NumScenesFailed"], (1, False))

    def test_negative_difference(self):
        recs = [testdata.record("bunny", 69600)]
        results, manifest = testdata.write_fixture(
            os.path.join(self.tmp.name, "neg"), records=recs)
        ctx = context.Context(results, manifest, self.out)
        table1.generate(ctx)
        with open(os.path.join(self.out, "table1.tex"), encoding="utf-8") as f:
            self.assertIn("69,600 & 69,666 & $-$66 &", f.read())

    def test_macros(self):
        _, macros = self.generate()
        self.assertEqual(macros["NumScenes"], (4, False))
        self.assertEqual(macros["NumScenesTried"], (5, False))
        self.assertEqual(macros["TotalTriangles"],
                         ("484,588", False))  # 69666+345944+68010+968
        self.assertEqual(macros["LargestScene"], ("armadillo", False))
        self.assertEqual(macros["LargestSceneTriangles"][0], "345,944")
        self.assertEqual(macros["NumReportScenesCovered"], (3, False))
        self.assertEqual(macros["NumReportScenes"], (18, False))
        self.assertEqual(macros["NumScenesWithExpected"], (3, False))
        self.assertEqual(macros["NumScenesMatchExpected"], (2, False))
        self.assertEqual(macros["Profile"], ("quick", False))

    def test_booktabs_shape(self):
        text, _ = self.generate()
        for token in ("\\toprule", "\\midrule", "\\bottomrule",
                      "\\label{tab:scenes}", "\\caption{"):
            self.assertIn(token, text)
        # every body row has 7 cells
        for row in self.body_lines(text):
            self.assertEqual(len(row.split(" & ")), 7, row)

    def test_no_results_is_an_error(self):
        os.unlink(os.path.join(self.results, "scenes.jsonl"))
        with self.assertRaises(RuntimeError):
            table1.generate(self.ctx)

    def test_scene_missing_from_manifest_comes_last(self):
        recs = testdata.RECORDS + [testdata.record("stray_scene", 5)]
        results, manifest = testdata.write_fixture(
            os.path.join(self.tmp.name, "stray"), records=recs)
        ctx = context.Context(results, manifest, self.out)
        table1.generate(ctx)
        with open(os.path.join(self.out, "table1.tex"), encoding="utf-8") as f:
            rows = self.body_lines(f.read())
        self.assertTrue(rows[-1].startswith("--- & stray\\_scene & --- & 5 &"))


class ManifestShapeTest(unittest.TestCase):
    def test_list_and_dict(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "m.json")
            scenes = [{"name": "a"}, {"name": "b", "number": 7}]
            for data in (scenes, {"scenes": scenes}):
                with open(p, "w") as f:
                    json.dump(data, f)
                got = inputs.load_manifest(p)
                self.assertEqual([(s["name"], s["number"]) for s in got],
                                 [("a", 1), ("b", 7)])

    def test_bad_manifests(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "m.json")
            for data in ({"nope": []}, [{"name": "a"}, {"name": "a"}],
                         [{"kind": "x"}]):
                with open(p, "w") as f:
                    json.dump(data, f)
                with self.assertRaises(ValueError):
                    inputs.load_manifest(p)

    def test_the_analysis_refuses_a_record_cut_short(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "kdtree.jsonl"), "w") as f:
                f.write('{"scene": "a"}\n{"scene": ')
            ctx = context.Context(d, os.path.join(d, "none.json"), d)
            with self.assertRaisesRegex(ValueError, r"kdtree\.jsonl:2: .*cut short"):
                ctx.results("kdtree.jsonl")


if __name__ == "__main__":
    unittest.main()
