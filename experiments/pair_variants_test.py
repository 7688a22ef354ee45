"""pair_variants: the variant's time over the base's, paired per round."""
import io
import json
import os
import sys
import tempfile
import unittest
from contextlib import redirect_stdout

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_variants  # noqa: E402


def record(scene, base, variant, replay=True, mismatches=0):
    tracers = {
        "kd@AVX3": {"T_R_runs": base, "primary_s_runs": [b / 2 for b in base],
                    "secondary_s_runs": [b / 4 for b in base]},
        "kd@AVX3_DL": {"T_R_runs": variant, "primary_s_runs": [v / 2 for v in variant],
                       "secondary_s_runs": [v / 4 for v in variant]},
    }
    if replay:  # kd is a single-ray mode: its replay is "replay"
        tracers["replay"] = {"T_R_runs": [0.0] * len(base),
                             "primary_s_runs": [0.1] * len(base),
                             "secondary_s_runs": [0.0] * len(base)}
    return {"scene": scene, "tracers": tracers,
            "validation": {"variants_vs_kd_mismatches": {"kd@AVX3_DL": mismatches}}}


class PairTest(unittest.TestCase):
    def test_the_variant_over_the_base_per_round(self):
        # Round 2 is slow on both sides: pairing takes it out.
        r = record("bunny", [1.0, 2.0, 1.0], [0.9, 1.8, 0.95])
        p = pair_variants.pair(r, "kd@AVX3", "kd@AVX3_DL")
        self.assertAlmostEqual(p["T_R"][0], 0.9)
        self.assertAlmostEqual(p["T_R"][1], 0.9)
        self.assertAlmostEqual(p["T_R"][2], 0.95)

    def test_a_pass_alone_is_its_tracing_time_less_the_replay(self):
        r = record("bunny", [1.0, 1.0, 1.0], [0.8, 0.8, 0.8])
        self.assertAlmostEqual(pair_variants.pair(r, "kd@AVX3", "kd@AVX3_DL")["camera"][0], 0.8)
        # camera alone: (0.4 - 0.1) / (0.5 - 0.1), the replay's 0.1 taken off both.
        alone = pair_variants.pair(r, "kd@AVX3", "kd@AVX3_DL", alone=True)
        self.assertAlmostEqual(alone["camera"][0], 0.75)
        r = record("bunny", [1.0, 1.0, 1.0], [0.8, 0.8, 0.8], replay=False)
        self.assertIsNone(pair_variants.pair(r, "kd@AVX3", "kd@AVX3_DL", alone=True)["camera"])

    def test_lines_name_the_scene_and_any_mismatch(self):
        out = pair_variants.lines([record("bunny", [1.0], [0.9]),
                                   record("city2", [1.0], [1.0], mismatches=3),
                                   {"scene": "other", "tracers": {}}],
                                  "kd@AVX3", "kd@AVX3_DL")
        self.assertEqual(len(out), 2)
        self.assertTrue(out[0].startswith("bunny"))
        self.assertIn("T_R 0.900 [0.900..0.900]", out[0])
        self.assertIn("MISMATCHES {'kd@AVX3_DL': 3}", out[1])

    def test_main_reads_the_records(self):
        with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
            f.write(json.dumps(record("bunny", [1.0, 1.0], [1.1, 1.1])) + "\n")
        buf = io.StringIO()
        with redirect_stdout(buf):
            self.assertEqual(pair_variants.main(["--base", "kd@AVX3", "--variant", "kd@AVX3_DL",
                                                 "--out", f.name]), 0)
        os.unlink(f.name)
        self.assertIn("T_R 1.100", buf.getvalue())

    def test_main_names_a_line_that_is_not_a_record(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "ab.jsonl")
            with open(path, "w") as f:
                f.write('{"scene": ')
            with self.assertRaises(SystemExit) as e:
                pair_variants.main(["--base", "a", "--variant", "b", "--out", path])
            self.assertRegex(str(e.exception.code), r"pair_variants: .*ab\.jsonl:1: .*cut short")
            with self.assertRaises(SystemExit) as e:
                pair_variants.main(["--base", "a", "--variant", "b", "--out", path + ".none"])
            self.assertIn("no file", str(e.exception.code))


if __name__ == "__main__":
    unittest.main()
