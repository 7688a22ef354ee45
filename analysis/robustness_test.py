"""analysis/robustness.py on a small fixture (made-up numbers, tests only)."""

import json
import os
import tempfile
import unittest

from analysis import context
from analysis import robustness


def cmp_rec(case, number, preset, mode, rays, mismatches=0, required=True):
    return {"case": case, "hard_case": number, "binary": "b%d" % number,
            "preset": preset, "mode": mode, "rays": rays, "hits": rays // 2,
            "mismatches": mismatches, "any_hit_mismatches": 0,
            "required": required}


SUITE = (
    [cmp_rec("axis_rays/tiny", 1, p, m, 1000)
     for p in robustness.PRESETS for m in ("watertight", "fast")]
    + [cmp_rec("axis_rays/tiny", 1, "pruning-seed", "watertight", 1000,
               mismatches=7, required=False),
       cmp_rec("stairs/dyadic", 3, "default", "watertight", 20000),
       cmp_rec("axis_rays/tiny", 1, "triangle-bvh", "watertight", 3000, mismatches=2),
       {"case": "watertight_sphere/origin", "hard_case": 5, "mode":
        "watertight", "random_rays": 100, "random_misses": 0,
        "vertex_rays": 10, "vertex_misses": 0, "edge_midpoint_rays": 30,
        "edge_midpoint_misses": 0},
       {"case": "watertight_sphere/origin", "hard_case": 5, "mode": "fast",
        "random_rays": 100, "random_misses": 2, "vertex_rays": 10,
        "vertex_misses": 1, "edge_midpoint_rays": 30,
        "edge_midpoint_misses": 3},
       {"case": "self_intersection/1e-08", "hard_case": 7, "preset":
        "default", "mode": "watertight", "offset": "error_bound",
        "shadow_rays": 50, "self_hits": 0, "any_vs_closest": 0,
        "occluder_skipped": 0},
       {"case": "self_intersection/1e-08", "hard_case": 7, "preset":
        "default", "mode": "watertight", "offset": "fixed_1e-4",
        "shadow_rays": 50, "self_hits": 0, "occluder_skipped": 9},
       {"case": "self_intersection/1e+08", "hard_case": 7, "preset":
        "default", "mode": "watertight", "offset": "fixed_1e-4",
        "shadow_rays": 50, "self_hits": 4, "occluder_skipped": 0},
       {"kind": "binary", "hard_case": 1, "binary": "b1", "passed": True},
       {"kind": "binary", "hard_case": 3, "binary": "b3", "passed": False}])


PROV = {"commit": "c0ffee" * 6 + "abcd", "dirty": False,
        "source_tree": "7ree" * 10, "compilation_mode": "opt",
        "optimized": True, "ndebug": True, "timing_build": True,
        "compiler": "12.2.0", "cpu_model": "Fixture CPU", "cores": 2,
        "timing_lock": "/tmp/kdtree-timing.lock", "timed_beside": 0}


def prov(**changes):
    return dict(PROV, **changes)


def cost_rec(scene, preset, ratios, fast_s=1.0, provenance=None):
    """A record shaped as robust_cost_bench writes it (one per scene and
    preset), with made-up times: the watertight runs are fast_s * ratio."""
    fast_runs = [fast_s] * len(ratios)
    wt_runs = [fast_s * q for q in ratios]

    def lane(runs):
        med = sorted(runs)[len(runs) // 2]
        return {"seconds": med, "seconds_runs": runs, "warmup_seconds": 1.5,
                "rays_per_s": 2000 / med, "primary_hits": 900,
                "shadow_hits": 100}
    return {"scene": scene, "triangles": 1000, "view": "manifest",
            "width": 40, "height": 40, "preset": preset, "threads": 1,
            "rays": 2000, "primary_rays": 1600, "shadow_rays": 400,
            "build_seconds": 0.01, "repeats": len(ratios),
            "timing": {"rounds": len(ratios), "lock_wait_s": 0.0},
            "fast": lane(fast_runs), "watertight": lane(wt_runs),
            "paired_ratio_runs": list(ratios),
            "paired_ratio": sorted(ratios)[len(ratios) // 2],
            "paired_ratio_min": min(ratios), "paired_ratio_max": max(ratios),
            "mismatches_between_modes": 3, "same_triangle_other_t": 0,
            "provenance": PROV if provenance is None else provenance}


# bunny +10 % and city +30 %, both beyond their spread; park +1 %, its
# rounds on both sides of 1: within noise; generated/pruning within noise.
COST = [cost_rec("bunny", "default", [1.08, 1.10, 1.12]),
        cost_rec("city", "default", [1.25, 1.30, 1.35], fast_s=2.0),
        cost_rec("park", "default", [0.97, 1.01, 1.04]),
        cost_rec("generated", "pruning", [0.95, 1.20, 1.30])]


class RobustnessTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results = os.path.join(self.tmp.name, "results")
        self.out = os.path.join(self.tmp.name, "gen")
        os.makedirs(self.results)
        os.makedirs(self.out)

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, name, recs):
        with open(os.path.join(self.results, name), "w") as f:
            for r in recs:
                f.write(json.dumps(r) + "\n")

    def run_gen(self, **flags):
        ctx = context.Context(self.results, "/nonexistent.json", self.out)
        for flag in ("allow_mixed_cpus", "allow_mixed_provenance",
                     "allow_unoptimized_timings"):
            setattr(ctx, flag, flags.pop(flag, False))
        self.assertEqual(flags, {})
        return ctx, robustness.generate(ctx)

    def read(self, name):
        with open(os.path.join(self.out, name)) as f:
            return f.read()

    def test_tables_and_macros(self):
        self.write(robustness.SUITE_FILE, SUITE)
        self.write(robustness.COST_FILE, COST)
        _, macros = self.run_gen()
        self.assertEqual(sorted(macros), sorted(robustness.MACROS))
        # 10 presets x 2 modes x 1000 rays, plus 20000 stairs rays.
        self.assertEqual(macros["RobustRays"], ("40,000", False))
        self.assertEqual(macros["RobustMismatches"], ("0", False))
        self.assertEqual(macros["RobustSeedMismatches"], ("7", False))
        self.assertEqual(macros["RobustCases"], ("2", False))
        self.assertEqual(macros["RobustCasesPassed"], ("1", False))
        self.assertEqual(macros["RobustPresets"], ("10", False))
        # The baseline: a row of its own, outside the presets' totals.
        self.assertEqual(macros["RobustBaselineRays"], ("3,000", False))
        self.assertEqual(macros["RobustBaselineMismatches"], ("2", False))
        self.assertEqual(macros["RobustSphereRays"], ("140", False))
        self.assertEqual(macros["RobustSphereMisses"], ("0", False))
        self.assertEqual(macros["RobustFastSphereMisses"], ("6", False))
        self.assertEqual(macros["RobustFixedSelfHits"], ("4", False))
        self.assertEqual(macros["RobustFixedSkipped"], ("9", False))
        # Paired costs of the default preset: +10 %, +30 %, +1 % (noise).
        self.assertEqual(macros["RobustCostMedian"],
                         ("+10.0\\% (within noise on 1 of 3 scenes)", True))
        self.assertEqual(macros["RobustCostMin"], ("+1.0\\%", True))
        self.assertEqual(macros["RobustCostMax"], ("+30.0\\%", True))
        self.assertEqual(macros["RobustCostScenes"], ("3", False))
        self.assertEqual(macros["RobustCostWithinNoise"], ("1", False))
        self.assertEqual(macros["RobustCostCpu"], ("Fixture CPU", False))
        self.assertEqual(macros["RobustCostDiffering"], ("12", False))
        cases = self.read("robust_cases.tex")
        self.assertIn("2,000 / 0", cases)      # a preset of case 1
        self.assertIn("1,000 / 7", cases)      # the seed mode
        self.assertIn("BVH of whole triangles (baseline) & 3,000 / 2", cases)
        self.assertLess(cases.index("Pruning, seed mode &"),
                        cases.index("BVH of whole triangles (baseline) &"))
        self.assertIn("20.0k / 0", cases)      # stairs, default
        self.assertIn("\\textbf{no}", cases)   # case 3's binary failed
        self.assertIn("tab:robust-sphere", self.read("robust_sphere.tex"))
        spawn = self.read("robust_spawn.tex")
        self.assertLess(spawn.index("1e-08"), spawn.index("1e+08"))
        cost = self.read("robust_cost.tex")
        self.assertIn("+30.0\\% (+25.0\\% to +35.0\\%)", cost)
        self.assertIn("+10.0\\% (+8.0\\% to +12.0\\%)", cost)
        # park and generated/pruning: no cost printed, the spread instead.
        self.assertIn("within noise ($-$3.0\\% to +4.0\\%)", cost)
        self.assertIn("within noise ($-$5.0\\% to +30.0\\%)", cost)
        self.assertNotIn("+1.0\\%", cost)
        self.assertLess(cost.index("city"), cost.index("generated"))
        # Mrays/s of the median runs: city's fast runs take 2 s.
        self.assertIn("0.001", cost)

    def test_a_sampled_suite_says_so(self):
        self.write(robustness.SUITE_FILE, SUITE)
        self.run_gen()
        self.assertNotIn("packet of 16", self.read("robust_cases.tex"))
        self.write(robustness.SUITE_FILE,
                   SUITE + [{"kind": "suite", "ray_stride": 4}])
        self.run_gen()
        self.assertIn("every 4\\textsuperscript{th} packet of 16",
                      self.read("robust_cases.tex"))

    def test_cost_verdict(self):
        self.assertEqual(robustness.cost_verdict([1.1, 1.2, 1.3]),
                         (1.2, 1.1, 1.3, False))
        self.assertTrue(robustness.cost_verdict([0.9, 1.2, 1.3])[3])
        self.assertTrue(robustness.cost_verdict([1.0, 1.2])[3])
        # One round measures no spread: not "within noise", and said so.
        self.assertFalse(robustness.cost_verdict([1.0])[3])

    def test_one_round_is_marked(self):
        self.write(robustness.COST_FILE, [cost_rec("bunny", "default",
                                                   [1.2])])
        _, macros = self.run_gen()
        self.assertIn("+20.0\\% (one round)", self.read("robust_cost.tex"))
        self.assertEqual(macros["RobustCostMedian"], ("+20.0\\%", True))

    def test_newest_record_wins_and_old_format_is_left_out(self):
        old = {"scene": "bunny", "preset": "default", "mode": "fast",
               "seconds": 1.0, "rays_per_s": 2000.0, "cpu": "Fixture CPU"}
        self.write(robustness.COST_FILE,
                   [old, cost_rec("bunny", "default", [1.5, 1.6, 1.7])]
                   + COST)
        _, macros = self.run_gen()
        self.assertEqual(macros["RobustCostScenes"], ("3", False))
        cost = self.read("robust_cost.tex")
        self.assertNotIn("+60.0", cost)
        self.assertIn("1 records of the old unpaired format", cost)
        self.write(robustness.COST_FILE, [old])
        self.run_gen()
        self.assertIn("1 of the old unpaired format left out",
                      self.read("robust_cost.tex"))

    def test_no_results(self):
        _, macros = self.run_gen()
        self.assertEqual(sorted(macros), sorted(robustness.MACROS))
        self.assertIn("not run", self.read("robust_cases.tex"))
        self.assertIn("not run", self.read("robust_cost.tex"))

    def test_mixed_provenance_refused_unless_allowed(self):
        other = prov(commit="feed" * 10, dirty=True, source_tree="0ther" * 8)
        self.write(robustness.COST_FILE,
                   COST + [cost_rec("x", "default", [1.1, 1.2],
                                    provenance=other)])
        with self.assertRaises(ValueError) as err:
            self.run_gen()
        msg = str(err.exception)
        self.assertIn("--allow_mixed_provenance", msg)
        self.assertIn(PROV["commit"][:12], msg)
        self.assertIn("feedfeedfeed +dirty 0ther0ther0t", msg)
        _, macros = self.run_gen(allow_mixed_provenance=True)
        self.assertEqual(macros["RobustCostScenes"], ("4", False))
        # Records without provenance are of another (unknown) one.
        self.write(robustness.COST_FILE,
                   COST + [dict(cost_rec("x", "default", [1.1, 1.2]),
                                provenance=None)])
        with self.assertRaises(ValueError):
            self.run_gen()

    def test_suite_of_two_provenances_refused(self):
        other = prov(source_tree="0ther" * 8)
        self.write(robustness.SUITE_FILE,
                   [dict(r, provenance=PROV) for r in SUITE[:-1]]
                   + [dict(SUITE[-1], provenance=other)])
        with self.assertRaises(ValueError) as err:
            self.run_gen()
        self.assertIn("--allow_mixed_provenance", str(err.exception))
        self.assertIn("robust.jsonl", str(err.exception))
        self.run_gen(allow_mixed_provenance=True)

    def test_unoptimized_timings_refused_unless_allowed(self):
        debug = prov(compilation_mode="fastbuild", optimized=True,
                     ndebug=False, timing_build=False)
        self.write(robustness.COST_FILE,
                   [cost_rec("bunny", "default", [1.1, 1.2, 1.3],
                             provenance=debug)])
        with self.assertRaises(ValueError) as err:
            self.run_gen()
        msg = str(err.exception)
        self.assertIn("--allow_unoptimized_timings", msg)
        self.assertIn("bunny/default", msg)
        _, macros = self.run_gen(allow_unoptimized_timings=True)
        self.assertEqual(macros["RobustCostScenes"], ("1", False))

    def test_mixed_cpus_refused_unless_allowed(self):
        self.write(robustness.COST_FILE,
                   COST + [cost_rec("x", "default", [1.1, 1.2],
                                    provenance=prov(cpu_model="Other"))])
        with self.assertRaises(ValueError) as err:
            self.run_gen()
        self.assertIn("--allow_mixed_cpus", str(err.exception))
        _, macros = self.run_gen(allow_mixed_cpus=True)
        self.assertEqual(macros["RobustCostScenes"], ("4", False))
        self.assertEqual(macros["RobustCostCpu"],
                         ("Fixture CPU; Other", False))


if __name__ == "__main__":
    unittest.main()
