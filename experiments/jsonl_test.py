"""The results files' reader and appender (experiments/jsonl.py)."""

import io
import os
import sys
import tempfile
import unittest
from contextlib import redirect_stderr

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import jsonl  # noqa: E402


class JsonlTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "r.jsonl")

    def tearDown(self):
        self.dir.cleanup()

    def write(self, data):
        with open(self.path, "wb") as f:
            f.write(data)

    def test_a_missing_file_has_no_records(self):
        self.assertEqual(jsonl.read(self.path), [])

    def test_records_in_order_blank_lines_skipped(self):
        self.write(b'{"a": 1}\n\n  \n{"a": 2}\n')
        self.assertEqual(jsonl.read(self.path), [{"a": 1}, {"a": 2}])

    def test_a_line_that_is_not_a_record_names_file_and_line(self):
        for data, line, why in ((b'{"a": 1}\n\n{oops\n', 3, "cut short"),
                                (b'{"a": 1}\n{"a": "\xff"}\n', 2, "cut short"),
                                (b'{"a": 1}\n[1, 2]\n', 2, "a JSON list, not a record"),
                                (b'7\n', 1, "a JSON int, not a record")):
            self.write(data)
            with self.assertRaisesRegex(ValueError, r"r\.jsonl:%d: .*%s" % (line, why)):
                jsonl.read(self.path)

    def test_on_bad_passes_a_line_over(self):
        self.write(b'{"a": 1}\n{"a": 2\n{"a": "\xff"}\n{"a": 3}\n')
        bad = []
        records = jsonl.read(self.path, on_bad=lambda p, n: bad.append((p, n)))
        self.assertEqual(records, [{"a": 1}, {"a": 3}])
        self.assertEqual(bad, [(self.path, 2), (self.path, 3)])

    def test_read_resuming_warns_and_passes_over(self):
        self.write(b'{"a": 1}\n{"a": ')
        err = io.StringIO()
        with redirect_stderr(err):
            self.assertEqual(jsonl.read_resuming(self.path, "resume"), [{"a": 1}])
        self.assertIn("resume: %s:2 is not a JSON record" % self.path, err.getvalue())
        self.assertIn("its job runs again", err.getvalue())

    def test_append_sorts_keys_and_starts_a_line_after_one_cut_short(self):
        jsonl.append(self.path, {"b": 1, "a": 2})
        with open(self.path, "a") as f:
            f.write('{"a": ')  # a run killed while appending
        self.assertTrue(jsonl.ends_cut_short(self.path))
        jsonl.append(self.path, {"c": 3})
        with open(self.path) as f:
            self.assertEqual(f.read(), '{"a": 2, "b": 1}\n{"a": \n{"c": 3}\n')
        self.assertFalse(jsonl.ends_cut_short(self.path))
        self.assertEqual(jsonl.read(self.path, on_bad=lambda p, n: None),
                         [{"a": 2, "b": 1}, {"c": 3}])


if __name__ == "__main__":
    unittest.main()
