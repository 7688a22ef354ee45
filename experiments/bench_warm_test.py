"""Tests of experiments/bench_warm.py: the first and second traces of
render_bench --twice, paired per round, and what the other tables make of
the tracers that trace twice."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_tables  # noqa: E402
import bench_warm  # noqa: E402


def runs(primary, secondary):
    return {"T_R_runs": [p + s + 1 for p, s in zip(primary, secondary)],
            "primary_s_runs": primary, "secondary_s_runs": secondary}


def record():
    # Camera pass, single rays, per round: ours first 1.0 and 1.2 (pass less
    # replay 0.5), second 0.6 and 0.6; Embree's first 0.8 and 0.6, second 0.3
    # and 0.3. Shadow pass: Embree's second trace is 0 in round 2 (left out).
    return {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": 1,
            "tracers": {"kd_origin": runs([1.5, 1.7], [1.0, 1.0]),
                        "kd_origin_twice": runs([2.1, 2.3], [1.4, 1.4]),
                        "embree": runs([1.3, 1.1], [0.8, 0.8]),
                        "embree_twice": runs([1.6, 1.4], [1.0, 0.8]),
                        "kd_packet_origin": runs([1.0, 1.0], [1.0, 1.0]),
                        "replay": runs([0.5, 0.5], [0.5, 0.5]),
                        "replay_packet": runs([0.5, 0.5], [0.5, 0.5])}}


class BenchWarmTest(unittest.TestCase):
    def test_first_and_second_traces_paired_per_round(self):
        text = bench_warm.warm_summary([record(), dict(record(), threads=2)])
        rows = [l for l in text.splitlines() if l.startswith("| s |")]
        # Only single rays: the packets were not traced twice.
        self.assertEqual(len(rows), 2)
        # Ours 0.6/1.0 and 0.6/1.2; Embree's 0.3/0.8 and 0.3/0.6; Embree's over
        # ours 0.8/1.0 and 0.6/1.2 first, 0.3/0.6 twice second.
        self.assertEqual(rows[0], "| s | 100,000 | camera, single | 0.55 [0.50..0.60] | "
                         "0.44 [0.38..0.50] | 0.65 [0.50..0.80] | 0.50 [0.50..0.50] |")
        # Shadow: round 1 alone (ours 0.4/0.5, Embree's 0.2/0.3).
        self.assertEqual(rows[1], "| s | 100,000 | shadow, single | 0.80 [0.80..0.80] | "
                         "0.67 [0.67..0.67] | 0.60 [0.60..0.60] | 0.50 [0.50..0.50] |")
        self.assertIn("Camera, single over 1 rows, Embree's over ours: first trace median 0.65 "
                      "(0.65 to 0.65), second trace median 0.50 (0.50 to 0.50).", text)
        # Records without the tracers traced twice: no rows.
        plain = record()
        del plain["tracers"]["kd_origin_twice"]
        self.assertNotIn("| s |", bench_warm.warm_summary([plain]))

    def test_tracers_traced_twice_are_not_among_our_modes(self):
        r = record()
        # Faster than everything: would be our best mode if it counted.
        r["tracers"]["kd_packet_origin_twice"] = runs([0.1, 0.1], [0.1, 0.1])
        text = bench_tables.targets_summary([r])
        plain = record()
        self.assertEqual(text, bench_tables.targets_summary([plain]))


if __name__ == "__main__":
    unittest.main()
