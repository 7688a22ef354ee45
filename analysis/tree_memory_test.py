"""The tree-memory macros on kdrt records: tree_bytes and N_TP per triangle,
per preset, over the scenes with a record of it."""

import unittest

from analysis import testdata
from analysis import tree_memory


class TreeMemoryTest(testdata.KdtreeFixtureTest):
    def append(self, scene, preset, **over):
        testdata.write_kdtree(self.ctx.results_dir, [testdata.kdrt_record(scene, preset, **over)])

    def test_bytes_and_references_per_triangle(self):
        # n_tri 1000 (alpha), 2000 (beta), 4000 (gamma).
        self.append("alpha", "sah-packet", n_tri=1000, tree_bytes=60000, N_TP=1500,
                    embree=testdata.embree(bvh_bytes=30000))
        self.append("beta", "sah-packet", n_tri=2000, tree_bytes=160000, N_TP=4000,
                    embree=testdata.embree(bvh_bytes=100000))
        self.append("gamma", "sah-packet", n_tri=4000, tree_bytes=256000, N_TP=7200)
        self.append("alpha", "sah-packet-binned", n_tri=1000, tree_bytes=70000)
        macros = tree_memory.generate(self.ctx)
        self.assertEqual(macros["TreeBytesFastScenes"][0], "3")
        self.assertEqual(macros["TreeBytesFastMedian"][0], "64")  # 60, 80, 64
        self.assertEqual(macros["TreeBytesFastMin"][0], "60")
        self.assertEqual(macros["TreeBytesFastMax"][0], "80")
        self.assertEqual(macros["TreeBytesFastAtMostTarget"][0], "2")  # 60 and 64
        self.assertEqual(macros["TreeRefsFastMedian"][0], "1.80")  # 1.5, 2.0, 1.8
        self.assertEqual(macros["TreeBytesBinnedMedian"][0], "70")
        # The fixture's clipping-pruning: tree_bytes 4000 over n_tri 1000.
        self.assertEqual(macros["TreeBytesReportMedian"][0], "4")
        self.assertEqual(macros["TreeBytesTarget"][0], "64")
        # Embree's BVH where the record has it (gamma's fixture has none):
        # 30 and 50 bytes a triangle; ours over its 2.0 and 1.6.
        self.assertEqual(macros["TreeBytesEmbreeScenes"][0], "2")
        self.assertEqual(macros["TreeBytesEmbreeMedian"][0], "40")
        self.assertEqual(macros["TreeBytesEmbreeMin"][0], "30")
        self.assertEqual(macros["TreeBytesEmbreeMax"][0], "50")
        self.assertEqual(macros["TreeBytesOverEmbreeMedian"][0], "1.8")
        self.assertEqual(macros["TreeBytesOverEmbreeMin"][0], "1.6")
        self.assertEqual(macros["TreeBytesOverEmbreeMax"][0], "2.0")
        self.assertEqual(set(macros), set(tree_memory.MACROS))
        # The table: a row per sah-packet scene, Embree's bytes where present.
        with open(self.ctx.path("tree_memory.tex")) as f:
            text = f.read()
        self.assertIn("alpha & 1,000 & 1.50 & 60 & 30 & 2.00", text)
        self.assertIn("beta & 2,000 & 2.00 & 80 & 50 & 1.60", text)
        self.assertIn("gamma & 4,000 & 1.80 & 64 & --- & ---", text)

    def test_the_bytes_the_best_mode_reads(self):
        import pandas as pd
        new = {"bvh_bytes": 100, "bvh_packet_bytes": 400, "tree_bytes": 900}
        self.assertEqual(tree_memory.best_mode_bytes(new), 500.0)
        self.assertEqual(tree_memory.best_mode_bytes(pd.Series(new)), 500.0)
        # An empty BVH's packets are its bytes too, not a reason for the tree's.
        self.assertEqual(tree_memory.best_mode_bytes(dict(new, bvh_packet_bytes=0)), 100.0)
        # Before its own packets (no field, or NaN in a frame): its nodes and the tree.
        old = {"bvh_bytes": 100, "tree_bytes": 900}
        self.assertEqual(tree_memory.best_mode_bytes(old), 1000.0)
        self.assertEqual(tree_memory.best_mode_bytes(
            pd.Series(dict(old, bvh_packet_bytes=float("nan")))), 1000.0)
        self.assertIsNone(tree_memory.best_mode_bytes({"tree_bytes": 900}))
        self.assertIsNone(tree_memory.best_mode_bytes({"bvh_bytes": 100}))

    def test_no_records_of_a_preset_give_dashes(self):
        macros = tree_memory.generate(self.ctx)
        self.assertEqual(macros["TreeBytesFastScenes"][0], "0")
        self.assertEqual(macros["TreeBytesFastMedian"][0], "---")
        self.assertEqual(macros["TreeRefsFastMedian"][0], "---")
        self.assertEqual(macros["TreeBytesEmbreeScenes"][0], "0")
        self.assertEqual(macros["TreeBytesOverEmbreeMedian"][0], "---")
        with open(self.ctx.path("tree_memory.tex")) as f:
            self.assertIn("no records of sah-packet", f.read())


if __name__ == "__main__":
    unittest.main()
