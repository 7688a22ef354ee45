"""analysis/cost_images.py on a fixture: images that match their records are
drawn, in the report's column order; one from another run is refused."""

import gzip
import json
import os
import tempfile
import unittest

import numpy as np

from analysis import context
from analysis import cost_images
from analysis import testdata


def counts(h, w, primary_inner, shadow_tests):
    """A cost image: one primary ray per pixel, a shadow ray on the left
    half, uniform counts."""
    a = np.zeros((h, w, 3, 3), dtype="<u4")
    a[:, :, 0, 0] = 1
    a[:, :, 0, 1] = primary_inner
    a[:, :, 0, 2] = 3
    a[:, : w // 2, 1, 0] = 1
    a[:, : w // 2, 1, 1] = 2
    a[:, : w // 2, 1, 2] = shadow_tests
    return a


def record(scene, variant, a):
    return testdata.kdrt_record(scene, variant, traversal=testdata.cost_traversal(a))


class CostImagesTest(unittest.TestCase):
    def test_matching_images_drawn_others_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = os.path.join(tmp, "out", "results")
            costs = os.path.join(tmp, "out", "costs")
            out = os.path.join(tmp, "gen")
            for d in (results, costs, out):
                os.makedirs(d)
            images = {("bunny", "pruning"): counts(40, 60, 7, 5),
                      ("bunny", "median-16-2"): counts(40, 60, 4, 30),
                      ("city", "binning-8"): counts(30, 30, 9, 2)}
            with open(os.path.join(results, "kdtree.jsonl"), "w") as f:
                for (scene, v), a in images.items():
                    rec = record(scene, v, a)
                    if scene == "city":  # the file is from another run
                        rec["traversal"]["primary"]["N_TR"] += 1
                    f.write(json.dumps(rec) + "\n")
                    with gzip.open(os.path.join(costs, "%s_%s.npy.gz" % (scene, v)), "wb") as g:
                        np.save(g, a)
            manifest = os.path.join(tmp, "manifest.json")
            with open(manifest, "w") as f:
                json.dump({"scenes": [{"name": "city"}, {"name": "bunny"},
                                      {"name": "alpha"}]}, f)
            ctx = context.Context(results, manifest, out)
            macros = cost_images.generate(ctx)
            self.assertEqual(macros["CostImageScenes"][0], "1")
            self.assertEqual(macros["CostImagesRefused"][0], "1")
            self.assertEqual(macros["CostImageFigures"][0], "Figure~\\ref{fig:cost-bunny}")
            with open(os.path.join(out, "cost_images.tex")) as f:
                tex = f.read()
            self.assertIn("fig:cost-bunny", tex)
            self.assertNotIn("fig:cost-city", tex)
            self.assertIn("2 variants", tex)
            self.assertTrue(os.path.exists(os.path.join(out, "cost", "bunny.png")))
            self.assertNotIn("fig:cost-bunny-seed", tex)

    def test_the_seed_mode_figure_from_the_in_plane_study(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = os.path.join(tmp, "out", "results")
            costs = os.path.join(tmp, "out", "costs")
            out = os.path.join(tmp, "gen")
            for d in (results, os.path.join(costs, "planar"), out):
                os.makedirs(d)
            a = counts(40, 60, 7, 5)
            seed = counts(40, 60, 9, 6)
            with open(os.path.join(results, "kdtree.jsonl"), "w") as f:
                f.write(json.dumps(record("lost-empire", "pruning", a)) + "\n")
            with gzip.open(os.path.join(costs, "lost-empire_pruning.npy.gz"), "wb") as g:
                np.save(g, a)
            with open(os.path.join(results, "planar.jsonl"), "w") as f:
                for mode in ("seed", "default"):
                    rec = record("lost-empire", "pruning", seed)
                    rec.update({"mode": mode, "label": "pruning_" + mode})
                    f.write(json.dumps(rec) + "\n")
            with gzip.open(os.path.join(costs, "planar", "lost-empire_pruning_seed.npy.gz"), "wb") as g:
                np.save(g, seed)
            manifest = os.path.join(tmp, "manifest.json")
            with open(manifest, "w") as f:
                json.dump({"scenes": [{"name": "lost-empire"}]}, f)
            macros = cost_images.generate(context.Context(results, manifest, out))
            self.assertEqual(macros["CostImagesRefused"][0], "0")
            with open(os.path.join(out, "cost_images.tex")) as f:
                tex = f.read()
            self.assertLess(tex.index("fig:cost-lost-empire}"), tex.index("fig:cost-lost-empire-seed"))
            self.assertIn("seed-compatible mode", tex)
            self.assertTrue(os.path.exists(os.path.join(out, "cost", "lost-empire_seed.png")))

    def test_per_ray_averages_blocks_and_leaves_rayless_blocks_empty(self):
        a = counts(800, 800, 6, 10)
        primary = cost_images.per_ray(a, "primary", cost_images.INNER)
        self.assertEqual(primary.shape, (200, 200))
        self.assertTrue(np.all(primary == 6))
        shadow = cost_images.per_ray(a, "shadow", cost_images.TESTS)
        self.assertTrue(np.all(shadow[:, :100] == 10))
        self.assertTrue(np.all(np.isnan(shadow[:, 100:])))
        self.assertEqual(cost_images.mean_per_ray(a, "shadow", cost_images.TESTS), 10)

    def test_titles_in_the_report_order(self):
        self.assertEqual(cost_images.SHOWN[:9], cost_images.kr.VARIANTS)
        self.assertEqual(cost_images.short_title("median-16-2"), "Spatial median\n16/2")
        self.assertEqual(cost_images.short_title("binning-8-driving"), "Binning 8\n(driving axis)")


if __name__ == "__main__":
    unittest.main()
