"""bench_classes: the ray-class table from render_bench records."""
import unittest

import bench_classes


def record(scene, n_tri, classes, threads=1):
    return {"scene": scene, "n_tri": n_tri, "preset": "sah-packet", "threads": threads,
            "ray_classes": {"rounds": 2, "classes": classes}}


class ClassesSummaryTest(unittest.TestCase):
    def test_rows_per_class_with_paired_ratios_and_shares(self):
        classes = {
            "camera_no_node": {"rays": 300, "ns_runs": {"kd_origin": [8.0, 10.0],
                                                         "embree": [10.0, 10.0]}},
            "shadow": {"rays": 100, "ns_runs": {"kd_origin": [100.0, 50.0],
                                                 "embree": [50.0, 50.0]}},
        }
        table = bench_classes.classes_summary([record("bunny", 69666, classes),
                                               record("city", 68497, classes)])
        lines = table.splitlines()
        # Over the scenes first: each class's median share and ratio.
        self.assertEqual(lines[2], "| camera_no_node | kd_origin | 2 | 75 % | 1.12 [1.12..1.12] |")
        self.assertEqual(lines[3], "| shadow | kd_origin | 2 | 25 % | 0.75 [0.75..0.75] |")
        self.assertEqual(lines[4], "")
        rows = [l for l in lines[7:] if l.startswith("| bunny")]
        self.assertEqual(len(rows), 2)
        # 10/8 and 10/10: median 1.125.
        self.assertIn("| bunny | 69,666 | camera_no_node | kd_origin | 300 | 75 % | 9.0 | 10.0 | "
                      "1.12 [1.00..1.25] |", rows[0])
        self.assertIn("| shadow | kd_origin | 100 | 25 % | 75.0 | 50.0 | 0.75 [0.50..1.00] |", rows[1])

    def test_prefers_kd_bvh(self):
        classes = {"camera_hit": {"rays": 4, "ns_runs": {"kd_origin": [4.0], "kd_bvh": [2.0],
                                                         "embree": [1.0]}}}
        lines = bench_classes.classes_summary([record("a", 10, classes)]).splitlines()
        self.assertEqual(lines[2], "| camera_hit | kd_bvh | 1 | 100 % | 0.50 [0.50..0.50] |")

    def test_falls_back_to_kd_and_skips_records_without_classes(self):
        classes = {"camera_hit": {"rays": 4, "ns_runs": {"kd": [2.0], "embree": [1.0]}},
                   "shadow": {"rays": 4, "ns_runs": {"kd": [2.0]}}}  # no Embree: left out
        records = [record("a", 10, classes),
                   {"scene": "b", "n_tri": 5, "preset": "sah-packet", "threads": 1},
                   record("c", 10, classes, threads=2)]
        rows = [l for l in bench_classes.classes_summary(records).splitlines()
                if l.startswith("| a |")]
        self.assertEqual(len(rows), 1)
        self.assertIn("| a | 10 | camera_hit | kd | 4 | 100 % | 2.0 | 1.0 | 0.50 [0.50..0.50] |",
                      rows[0])
        self.assertEqual(bench_classes.classes_summary([records[1]]), "")


if __name__ == "__main__":
    unittest.main()
