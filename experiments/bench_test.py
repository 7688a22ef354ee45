"""Tests of experiments/bench.py: scene selection and the summaries."""
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402


def build_record(threads, runs, n=2000000, warmup=None):
    r = {"scene": "big", "n_tri": n, "preset": "binning-32", "threads": threads,
         "T_B": sorted(runs)[len(runs) // 2], "T_B_runs": runs}
    if warmup is not None:
        r["T_B_warmup_runs"] = warmup
    return r


class BenchTest(unittest.TestCase):
    def test_scenes_from_index_filters_by_triangles_and_names(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "index.json")
            with open(path, "w") as f:
                json.dump({"scenes": {"a": {"triangles": 10, "file": "a.ply"},
                                      "b": {"triangles": 2000000, "file": "b.ply"},
                                      "c": {"triangles": 60000, "file": "c.ply"}}}, f)
            self.assertEqual([n for n, _ in bench.scenes_from_index(path, 50000)], ["b", "c"])
            self.assertEqual([n for n, _ in bench.scenes_from_index(path, 0, "c,a,zz")],
                             ["c", "a"])

    def test_build_summary_gives_throughput_and_speed_up(self):
        text = bench.build_summary([build_record(1, [1.0, 0.8, 1.2], warmup=[1.5]),
                                    build_record(2, [0.5, 0.6, 0.4], warmup=[0.7])])
        row = text.splitlines()[2]
        self.assertIn("1.000 s (0.800), 2.00 (2.50)", row)  # median, fastest; Mtri/s
        self.assertIn("0.500 s (0.400), 4.00 (5.00)", row)
        self.assertTrue(row.endswith("| 2.00x | 1.500 s / 0.700 s |"))
        # binning-32's target is 3 Mtri/s: 2.00 misses it.
        self.assertIn("binning-32: 1 thread median 2.00 Mtri/s (2.00 to 2.00), 0 of 1 at 3.0 "
                      "or more; 2 threads 2.00x median (2.00 to 2.00), 1 of 1 at 1.7x or more.",
                      text)

    def test_render_summary_gives_ratio_to_embree(self):
        def rec(threads, kd, embree):
            return {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": threads,
                    "tracers": {"kd": {"T_R_median": kd}, "embree": {"T_R_median": embree}},
                    "validation": {"brute_force_mismatches": 0, "brute_force_checked": 301,
                                   "embree_disagreements": {"total": 3}}}
        one = rec(1, 0.2, 0.1)
        one["ratio_kd_over_embree"] = {"kd": {"median": 0.5, "min": 0.5, "paired": 0.55},
                                       "kd_origin": {"median": 0.6, "min": 0.6, "paired": 0.66},
                                       "kd_packet_origin": {"median": 0.8, "paired": 0.81}}
        one["ratio_kd_over_embree_packet"] = {"kd_packet": {"median": 0.6, "paired": 0.62},
                                              "kd_packet_origin": {"median": 0.7,
                                                                   "paired": 0.69}}
        text = bench.render_summary([one, rec(2, 0.1, 0.05)])
        row = text.splitlines()[2]
        self.assertIn("| 0.50 | 0.55 | - | 0.62 | 0.66 | 0.81, 0.69 | 2.00x | 2.00x |", row)
        self.assertIn("paired kd_packet_origin/Embree over 1 rows: median 0.81, range 0.81 to "
                      "0.81, 1 at 0.7 or more; over Embree's packets: median 0.69, range 0.69 "
                      "to 0.69, 0 at 0.7 or more.", text)
        self.assertIn("paired kd_origin/Embree over 1 rows: median 0.66", text)
        self.assertIn("kd_packet/embree_packet over 1 rows: median 0.62", text)
        self.assertIn("Paired kd/Embree over 1 rows: median 0.55", text)
        self.assertIn("0/301 brute-force mismatches, 3 Embree disagreements", row)
        self.assertIn("median 0.50", text)


if __name__ == "__main__":
    unittest.main()
