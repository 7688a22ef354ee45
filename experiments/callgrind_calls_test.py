"""callgrind_calls.py on a small callgrind file: compressed names, calls
summed over call sites, inclusive cost per call, and its exits."""

import contextlib
import io
import os
import tempfile
import unittest

import callgrind_calls

# Two callers call trace(); trace calls leaf. Names are compressed as
# callgrind writes them: "(id) name" the first time, "(id)" after.
PROFILE = """# callgrind format
version: 1
events: Ir Bc
fn=(1) main
0 10
cfn=(2) kdtree::Tracer::Occluded(kdtree::Ray const&) const
calls=2 0
0 150
fn=(3) caller2
0 5
cfn=(2)
calls=1 0
0 50
fn=(2)
0 170
cfn=(4) leaf
calls=4 0
+1 30
"""


class CallgrindCallsTest(unittest.TestCase):
    def test_calls_and_inclusive_cost(self):
        table = callgrind_calls.calls_per_function(io.StringIO(PROFILE))
        self.assertEqual(table["kdtree::Tracer::Occluded(kdtree::Ray const&) const"], (3, 200))
        self.assertEqual(table["leaf"], (4, 30))

    def test_main_prints_per_call(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "p.cg")
            with open(path, "w") as f:
                f.write(PROFILE)
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                self.assertEqual(callgrind_calls.main([path, r"Tracer::Occluded\("]), 0)
            self.assertIn("3 calls", out.getvalue())
            self.assertIn("66.7 Ir/call", out.getvalue())
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                self.assertEqual(callgrind_calls.main([path, "nothing"]), 1)
                self.assertEqual(callgrind_calls.main([os.path.join(d, "absent"), "x"]), 2)
            self.assertIn("absent", err.getvalue())


    def test_positions_and_event_order(self):
        # --dump-instr=yes writes "instr line" positions; Ir need not come first.
        profile = PROFILE.replace("events: Ir Bc", "positions: instr line\nevents: Bc Ir")
        profile = profile.replace("0 150", "0x10 0 1 150").replace("0 50", "0x20 0 1 50")
        profile = profile.replace("+1 30", "+4 +1 2 30")
        table = callgrind_calls.calls_per_function(io.StringIO(profile))
        self.assertEqual(table["kdtree::Tracer::Occluded(kdtree::Ray const&) const"], (3, 200))
        self.assertEqual(table["leaf"], (4, 30))


if __name__ == "__main__":
    unittest.main()
