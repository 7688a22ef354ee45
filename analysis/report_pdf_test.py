"""The report's PDF, built from a fixture with latexmk, has no table below
80 % of the body font and no generated figure shrunk below 80 % of its size
(analysis/table_scale.py, issue 25). The fixture has the scenes of
testdata.MANIFEST, every variant of the matrix with Embree on the timed ones,
and a cost image; experiments/reproduce.sh runs the same check on real
results. Needs TeX Live and latexmk (experiments/setup.sh installs them)."""

import gzip
import io
import os
import shutil
import subprocess
import tempfile
import unittest
from contextlib import redirect_stdout

import numpy as np

from analysis import kdtree_results as kr
from analysis import make_all
from analysis import table_scale
from analysis import testdata

HERE = os.path.dirname(os.path.abspath(__file__))
MAIN_TEX = os.path.join(os.path.dirname(HERE), "report", "main.tex")
SCENES = ("bunny", "armadillo", "city_gen")


def cost_image():
    a = np.zeros((80, 80, 3, 3), dtype="<u4")
    a[:, :, 0, :] = (1, 20, 10)
    a[:40, :, 1, :] = (1, 30, 8)
    return a


def write_results(root):
    results, manifest = testdata.write_fixture(root)
    timed = kr.load_matrix()["embree_timed_variants"]
    recs = []
    for scene in SCENES:
        for v in kr.VARIANTS + kr.BEYOND:
            emb = (testdata.embree(0.2, [0.6, 0.7, 0.8]) if v in timed
                   else testdata.embree_untimed())
            over = {"embree": emb}
            if v == "sah-packet":
                over["fast_render"] = testdata.fast_render([0.9, 1.0, 1.1],
                                                           best=[0.7, 0.75, 0.8],
                                                           single=[0.7, 0.8, 0.9])
            if scene == "bunny":
                a = cost_image()
                over["traversal"] = testdata.cost_traversal(a)
                costs = os.path.join(root, "costs")
                os.makedirs(costs, exist_ok=True)
                with gzip.open(os.path.join(costs, "bunny_%s.npy.gz" % v), "wb") as f:
                    np.save(f, a)
            recs.append(testdata.kdrt_record(scene, v, **over))
    testdata.write_kdtree(results, recs)
    return results, manifest


class ReportPdfTest(unittest.TestCase):
    def test_no_table_or_figure_below_80_percent(self):
        if shutil.which("latexmk") is None:
            self.fail("latexmk is not installed (bash experiments/setup.sh installs it)")
        with tempfile.TemporaryDirectory() as tmp:
            results, manifest = write_results(tmp)
            report = os.path.join(tmp, "report")
            os.makedirs(report)
            shutil.copy(MAIN_TEX, report)
            make_all.make_all(results, manifest, os.path.join(report, "generated"))
            proc = subprocess.run(
                ["latexmk", "-pdf", "-cd", "-interaction=nonstopmode", "-halt-on-error",
                 "-output-directory=build", os.path.join(report, "main.tex")],
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                env=dict(os.environ, HOME=tmp))
            self.assertEqual(proc.returncode, 0, proc.stdout[-3000:])
            log = os.path.join(report, "build", "main.log")
            with open(log, errors="replace") as f:
                text = f.read()
            self.assertGreater(len(table_scale.parse(text)), 15)
            self.assertIn("cost/bunny.png", [f for f, _ in table_scale.parse_figures(text)])
            out = io.StringIO()
            with redirect_stdout(out):
                code = table_scale.main([log, "--strict", "--body_pt", "11"])
            self.assertEqual(code, 0, out.getvalue())


if __name__ == "__main__":
    unittest.main()
