"""Tests of experiments/bench.py, bench_tables.py and bench_structure.py: scene
selection, the summaries and the provenance they state and check."""
import contextlib
import io
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402
import bench_structure  # noqa: E402
import bench_tables  # noqa: E402


def provenance(tree="a" * 40, commit="c" * 40, dirty=False, mode="opt", cpu="Test CPU @ 2GHz"):
    # The shape of cc/base/provenance.cc's Provenance::ToJson().
    timing = mode == "opt"
    return {"commit": commit, "dirty": dirty, "source_tree": tree, "compilation_mode": mode,
            "optimized": timing, "ndebug": timing, "avx2": True, "avx512f": False, "fma": True,
            "timing_build": timing, "compiler": "12.2.0", "cpu_model": cpu, "cores": 2,
            "timing_lock": "/tmp/kdtree-timing.lock", "timed_beside": 0,
            "timestamp_utc": "2024-01-01T00:00:00Z"}


def build_record(threads, runs, n=2000000, warmup=None, prov=None):
    r = {"scene": "big", "n_tri": n, "preset": "binning-32", "threads": threads,
         "T_B": sorted(runs)[len(runs) // 2], "T_B_runs": runs,
         "provenance": prov or provenance()}
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
        text = bench_tables.build_summary([build_record(1, [1.0, 0.8, 1.2], warmup=[1.5]),
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
                    "provenance": provenance(),
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
        text = bench_tables.render_summary([one, rec(2, 0.1, 0.05)])
        row = text.splitlines()[2]
        self.assertIn("| 0.50 | 0.55 | 0.62 | 0.66 | 0.81, 0.69 | 2.00x | 2.00x |", row)
        self.assertIn("paired kd_packet_origin/Embree over 1 rows: median 0.81, range 0.81 to "
                      "0.81, 1 at 0.7 or more; over Embree's packets: median 0.69, range 0.69 "
                      "to 0.69, 0 at 0.7 or more.", text)
        self.assertIn("paired kd_origin/Embree over 1 rows: median 0.66", text)
        self.assertIn("kd_packet/embree_packet over 1 rows: median 0.62", text)
        self.assertIn("Paired kd/Embree over 1 rows: median 0.55", text)
        self.assertIn("0/301 brute-force mismatches, 3 Embree disagreements", row)
        self.assertIn("median 0.50", text)
        # A run without the kd variant (--variants kd_origin,...): no row.
        no_kd = dict(one, tracers={"kd_origin": {"T_R_median": 0.2}})
        self.assertEqual(len(bench_tables.render_summary([no_kd]).splitlines()), 2)

    def test_render_summary_names_scenes_whose_camera_or_light_sees_little(self):
        def rec(scene, n, seen, occluded=None):
            r = {"scene": scene, "n_tri": n, "preset": "sah-packet", "threads": 1,
                 "provenance": provenance(), "shadow": 1000,
                 "tracers": {"kd": {"T_R_median": 0.2}, "embree": {"T_R_median": 0.1}},
                 "validation": {"brute_force_mismatches": 0, "brute_force_checked": 301}}
            if seen is not None:
                r["camera_triangles"] = seen
            if occluded is not None:
                r["shadow_occluded"] = occluded
            return r
        text = bench_tables.render_summary([rec("box", 737856, 10, 990),
                                            rec("bunny", 69666, 30000, 200),
                                            rec("old", 100000, None)])
        self.assertIn("Camera coverage: primary rays hit a median of 21.5 % of a scene's "
                      "triangles (fewest: 0.00 % on box); under 0.1 %: box.", text)
        self.assertIn("Shadow rays occluded: median 60 % (most: 99 % on box); over 95 %: box.",
                      text)
        text = bench_tables.render_summary([rec("bunny", 69666, 30000, 200)])
        self.assertIn("under 0.1 %: none.", text)
        self.assertIn("over 95 %: none.", text)
        old = bench_tables.render_summary([rec("old", 100000, None)])
        self.assertNotIn("Camera coverage", old)
        self.assertNotIn("Shadow rays occluded", old)

    def test_targets_summary_pairs_the_fastest_modes_per_round(self):
        def runs(*t):
            return {"T_R_runs": list(t)}
        r = {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": 1,
             "provenance": provenance(),
             "tracers": {"kd": runs(2.0, 2.0, 4.0), "kd_origin": runs(1.6, 2.5, 2.0),
                         "kd_packet_origin": runs(1.0, 1.0, 1.0),
                         "embree": runs(1.6, 1.5, 1.6), "embree_packet": runs(1.2, 1.0, 0.9)}}
        two = dict(r, threads=2)  # ignored: one thread only
        text = bench_tables.targets_summary([r, two])
        # Single: Embree's single over our faster single mode per round: 1.6/1.6,
        # 1.5/2.0, 1.6/2.0. Best: Embree's faster over ours: 1.2, 1.0, 0.9.
        self.assertIn("| s | 100,000 | sah-packet | 0.80 [0.75..1.00] (met) | "
                      "1.00 [0.90..1.20] (met) |", text)
        self.assertEqual(len([l for l in text.splitlines() if l.startswith("| s |")]), 1)
        # The closing lines: over the rows' medians.
        self.assertIn("Single rays against Embree's single rays over 1 rows: median 0.80, "
                      "range 0.80 to 0.80, 1 at 0.8 or more.", text)
        self.assertIn("Best mode against Embree's best mode over 1 rows: median 1.00, "
                      "range 1.00 to 1.00, 1 at 1.0 or more.", text)
        # With the replays (render_bench --replay), each mode less its replay per
        # round. Single: Embree 1.1, 1.0, 1.1 over our faster 1.1, 1.5, 1.5. Best:
        # Embree's packets 0.8, 0.6, 0.5 over kd_packet_origin's 0.6 each round.
        traced = dict(r, tracers=dict(r["tracers"], replay=runs(0.5, 0.5, 0.5),
                                      replay_packet=runs(0.4, 0.4, 0.4)))
        self.assertIn("(met) | 0.73 [0.67..1.00] | 1.00 [0.83..1.33] (met) |",
                      bench_tables.targets_summary([traced]))
        self.assertIn("Tracing alone, best mode against Embree's best mode over 1 rows: "
                      "median 1.00", bench_tables.targets_summary([traced]))
        # A tracing time that is not positive is left out: in round 2 Embree's
        # single rays (1.5 - 1.5), so single/single has no ratio there (1.1/1.1,
        # 1.1/1.5) and best/best takes Embree's packets (0.8/0.6, 0.6/0.5,
        # 0.5/0.6).
        noisy = dict(traced, tracers=dict(traced["tracers"], replay=runs(0.5, 1.5, 0.5)))
        self.assertIn("(met) | 0.87 [0.73..1.00] (met) | 1.20 [0.83..1.33] (met) |",
                      bench_tables.targets_summary([noisy]))
        # Without Embree's packets, the best mode is against its single rays.
        del r["tracers"]["embree_packet"]
        self.assertIn("| 1.60 [1.50..1.60] (met) |", bench_tables.targets_summary([r]))
        # No Embree at all: no ratios.
        del r["tracers"]["embree"]
        self.assertIn("| s | 100,000 | sah-packet | - | - |", bench_tables.targets_summary([r]))

    def test_targets_summary_against_embree_robust(self):
        def runs(*t):
            return {"T_R_runs": list(t)}
        wrong = {"primary": {"other_wrong": 0}, "shadow": {"other_wrong": 1234},
                 "at_origin": 1230}
        r = {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": 1,
             "provenance": provenance(),
             "validation": {"embree_robust_disagreements": wrong},
             "tracers": {"kd_origin": runs(2.0, 2.0, 2.0), "kd_packet_origin": runs(1.0, 1.0, 1.0),
                         "embree": runs(1.0, 1.0, 1.0), "embree_packet": runs(0.5, 0.5, 0.5),
                         "embree_robust": runs(1.6, 1.8, 2.0),
                         "embree_robust_packet": runs(1.1, 1.2, 1.0)}}
        text = bench_tables.targets_summary([r], robust=True)
        # Against the robust tracers only: 1.6/2, 1.8/2, 2/2 and 1.1, 1.2, 1.0.
        self.assertIn("| s | 100,000 | sah-packet | 0.90 [0.80..1.00] (met) | "
                      "1.10 [1.00..1.20] (met) | - | - | 0, 1,234 (1,230) |", text)
        # The default table ignores them.
        self.assertIn("| 0.50 [0.50..0.50] | 0.50 [0.50..0.50] |",
                      bench_tables.targets_summary([r]))
        # A record without the robust tracers has no row.
        del r["tracers"]["embree_robust"]
        self.assertNotIn("| s |", bench_tables.targets_summary([r], robust=True))

    def test_passes_summary_pairs_each_pass_less_its_replay(self):
        def runs(total, primary, secondary):
            return {"T_R_runs": total, "primary_s_runs": primary, "secondary_s_runs": secondary}
        r = {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": 1,
             "provenance": provenance(),
             "tracers": {"kd": runs([3, 3], [1.5, 1.5], [1.5, 2.5]),
                         "kd_origin": runs([3, 3], [1.6, 1.5], [1.0, 1.5]),
                         "kd_packet_origin": runs([2, 2], [0.9, 0.8], [0.7, 0.7]),
                         "embree": runs([2, 2], [1.2, 1.3], [0.7, 0.9]),
                         "embree_packet": runs([1, 1], [0.6, 0.5], [0.7, 0.8]),
                         "replay": runs([1, 1], [0.5, 0.5], [0.3, 0.3]),
                         "replay_packet": runs([1, 1], [0.4, 0.4], [0.3, 0.3])}}
        text = bench_tables.passes_summary([r, dict(r, threads=2)])
        # Primary, single: Embree 0.7, 0.8 over our faster 1.0, 1.0. Shadow,
        # single: 0.4, 0.6 over 0.7, 1.2. Primary, packets: 0.2, 0.1 over 0.5,
        # 0.4 (median 0.325, printed 0.32). Shadow, packets: 0.4, 0.5 over 0.4
        # each round.
        self.assertIn("| s | 100,000 | 0.75 [0.70..0.80] | 0.54 [0.50..0.57] | "
                      "0.32 [0.25..0.40] | 1.12 [1.00..1.25] |", text)
        self.assertEqual(len([l for l in text.splitlines() if l.startswith("| s |")]), 1)
        self.assertIn("Shadow rays, packets, tracing alone, Embree's over ours over 1 rows: "
                      "median 1.12, range 1.12 to 1.12.", text)
        # Without the replays, or records without per-round pass times: no row.
        del r["tracers"]["replay"], r["tracers"]["replay_packet"]
        self.assertNotIn("| s |", bench_tables.passes_summary([r]))

    def test_triangle_bvh_summary_sets_the_baseline_beside_the_kd_tree(self):
        def runs(total, primary, secondary):
            return {"T_R_runs": total, "primary_s_runs": primary, "secondary_s_runs": secondary}
        r = {"scene": "s", "n_tri": 1000, "preset": "sah-packet", "threads": 1,
             "provenance": provenance(), "tree_bytes": 70000, "bvh_bytes": 10000,
             "tri_bvh_bytes": 50000, "embree_bvh_bytes": 60000,
             "tracers": {"kd_bvh_packet": runs([2, 2], [1.0, 1.0], [0.8, 0.8]),
                         "tri_bvh": runs([3, 3], [1.5, 1.5], [1.2, 1.2]),
                         "tri_bvh_packet": runs([1.6, 1.6], [0.8, 0.8], [0.6, 0.6]),
                         "embree": runs([2.5, 2.5], [1.2, 1.2], [1.0, 1.0]),
                         "embree_packet": runs([1.6, 2.0], [0.7, 0.7], [0.7, 0.7]),
                         "replay": runs([1, 1], [0.4, 0.4], [0.3, 0.3]),
                         "replay_packet": runs([1, 1], [0.4, 0.4], [0.3, 0.3])}}
        text = bench_structure.triangle_bvh_summary([r, dict(r, threads=2)])
        # Best mode: Embree's 1.6, 2.0 over kd_bvh_packet's 2, 2 (0.80, 1.00)
        # and over tri_bvh_packet's 1.6 (1.00, 1.25). Camera packets, tracing
        # alone: 0.3 over 0.6 and 0.4; shadow: 0.4 over 0.5 and 0.3.
        self.assertIn("| s | 1,000 | 0.90 [0.80..1.00] | 1.12 [1.00..1.25] | "
                      "0.50 [0.50..0.50], 0.75 [0.75..0.75] | 0.80 [0.80..0.80], "
                      "1.33 [1.33..1.33] | 80, 50, 60 |", text)
        self.assertEqual(len([l for l in text.splitlines() if l.startswith("| s |")]), 1)
        # Since session 47 the BVH reads its own leaf packets: its nodes and
        # those, not the tree.
        own = bench_structure.triangle_bvh_summary([dict(r, bvh_packet_bytes=65000)])
        self.assertIn("| 75, 50, 60 |", own)
        self.assertIn("Best mode, triangle BVH, Embree's over ours over 1 rows: median 1.12, "
                      "range 1.12 to 1.12, 1 at 1.0 or more.", text)
        # Rows without the baseline: no table.
        for name in ("tri_bvh", "tri_bvh_packet"):
            del r["tracers"][name]
        self.assertEqual(bench_structure.triangle_bvh_summary([r]), "")

    def test_memory_summary_gives_bytes_per_triangle(self):
        one = {"scene": "s", "n_tri": 1000, "preset": "sah-packet", "threads": 1,
               "tree_bytes": 120000, "embree_bvh_bytes": 60000}
        older = dict(one, scene="old", embree_bvh_bytes=None)
        text = bench_structure.memory_summary([one, dict(one, threads=2), older])
        self.assertIn("| s | 1,000 | sah-packet | 120 | 60 | 2.00 |", text)
        self.assertEqual(len(text.splitlines()), 3)  # the header, the rule, one row
        self.assertEqual(bench_structure.memory_summary([older]), "")

    def test_packets_summary_gives_steps_per_packet_and_lanes_per_step(self):
        def counts(packets, rays):
            return {"rays": rays, "packets": packets,
                    "per_packet": {"inner_steps": 20.25, "leaf_steps": 5.0,
                                   "triangle_steps": 23.0},
                    "lanes_per_step": {"inner": 13.5, "leaf": 11.0, "triangle": 13.62},
                    "per_ray": {"N_TR": 7.5, "N_IT": 8.53}}
        r = {"scene": "s", "n_tri": 100000, "preset": "sah-packet", "threads": 1,
             "provenance": provenance(),
             "packet_counts": {"kd_packet_origin": {"kernel": "AVX3", "closest": counts(17166, 640000),
                                                    "any": counts(8609, 134093)}}}
        text = bench_structure.packets_summary([r, dict(r, threads=2),
                                             dict(r, scene="t", packet_counts={})])
        self.assertIn("| s | kd_packet_origin | AVX3 | closest | 17,166 | 20.2 | 5.0 | 23.0 | "
                      "13.5 | 13.6 | 7.5 | 8.5 |", text)
        self.assertIn("| s | kd_packet_origin | AVX3 | any | 8,609 |", text)
        self.assertEqual(len(text.splitlines()), 4)  # one thread; no counts, no row

    def test_summary_states_the_provenance(self):
        text = bench.summarise([build_record(1, [1.0]), build_record(2, [0.5])],
                               bench_tables.build_summary, "build.jsonl")
        self.assertTrue(text.startswith("Provenance: cccccccccccc, opt, "
                                        "Test CPU @ 2GHz.\n\n| scene |"), text)
        dirty = provenance(dirty=True, tree="0123456789abcdef" * 2)
        text = bench.summarise([build_record(1, [1.0], prov=dirty)],
                               bench_tables.build_summary, "b")
        self.assertIn("cccccccccccc +dirty 0123456789ab, opt", text)

    def test_different_source_trees_are_refused_unless_allowed(self):
        records = [build_record(1, [1.0]), build_record(2, [0.5], prov=provenance(tree="b" * 40,
                                                                                commit="d" * 40))]
        with self.assertRaises(bench.ProvenanceError) as e:
            bench.summarise(records, bench_tables.build_summary, "build.jsonl")
        message = str(e.exception)
        self.assertIn("build.jsonl would mix records of 2 provenances", message)
        self.assertIn("cccccccccccc", message)
        self.assertIn("dddddddddddd", message)
        self.assertIn("--allow_mixed_provenance", message)
        text = bench.summarise(records, bench_tables.build_summary, "build.jsonl", allow_mixed=True)
        self.assertIn("Provenance, 2 of them: cccccccccccc, opt, Test CPU @ 2GHz "
                      "(1 records); dddddddddddd", text)
        # Another commit of the same source tree (an edit elsewhere) is one code.
        same = [build_record(1, [1.0]), build_record(2, [0.5], prov=provenance(commit="e" * 40))]
        bench.summarise(same, bench_tables.build_summary, "build.jsonl")
        # A record from before provenance is of another, unknown, code.
        old = build_record(2, [0.5])
        del old["provenance"]
        with self.assertRaises(bench.ProvenanceError):
            bench.summarise([build_record(1, [1.0]), old], bench_tables.build_summary, "b")

    def test_timings_not_built_for_timing_are_refused_unless_allowed(self):
        records = [build_record(1, [1.0], prov=provenance(mode="fastbuild"))]
        with self.assertRaises(bench.ProvenanceError) as e:
            bench.summarise(records, bench_tables.build_summary, "build.jsonl")
        self.assertIn("timings of big/binning-32 from a binary not built for timing "
                      "(cccccccccccc, fastbuild", str(e.exception))
        self.assertIn("--allow_unoptimized_timings", str(e.exception))
        text = bench.summarise(records, bench_tables.build_summary, "b", allow_unoptimized=True)
        self.assertIn("Provenance: cccccccccccc, fastbuild", text)

    def test_main_refuses_mixed_records_and_states_one_provenance(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "build.jsonl"), "w") as f:
                for r in (build_record(1, [1.0]), build_record(2, [0.5])):
                    f.write(json.dumps(r) + "\n")
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                bench.main(["--out", d, "--summary_only"])
            self.assertIn("## Build (build_bench)\n\nProvenance: cccccccccccc",
                          out.getvalue())
            self.assertIn("## Render (render_bench)\n\nProvenance: no records.",
                          out.getvalue())
            with open(os.path.join(d, "build.jsonl"), "a") as f:
                f.write(json.dumps(build_record(1, [1.0], prov=provenance(tree="b" * 40))) + "\n")
            with self.assertRaises(SystemExit) as e, contextlib.redirect_stdout(io.StringIO()):
                bench.main(["--out", d, "--summary_only"])
            self.assertIn("--allow_mixed_provenance", str(e.exception.code))
            with contextlib.redirect_stdout(io.StringIO()):
                bench.main(["--out", d, "--summary_only", "--allow_mixed_provenance"])

    def test_main_names_a_line_that_is_not_a_record(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "render.jsonl"), "w") as f:
                f.write(json.dumps(build_record(1, [1.0])) + '\n{"bench": ')
            with self.assertRaises(SystemExit) as e, contextlib.redirect_stdout(io.StringIO()):
                bench.main(["--out", d, "--summary_only"])
            self.assertRegex(str(e.exception.code), r"bench\.py: .*render\.jsonl:2: .*cut short")


if __name__ == "__main__":
    unittest.main()
