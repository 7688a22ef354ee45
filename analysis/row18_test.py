import json
import os
import tempfile
import unittest

from analysis import context
from analysis import kdtree_results as kr
from analysis import row18


def record(column, mode, **stats):
    base = {f: 0 for f in row18.FIELDS}
    base.update(stats)
    return {"column": column, "mode": mode, "stats": base}


class Row18Test(unittest.TestCase):
    def test_seed_csv_has_nine_columns_in_table_order(self):
        rows = row18.read_seed_rows()
        # The report's nine in the order of experiments/matrix.json.
        self.assertEqual([r["preset"] for r in rows], kr.VARIANTS)
        self.assertEqual(rows[7]["seed_preset"], "pruning-seed")
        self.assertEqual(rows[7]["N_PR"], "9808")

    def test_matches_uses_the_printed_precision(self):
        self.assertTrue(row18.matches(0.0819252, "0.082"))
        self.assertFalse(row18.matches(0.0851789, "0.083"))
        self.assertTrue(row18.matches(7.01646, "7"))
        self.assertTrue(row18.matches(11717, "11717"))
        self.assertIsNone(row18.matches(5, ""))

    def test_table_marks_exact_columns(self):
        rows = row18.read_seed_rows()
        records = []
        for r in rows:
            exact = {f: float(r[f]) for f in row18.FIELDS if r[f]}
            records.append(record(r["column"], "seed", **exact))
            records.append(record(r["column"], "default", **exact))
        with tempfile.TemporaryDirectory() as tmp:
            results = os.path.join(tmp, "results")
            os.makedirs(results)
            with open(os.path.join(results, row18.ROW18_FILE), "w") as f:
                for rec in records:
                    f.write(json.dumps(rec) + "\n")
            ctx = context.Context(results, os.path.join(tmp, "none.json"),
                                  os.path.join(tmp, "out"))
            macros = row18.generate(ctx)
            with open(os.path.join(tmp, "out", "row18.tex")) as f:
                text = f.read()
        self.assertEqual(macros["RowEighteenExactColumns"][0], "9")
        self.assertIn("\\textbf{11,717}", text)
        self.assertIn("9/9", text)  # Spatial median 16/2: all nine printed fields

    def test_missing_results_say_so(self):
        with tempfile.TemporaryDirectory() as tmp:
            ctx = context.Context(tmp, os.path.join(tmp, "none.json"),
                                  os.path.join(tmp, "out"))
            macros = row18.generate(ctx)
            self.assertEqual(sorted(macros), sorted(row18.MACROS))
            with open(os.path.join(tmp, "out", "row18.tex")) as f:
                self.assertIn("not run", f.read())


if __name__ == "__main__":
    unittest.main()
