"""analysis/gallery.py on a fixture: two scenes with images, one without."""

import json
import os
import tempfile
import unittest

from PIL import Image

from analysis import context
from analysis import gallery
from analysis import testdata


class GalleryTest(unittest.TestCase):
    def test_one_thumbnail_per_scene_with_an_image(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = os.path.join(tmp, "out", "results")
            images = os.path.join(tmp, "out", "images")
            out = os.path.join(tmp, "gen")
            for d in (results, images, out):
                os.makedirs(d)
            with open(os.path.join(results, "kdtree.jsonl"), "w") as f:
                for scene in ("beta", "alpha", "gamma"):
                    for v in ("pruning", "clipping-pruning"):
                        f.write(json.dumps(testdata.kdrt_record(scene, v))
                                + "\n")
            Image.new("RGB", (800, 800), (200, 10, 10)).save(
                os.path.join(images, "alpha_clipping-pruning.png"))
            Image.new("RGB", (800, 600), (10, 200, 10)).save(
                os.path.join(images, "beta_pruning.png"))
            manifest = os.path.join(tmp, "manifest.json")
            with open(manifest, "w") as f:
                json.dump({"scenes": [{"name": "alpha"}, {"name": "beta"},
                                      {"name": "gamma"}]}, f)
            ctx = context.Context(results, manifest, out)
            macros = gallery.generate(ctx)
            self.assertEqual(macros["GalleryImages"][0], "2")
            with open(os.path.join(out, "gallery.tex")) as f:
                tex = f.read()
            self.assertLess(tex.index("alpha"), tex.index("beta"))
            self.assertNotIn("gamma", tex)
            self.assertIn("fig:gallery", tex)
            with Image.open(os.path.join(out, "gallery", "beta.png")) as im:
                self.assertEqual(im.size, (320, 240))


if __name__ == "__main__":
    unittest.main()
