"""Tests of experiments/bench_merge.py: several render_bench processes'
records of one scene pooled round by round, never across code or scenes."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_merge  # noqa: E402
import bench_tables  # noqa: E402


def record(kd, embree, scene="s", tree="a" * 40, mismatches=0):
    def tracer(runs):
        return {"T_R_runs": runs, "T_R_median": sorted(runs)[len(runs) // 2],
                "T_R_min": min(runs), "primary_s_runs": [t / 2 for t in runs],
                "secondary_s_runs": [t / 4 for t in runs], "first_over_this_paired": 1.0,
                "trace_s_median": 0.1}
    return {"bench": "render", "scene": scene, "n_tri": 100000, "preset": "sah-packet",
            "threads": 1, "repeats": len(kd),
            "provenance": {"commit": "c" * 40, "source_tree": tree},
            "tracers": {"kd_origin": tracer(kd), "embree": tracer(embree)},
            "ratio_kd_over_embree": {"kd_origin": {"paired": 0.0}},
            "ratio_trace_only": {"kd_origin": {"embree": 0.0}},
            "validation": {"brute_force_checked": 10, "brute_force_mismatches": mismatches,
                           "variants_vs_kd_mismatches": {"kd_origin": mismatches}}}


class BenchMergeTest(unittest.TestCase):
    def test_rounds_of_several_processes_pooled_and_paired(self):
        a, b = record([1.0, 2.0], [0.8, 1.0]), record([1.0], [0.9], mismatches=1)
        merged = bench_merge.merge_processes([a, b])
        self.assertEqual(len(merged), 1)
        m = merged[0]
        self.assertEqual(m["processes"], 2)
        self.assertEqual(m["repeats"], 3)
        t = m["tracers"]["kd_origin"]
        self.assertEqual(t["T_R_runs"], [1.0, 2.0, 1.0])
        self.assertEqual(t["primary_s_runs"], [0.5, 1.0, 0.5])
        self.assertEqual(t["T_R_median"], 1.0)
        self.assertNotIn("first_over_this_paired", t)
        # Per round 0.8, 0.5, 0.9: the median 0.8.
        self.assertAlmostEqual(m["ratio_kd_over_embree"]["kd_origin"]["paired"], 0.8)
        self.assertNotIn("ratio_trace_only", m)
        self.assertEqual(m["validation"]["brute_force_checked"], 20)
        self.assertEqual(m["validation"]["variants_vs_kd_mismatches"], {"kd_origin": 1})
        # The inputs are left as they were.
        self.assertEqual(a["tracers"]["kd_origin"]["T_R_runs"], [1.0, 2.0])
        # The targets table pairs over the pooled rounds: 0.8 [0.5..0.9].
        self.assertIn("| s | 100,000 | sah-packet | 0.80 [0.50..0.90] (met) |",
                      bench_tables.targets_summary(merged))
        self.assertEqual(bench_merge.processes_line(merged),
                         "Each row pools the rounds of 2 render_bench processes "
                         "(experiments/bench_merge.py).")

    def test_ray_classes_runs_pooled_and_their_summaries_dropped(self):
        def with_classes(kd_ns, embree_ns):
            r = record([1.0], [0.8])
            r["ray_classes"] = {"rounds": len(kd_ns), "classes": {
                "shadow": {"rays": 5, "ns_runs": {"kd_origin": kd_ns, "embree": embree_ns},
                           "ns_per_ray": {"kd_origin": 0.0}, "embree_over": {}},
                "ao": {"rays": 2, "ns_runs": {"kd_origin": [1.0], "embree": [1.0]}}}}
            return r
        a, b = with_classes([2.0, 3.0], [1.0, 1.5]), with_classes([4.0], [2.0])
        del b["ray_classes"]["classes"]["ao"]
        m = bench_merge.merge_processes([a, b])[0]["ray_classes"]
        self.assertEqual(m["rounds"], 3)
        self.assertEqual(m["classes"], {"shadow": {"rays": 5, "ns_runs": {
            "kd_origin": [2.0, 3.0, 4.0], "embree": [1.0, 1.5, 2.0]}}})
        # A process without classes: none pooled.
        del b["ray_classes"]
        self.assertIsNone(bench_merge.merge_processes([a, b])[0]["ray_classes"])

    def test_other_scenes_and_other_code_are_not_pooled(self):
        a = record([1.0], [0.8])
        records = [a, record([1.0], [0.8], scene="t"), record([1.0], [0.8], tree="b" * 40)]
        merged = bench_merge.merge_processes(records)
        self.assertEqual([(r["scene"], r["processes"]) for r in merged],
                         [("s", 1), ("t", 1), ("s", 1)])
        self.assertEqual(merged[0]["tracers"], a["tracers"])  # one record: as it was
        self.assertEqual(bench_merge.processes_line(merged), "")

    def test_probe_line_counts_records_in_a_slow_state(self):
        self.assertEqual(bench_merge.probe_line([record([1.0], [0.8])]), "")
        records = []
        for cpu, probes in ((1, {"0": 4.0, "1": 2.7}), (0, {"0": 3.0, "1": 4.0}),
                            (1, {"0": 4.1, "1": 3.6})):
            r = record([1.0], [0.8])
            r["timing"] = {"cpu": cpu, "cpu_probe_ms": probes}
            records.append(r)
        two = dict(records[0], threads=2)  # not counted
        self.assertEqual(bench_merge.probe_line(records + [two]),
                         "The CPU probe of the rounds (cc/base/quiet_cpu.h): median 3.00 ms, "
                         "2.70 to 3.60; 1 of 3 one-thread records above 1.25 times the quickest, "
                         "in a slow state of the machine.")


if __name__ == "__main__":
    unittest.main()
