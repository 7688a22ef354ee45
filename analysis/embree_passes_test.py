"""The per-pass table against Embree on kdrt records of the real shape."""

import unittest

from analysis import embree_passes
from analysis import testdata


class EmbreePassesTest(testdata.KdtreeFixtureTest):
    def append(self, scene, n_tri, passes):
        testdata.write_kdtree(self.ctx.results_dir, [testdata.kdrt_record(
            scene, "sah-packet", n_tri=n_tri, T_R=0.3,
            embree=testdata.embree(0.2, [0.7, 0.8, 0.9]),
            fast_render=testdata.fast_render([1.1, 1.2, 1.3], passes=passes))])

    def test_each_pass_is_its_paired_median_with_the_rounds_range(self):
        self.append("alpha", 70000, {"camera_single": [0.8, 0.9, 0.7],
                                     "shadow_single": [0.5, 0.6, 0.55],
                                     "camera_packets": [0.7, 0.74, 0.72],
                                     "shadow_packets": [1.1, 0.9, 1.0]})
        self.append("beta", 60000, {"camera_single": [1.0, 1.0, 1.0],
                                    "shadow_single": [], "camera_packets": [0.5] * 3,
                                    "shadow_packets": [0.8] * 3})
        macros = embree_passes.generate(self.ctx)
        self.assertEqual(macros["EmbreePassCameraSingleMedian"][0], "0.90")
        self.assertEqual(macros["EmbreePassCameraSingleScenes"][0], "2")
        # beta's shadow pass gave no round: alpha's alone.
        self.assertEqual(macros["EmbreePassShadowSingleMedian"][0], "0.55")
        self.assertEqual(macros["EmbreePassShadowSingleScenes"][0], "1")
        self.assertEqual(macros["EmbreePassCameraPacketsMedian"][0], "0.61")
        self.assertEqual(macros["EmbreePassShadowPacketsMedian"][0], "0.90")
        self.assertEqual(macros["EmbreePassWeakestClause"][0],
                         "it is furthest behind on shadow rays one at a time (0.55 of Embree's speed)")
        table = self.read("embree_passes.tex")
        self.assertIn("0.80 {\\scriptsize (0.70--0.90)}", table)
        self.assertIn("0.55 {\\scriptsize (0.50--0.60)}", table)

    def test_a_run_without_passes_gives_dashes(self):
        testdata.write_kdtree(self.ctx.results_dir, [testdata.kdrt_record(
            "alpha", "sah-packet", T_R=0.3, embree=testdata.embree(0.2, [0.8]),
            fast_render=testdata.fast_render([1.2]))])
        macros = embree_passes.generate(self.ctx)
        self.assertEqual(macros["EmbreePassCameraSingleMedian"][0], "---")
        self.assertEqual(macros["EmbreePassCameraSingleScenes"][0], "0")
        self.assertEqual(macros["EmbreePassWeakestClause"][0], "no run recorded its passes apart")
        self.assertIn("alpha", self.read("embree_passes.tex"))


if __name__ == "__main__":
    unittest.main()
