"""kdrt on hostile inputs, one row per class of issue 24: each either renders
(exit 0, a record that is valid JSON) or is refused (exit 1) with a message
naming the input and the reason; never a crash (a signal), a hang (each run
has a time limit) or a silent wrong result. The run's peak memory is the
test's own concern only through the memory budget rows (refused before
anything large is allocated).
"""

import gzip
import json
import os
import resource
import subprocess
import tempfile
import threading
import unittest

RUNFILES = os.path.join(os.environ.get("TEST_SRCDIR", ""), os.environ.get("TEST_WORKSPACE", ""))
KDRT = os.path.join(RUNFILES, "cc", "tools", "kdrt")
OCTAHEDRON = os.path.join(RUNFILES, "cc", "tools", "testdata", "octahedron.obj")
CAMERA = "camera { position 0.5 2 6 look_at 0 -0.5 0 }\n"
QUAD = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"


def scaled_quad(scale, offset=0.0):
    return "".join("v %r %r 0\n" % (offset + x * scale, offset + y * scale)
                   for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))) + "f 1 2 3 4\n"


class HostileInputsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        os.environ["KDTREE_TIMING_LOCK"] = os.path.join(self.dir, "timing.lock")

    def tearDown(self):
        self.tmp.cleanup()

    def file(self, name, text, binary=False):
        path = os.path.join(self.dir, name)
        with open(path, "wb" if binary else "w") as f:
            f.write(text)
        return path

    def kdrt(self, *args, pipe=None):
        """(exit code, stdout, stderr) of kdrt with the small defaults; `pipe`:
        (name, bytes) written to a named pipe created first."""
        writer = None
        if pipe is not None:
            path = os.path.join(self.dir, pipe[0])
            os.mkfifo(path)
            writer = threading.Thread(target=lambda: open(path, "wb").write(pipe[1]))
            writer.start()
        proc = subprocess.run([KDRT, "--repeats=1", "--cache_dir="] + list(args),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              universal_newlines=True, timeout=120, check=False)
        if writer is not None:
            writer.join(timeout=10)
        self.assertGreaterEqual(proc.returncode, 0, "killed by a signal: " + proc.stderr[-500:])
        return proc.returncode, proc.stdout, proc.stderr

    def renders(self, *args, **kw):
        code, out, err = self.kdrt(*args, **kw)
        self.assertEqual(code, 0, err[-1000:])
        return json.loads(out.strip().splitlines()[-1])  # valid JSON

    def refused(self, why, *args, **kw):
        code, _, err = self.kdrt(*args, **kw)
        self.assertEqual(code, 1, err[-1000:])
        self.assertIn(why, err)
        return err

    def test_files_that_are_not_regular_files(self):
        with open(OCTAHEDRON, "rb") as f:
            octahedron = f.read()
        rec = self.renders("--mesh=" + os.path.join(self.dir, "pipe.obj"),
                           pipe=("pipe.obj", octahedron))
        self.assertEqual(rec["n_tri"], 10)
        rec = self.renders("--mesh=" + os.path.join(self.dir, "noext"), pipe=("noext", octahedron))
        self.assertEqual(rec["n_tri"], 10)
        self.refused("%s: the mesh file is a directory" % self.dir, "--mesh=" + self.dir)
        self.refused("/dev/zero: the mesh file is a device", "--mesh=/dev/zero")
        self.refused("the environment file is a directory", "--mesh=" + OCTAHEDRON, "--env=" + self.dir)
        self.refused("the view file is a directory", "--mesh=" + OCTAHEDRON, "--view=" + self.dir)

    def test_unbounded_memory(self):
        bomb = self.file("bomb.obj.gz", gzip.compress(b"\n" * (8 << 20)), binary=True)
        self.refused("inflates to more than the input budget of 1000000 bytes",
                     "--mesh=" + bomb, "--max_mesh_bytes=1000000")
        big = self.file("big.obj", QUAD + "#" * 2000)
        self.refused("more than the input budget of 1000 bytes", "--mesh=" + big,
                     "--max_mesh_bytes=1000")
        huge = self.file("huge.view", CAMERA + "resolution 16384 16384\nlight { position 0 5 0 }\n")
        self.refused("rendering 16384x16384 with 1 lights and recording every ray needs about",
                     "--mesh=" + OCTAHEDRON, "--view=" + huge, "--memory_budget_gb=8")
        lights = self.file("lights.view", CAMERA + "resolution 800 800\n"
                           + "light { position 0 5 0 }\n" * 10000)
        self.refused("more than the memory budget of 8.0 GB", "--mesh=" + OCTAHEDRON,
                     "--view=" + lights, "--memory_budget_gb=8")
        # A spatial-median tree 60 deep on a small mesh grows without bound: the
        # build stops at what the budget leaves for it, well under 1 GB here.
        self.refused("kd-tree would need more than the 0.23 GB it may use", "--mesh=" + OCTAHEDRON,
                     "--preset=median-16-2", "--max_depth=60", "--max_leaf_size=1",
                     "--memory_budget_gb=0.5")
        peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        self.assertLess(peak_kb, 1 << 20, "a refused run's peak memory")

    def test_numeric_extremes(self):
        tiny = self.file("tiny.obj", scaled_quad(1e-30))
        self.refused("would underflow", "--mesh=" + tiny)
        vast = self.file("vast.obj", scaled_quad(1e25))
        self.refused("would overflow", "--mesh=" + vast)
        far = self.file("far.obj", scaled_quad(1e5, offset=1e12))
        self.refused("too few bits", "--mesh=" + far)
        # The offset sphere of the adversarial suite's scale, at 1e5: renders.
        rec = self.renders("--mesh=" + self.file("moved.obj", scaled_quad(10.0, offset=1e5)))
        self.assertGreater(rec["P_hit"], 0)

    def test_nothing_dropped_or_wrapped_in_silence(self):
        soup = QUAD + "v 1e31 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 0\nv 1 1 1\nv 2 2 2\nf -3 -2 -1\n"
        rec = self.renders("--mesh=" + self.file("dropped.obj", soup))
        self.assertEqual(rec["dropped_at_load"],
                         {"nonfinite": 1, "degenerate": 1, "point_line_faces": 0})
        many = self.file("many.view", CAMERA + "resolution 8 8\n" + "light { position 0 5 0 }\n" * 65536)
        self.refused("at most 65535 lights", "--mesh=" + OCTAHEDRON, "--view=" + many)


if __name__ == "__main__":
    unittest.main()
