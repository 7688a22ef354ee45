"""experiments/step_times.py on a log of reproduce.sh's shape."""

import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import step_times  # noqa: E402

LOG = """
==> [06:00:05, +0 s] set-up (Debian packages, idempotent)
setup: all 26 packages present
==> [06:00:06, +1 s] fetch scenes (profile quick)
==> [06:00:06, +1 s] build tools
==> [06:00:07, +2 s] load scenes (scene_info)
==> [06:00:09, +4 s] scene 18 in the seed-compatible mode (row18.jsonl)
==> [06:00:10, +5 s] kd-tree matrix: the report's nine variants (quick)
==> [06:04:30, +265 s] robustness: the adversarial suite
==> [06:09:30, +565 s] a step the table does not know
==> [06:09:40, +575 s] analysis (tables, figures, macros)
==> [06:09:45, +580 s] report (LaTeX)
reproduce: report at /x/out/report.pdf (586 s in all)
"""


class StepTimesTest(unittest.TestCase):
    def test_each_step_lasts_until_the_next(self):
        steps, total = step_times.step_seconds(LOG.splitlines())
        self.assertEqual(total, 586)
        self.assertEqual(dict(steps)["kd-tree matrix: the report's nine variants (quick)"], 260)
        self.assertEqual(steps[-1], ("report (LaTeX)", 6))

    def test_an_unfinished_log_drops_its_last_step(self):
        steps, total = step_times.step_seconds(LOG.splitlines()[:8])
        self.assertIsNone(total)
        self.assertEqual(steps[-1][0], "scene 18 in the seed-compatible mode (row18.jsonl)")

    def test_table_groups_rows_and_keeps_unknown_steps(self):
        steps, total = step_times.step_seconds(LOG.splitlines())
        text = step_times.table([("a", steps, total), ("b", steps[:3], None)])
        self.assertIn("| load scenes, scene 18 | 3 s | - |", text)
        self.assertIn("| kd-tree matrix | 4 min 20 s | - |", text)
        self.assertIn("| a step the table does not know | 10 s | - |", text)
        self.assertIn("| analysis and LaTeX | 11 s | - |", text)
        self.assertIn("| **in all** | **9 min 46 s** | (not finished) |", text)


if __name__ == "__main__":
    unittest.main()
