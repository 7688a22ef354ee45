"""analysis/record_schema.py and the schema it reads
(cc/tools/kdrt_record.schema.json): the validator; every column of
kdtree_results.FIELDS names a declared field; the fixtures of
analysis/testdata.py are real-shaped; experiments/matrix.json's variants,
titles and groups agree."""

import contextlib
import io
import json
import os
import tempfile
import unittest

from analysis import kdtree_results as kr
from analysis import record_schema as rs
from analysis import testdata


class ValidatorTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.schema = rs.load()

    def errors(self, rec, sections=rs.MATRIX_RECORD):
        return rs.validate(rec, self.schema, sections)

    def test_the_schema_is_well_formed(self):
        self.assertEqual(rs.check_schema(self.schema), [])

    def test_a_fixture_record_is_valid(self):
        self.assertEqual(self.errors(testdata.kdrt_record("a", "clipping")), [])

    def test_missing_wrong_and_undeclared_fields(self):
        rec = testdata.kdrt_record("a", "clipping", T_R="fast", T_R_runs=[1.0],
                                   surprise=1)
        del rec["N_I"]
        rec["config"]["bins"] = 16.5
        rec["provenance"]["extra"] = True
        self.assertEqual(sorted(self.errors(rec)), sorted([
            "T_R: expected number, got str 'fast'", "N_I: missing",
            "config.bins: expected integer, got float 16.5",
            "provenance.extra: not declared in the schema",
            "surprise: not declared in the schema"]))

    def test_null_only_where_declared(self):
        rec = testdata.kdrt_record("a", "clipping", T_B=None, T_B_runs=[None])
        rec["provenance"]["commit"] = None  # nullable
        self.assertEqual(self.errors(rec), ["T_B: null, expected number",
                                            "T_B_runs[0]: null, expected number"])

    def test_a_boolean_is_not_a_number(self):
        rec = testdata.kdrt_record("a", "clipping", n_tri=True)
        self.assertEqual(self.errors(rec), ["n_tri: expected integer, got bool True"])

    def test_optional_members_and_maps(self):
        fast = testdata.fast_render([1.2])
        del fast["paired_ratio"], fast["paired_ratio_runs"]  # without Embree
        rec = testdata.kdrt_record("a", "sah-packet", fast_render=fast)
        rec["timing"]["phases_s"]["counting pass"] = "long"
        self.assertEqual(self.errors(rec),
                         ["timing.phases_s.counting pass: expected number, got str 'long'"])

    def test_every_fast_render_member_of_the_fixtures_is_declared(self):
        fast = testdata.fast_render(
            [1.1, 1.2], best=[0.9, 1.0], robust=([0.8, 0.9], [0.9, 1.0], 3),
            single=[0.8, 0.85],
            passes={p: [0.9, 1.0] for p in ("camera_single", "shadow_single",
                                            "camera_packets", "shadow_packets")},
            tri=([0.85, 0.9], [1.0, 1.1], 4000))
        rec = testdata.kdrt_record("a", "sah-packet", embree=testdata.embree(0.2, [0.7, 0.8]),
                                   fast_render=fast)
        self.assertEqual(self.errors(rec), [])

    def test_the_runner_fields_are_a_section_of_their_own(self):
        rec = testdata.kdrt_record("a", "clipping")
        self.assertEqual(sorted(self.errors(rec, ["kdrt"])),
                         sorted("%s: not declared in the schema" % n
                                for n in self.schema["run_matrix"]))

    def test_command_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "r.jsonl")
            good = testdata.kdrt_record("a", "clipping")
            with open(path, "w") as f:
                f.write(json.dumps(good) + "\n" + json.dumps(dict(good, x=1)) + "\n")
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                self.assertEqual(rs.main(["--sections", "kdrt,run_matrix", path]), 1)
            self.assertEqual(err.getvalue(), "%s:2: x: not declared in the schema\n" % path)


class DeclaredTest(unittest.TestCase):
    """Both sides against the one schema: the analysis reads only declared
    fields, and its fixtures have the shape kdrt and the runners give."""

    @classmethod
    def setUpClass(cls):
        cls.schema = rs.load()

    def test_every_column_is_a_declared_field(self):
        undeclared = [(n, p) for n, p in kr.FIELDS.items()
                      if rs.spec_at(self.schema, p, rs.MATRIX_RECORD) is None]
        self.assertEqual(undeclared, [])

    def test_the_runners_columns_are_declared_as_the_runners(self):
        runner = {p for p in kr.FIELDS.values()
                  if rs.section_of(self.schema, p.split(".")[0]) == "run_matrix"}
        self.assertEqual(runner, {"job", "concurrent_jobs"})

    def test_no_alias(self):
        paths = list(kr.FIELDS.values())
        self.assertEqual(len(paths), len(set(paths)), "two columns, one field")

    def test_the_fixtures_are_real_shaped(self):
        with tempfile.TemporaryDirectory() as tmp:
            results, _ = testdata.kdtree_fixture(tmp)
            with open(os.path.join(results, kr.KDTREE_FILE)) as f:
                recs = [json.loads(line) for line in f]
        recs += [testdata.kdrt_record("a", "sah-packet", embree=testdata.embree(),
                                      fast_render=testdata.fast_render([1.1, 1.3]))]
        for rec in recs:
            sections = rs.MATRIX_RECORD if rec["ok"] else ["run_matrix_failure"]
            self.assertEqual(rs.validate(rec, self.schema, sections), [], rec["preset"])

    def test_the_accuracy_fixture_is_real_shaped(self):
        rec = testdata.kdrt_record(
            "a", "sah-hybrid", added=testdata.accuracy_fields(
                "a", "bins", "bins 32", {"bins": 32, "useClipping": "OFF"}))
        self.assertEqual(rs.validate(rec, self.schema, ["kdrt", "accuracy"]), [])


class MatrixTest(unittest.TestCase):
    """experiments/matrix.json, the one list of the variants."""

    def test_nine_variants_in_three_groups_of_three(self):
        self.assertEqual(len(kr.VARIANTS), 9)
        self.assertEqual([len(g) for g in kr.GROUPS], [3, 3, 3])
        self.assertEqual(sum(kr.GROUPS, []), kr.VARIANTS)
        self.assertEqual(kr.GROUPS[0][0], "median-16-2")
        self.assertEqual(kr.GROUP_NAMES[1], "binned SAH")

    def test_every_variant_and_only_them_has_a_title(self):
        self.assertEqual(sorted(kr.TITLES), sorted(kr.VARIANTS + kr.BEYOND))
        self.assertEqual(kr.TITLES["median-16-2"], "Spatial median 16/2")
        self.assertEqual(kr.TITLES["sah-packet-binned"], "SAH per packet of 4, binned")

    def test_the_runner_reads_the_same_file(self):
        matrix = kr.load_matrix()
        self.assertEqual(matrix["variants"], kr.VARIANTS)
        self.assertEqual(matrix["beyond_variants"], kr.BEYOND)
        self.assertTrue(set(matrix["fast_render_variants"]) <= set(kr.BEYOND + kr.VARIANTS))
        for name in ("test", "quick", "standard", "full"):
            self.assertIn("repeats", matrix["profiles"][name])

    def test_groups_must_cover_the_variants(self):
        matrix = dict(kr.load_matrix(), groups=[{"name": "one", "size": 3}])
        with self.assertRaisesRegex(ValueError, "hold 3 variants, not the 9"):
            kr._groups(matrix)


if __name__ == "__main__":
    unittest.main()
