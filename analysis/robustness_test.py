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


def cost_rec(scene, preset, mode, seconds, cpu="Fixture CPU"):
    return {"scene": scene, "triangles": 1000, "preset": preset, "mode": mode,
            "rays": 2000, "seconds": seconds, "rays_per_s": 2000 / seconds,
            "mismatches_between_modes": 3, "cpu": cpu}


COST = [cost_rec("bunny", "default", "fast", 1.0),
        cost_rec("bunny", "default", "watertight", 1.1),
        cost_rec("city", "default", "fast", 2.0),
        cost_rec("city", "default", "watertight", 2.6),
        cost_rec("generated", "pruning", "fast", 1.0),
        cost_rec("generated", "pruning", "watertight", 1.2)]


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

    def run_gen(self, allow_mixed=False):
        ctx = context.Context(self.results, "/nonexistent.json", self.out)
        ctx.allow_mixed_cpus = allow_mixed
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
        self.assertEqual(macros["RobustSphereRays"], ("140", False))
        self.assertEqual(macros["RobustSphereMisses"], ("0", False))
        self.assertEqual(macros["RobustFastSphereMisses"], ("6", False))
        self.assertEqual(macros["RobustFixedSelfHits"], ("4", False))
        self.assertEqual(macros["RobustFixedSkipped"], ("9", False))
        # Costs of the default preset: +10% and +30%.
        self.assertEqual(macros["RobustCostMedian"], ("20.0\\%", True))
        self.assertEqual(macros["RobustCostMin"], ("10.0\\%", True))
        self.assertEqual(macros["RobustCostMax"], ("30.0\\%", True))
        self.assertEqual(macros["RobustCostScenes"], ("2", False))
        cases = self.read("robust_cases.tex")
        self.assertIn("2,000 / 0", cases)      # a preset of case 1
        self.assertIn("1,000 / 7", cases)      # the seed mode
        self.assertIn("20.0k / 0", cases)      # stairs, default
        self.assertIn("\\textbf{no}", cases)   # case 3's binary failed
        self.assertIn("tab:robust-sphere", self.read("robust_sphere.tex"))
        spawn = self.read("robust_spawn.tex")
        self.assertLess(spawn.index("1e-08"), spawn.index("1e+08"))
        cost = self.read("robust_cost.tex")
        self.assertIn("+30.0\\%", cost)
        self.assertLess(cost.index("city"), cost.index("generated"))

    def test_no_results(self):
        _, macros = self.run_gen()
        self.assertEqual(sorted(macros), sorted(robustness.MACROS))
        self.assertIn("not run", self.read("robust_cases.tex"))
        self.assertIn("not run", self.read("robust_cost.tex"))

    def test_mixed_cpus_refused_unless_allowed(self):
        self.write(robustness.COST_FILE,
                   COST + [cost_rec("x", "default", "fast", 1, cpu="Other"),
                           cost_rec("x", "default", "watertight", 1,
                                    cpu="Other")])
        with self.assertRaises(ValueError):
            self.run_gen()
        _, macros = self.run_gen(allow_mixed=True)
        self.assertEqual(macros["RobustCostScenes"], ("3", False))


if __name__ == "__main__":
    unittest.main()
