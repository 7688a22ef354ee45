"""The table of what the kd-tree's structure costs, on kdrt records of the
real shape."""

import unittest

from analysis import embree_structure
from analysis import testdata


class EmbreeStructureTest(testdata.KdtreeFixtureTest):
    def append(self, scene, n_tri, tri=None, variant="sah-packet", packet_bytes=None):
        fast = testdata.fast_render([1.1, 1.2, 1.3], best=[0.9, 0.92, 0.94],
                                    single=[0.85, 0.9, 0.8], tri=tri)
        fast["single_bvh"]["bytes"] = 7 * n_tri  # the BVH over the leaves
        # Its own leaf packets (since session 47); none in older records.
        fast["single_bvh"].pop("packet_bytes")
        if packet_bytes is not None:
            fast["single_bvh"]["packet_bytes"] = packet_bytes
        testdata.write_kdtree(self.ctx.results_dir, [testdata.kdrt_record(
            scene, variant, n_tri=n_tri, T_R=0.3, tree_bytes=80 * n_tri,
            embree=testdata.embree(0.2, [0.7, 0.8, 0.9], bvh_bytes=64 * n_tri),
            fast_render=fast)])

    def test_the_baseline_beside_our_tree_per_scene(self):
        self.append("alpha", 70000, tri=([0.8, 0.95, 0.9], [1.0, 1.02, 0.98], 50 * 70000))
        self.append("beta", 60000, tri=([0.7] * 3, [0.9, 0.96, 0.93], 56 * 60000))
        self.append("gamma", 60000)  # made before kdrt timed the baseline: left out
        self.append("delta", 60000, tri=([1.0] * 3, [1.2] * 3, 1), variant="sah-packet-binned")
        macros = embree_structure.generate(self.ctx)
        self.assertEqual(macros["EmbreeTriBestScenes"][0], "2")
        self.assertEqual(macros["EmbreeTriBestRatioMedian"][0], "0.97")
        self.assertEqual(macros["EmbreeTriBestBigAtLeastOne"][0], "1")
        self.assertEqual(macros["EmbreeTriSingleRatioMedian"][0], "0.80")
        # Our tree's best mode over the same two scenes.
        self.assertEqual(macros["EmbreeTriKdBestScenes"][0], "2")
        self.assertEqual(macros["EmbreeTriKdBestRatioMedian"][0], "0.92")
        self.assertEqual((macros["EmbreeTriBytesMin"][0], macros["EmbreeTriBytesMax"][0]),
                         ("50", "56"))
        # alpha 1.00 / 0.92, beta 0.93 / 0.92: a median of 1.05.
        self.assertEqual(macros["EmbreeTriClause"][0][:100],
                         "Per scene, the baseline's best mode is 1.05 times as fast as our tree's "
                         "at the median (1.01 to 1.09 ")
        self.assertIn("most of what our best mode lacks is the kd-tree's structure",
                      macros["EmbreeTriClause"][0])
        table = self.read("embree_structure.tex")
        self.assertIn("alpha & 70,000 & 0.92 {\\scriptsize (0.90--0.94)} & "
                      "1.00 {\\scriptsize (0.98--1.02)} & 0.85 & 0.90 & 87 & 50 & 64", table)
        self.assertNotIn("gamma", table)
        self.assertNotIn("delta", table)

    def test_our_bytes_are_the_bvh_and_its_own_packets(self):
        # Since session 47 the BVH reads its own leaf packets, not the tree's.
        self.append("alpha", 70000, tri=([0.8] * 3, [1.0] * 3, 50 * 70000),
                    packet_bytes=60 * 70000)
        embree_structure.generate(self.ctx)
        self.assertIn("0.85 & 0.80 & 67 & 50 & 64", self.read("embree_structure.tex"))

    def test_no_run_with_the_baseline(self):
        self.append("alpha", 70000)
        macros = embree_structure.generate(self.ctx)
        self.assertEqual(macros["EmbreeTriBestScenes"][0], "0")
        self.assertEqual(macros["EmbreeTriBestRatioMedian"][0], "---")
        self.assertEqual(macros["EmbreeTriBytesMin"][0], "---")
        self.assertIn("no runs with the baseline", self.read("embree_structure.tex"))
        self.assertEqual(macros["EmbreeTriClause"][0],
                         "No run timed the baseline beside our tree's best mode.")

    def test_the_conclusion_follows_the_numbers(self):
        def row(kd, tri):
            return {"kd_best": (kd, kd, kd), "tri_best": (tri, tri, tri)}
        self.assertIn("not what holds", embree_structure.conclusion([row(1.0, 0.9)]))
        self.assertIn("not shown to cost", embree_structure.conclusion([row(1.0, 1.01)]))
        self.assertIn("is the kd-tree's structure",
                      embree_structure.conclusion([row(0.9, 1.0)]))


if __name__ == "__main__":
    unittest.main()
