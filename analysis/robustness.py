"""The adversarial suite and what robustness costs (issue "Hard cases stay
numerically stable"), from results/robust.jsonl and robust_cost.jsonl written
by cc/robust/robust_suite.py.

Every kd-tree preset is compared with brute force ray by ray on rays built to
break traversal and intersection; the triangle test is the watertight one of
Woop, Benthin & Wald (JCGT 2013) and the traversal pads its intervals after
Ize (JCGT 2013). The fast Moeller-Trumbore test is kept to measure the cost.

Output: robust_cases.tex (rays tried and mismatches per hard case and preset,
both intersection modes), robust_sphere.tex (watertightness: misses from
inside closed spheres), robust_spawn.tex (shadow rays at magnitudes 1e-8 to
1e8: error-bound offset against none and a fixed epsilon), robust_cost.tex
(fast versus watertight on the same rays, single thread) and macros.
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex

SUITE_FILE = "robust.jsonl"
COST_FILE = "robust_cost.jsonl"

CASE_TITLES = {
    1: "Axis-parallel rays ($\\pm 0$) on vertex and split grids",
    2: "Origins exactly on split planes",
    3: "Stairs, axis rays, analytic $t$",
    4: "Flat scene; voxel blocks",
    5: "Closed spheres at 0 and $1.5\\cdot 10^5$, from inside",
    6: "Scales $10^{-4}$, 1, $10^4$",
    7: "Shadow rays, magnitudes $10^{-8}$--$10^8$",
    8: "Garbage and degenerate triangles",
    9: "Images equal brute force",
}
PRESETS = ["default"] + kr.VARIANTS
SEED = "pruning-seed"
PRESET_TITLES = dict(kr.TITLES, **{"default": "Default",
                                   SEED: "Pruning, seed mode"})

MACROS = ["RobustCases", "RobustCasesPassed", "RobustPresets",
          "RobustRays", "RobustMismatches", "RobustSeedMismatches",
          "RobustSphereRays", "RobustSphereMisses", "RobustFastSphereMisses",
          "RobustSelfHits", "RobustFixedSelfHits", "RobustFixedSkipped",
          "RobustCostScenes", "RobustCostMedian", "RobustCostMin",
          "RobustCostMax", "RobustCostDiffering", "RobustCostCpu"]


def _compact(n):
    """Rays in a narrow cell: 1,234 / 12.3k / 1.23M."""
    if n < 10000:
        return latex.fmt_int(n)
    if n < 10 ** 6:
        return latex.fmt_float(n / 1000.0) + "k"
    return latex.fmt_float(n / 1e6) + "M"


def _comparisons(records):
    """Brute-force comparison records (case, preset, mode, rays, mismatches)."""
    return [r for r in records if "preset" in r and "mismatches" in r
            and "rays" in r and "hard_case" in r]


def _cases_table(records, binaries):
    comps = _comparisons(records)
    # The report's presets in order, then any others the suite ran (newer
    # builders), the seed mode last.
    found = {r["preset"] for r in comps}
    presets = list(PRESETS) + sorted(found - set(PRESETS) - {SEED})
    if SEED in found:
        presets.append(SEED)
    numbers = sorted(CASE_TITLES)
    header = ["Preset"] + ["%d" % n for n in numbers]
    body, total_rays, total_bad, seed_bad = [], 0, 0, 0
    for p in presets:
        row = [latex.escape(PRESET_TITLES.get(p, p))]
        for number in numbers:
            sel = [r for r in comps if r["hard_case"] == number
                   and r["preset"] == p]
            if not sel:
                row.append(latex.DASH)
                continue
            rays = sum(int(r["rays"]) for r in sel)
            bad = sum(int(r["mismatches"]) + int(r.get("any_hit_mismatches", 0))
                      for r in sel)
            if p == SEED:
                seed_bad += bad
            else:
                total_rays += rays
                total_bad += bad
            row.append("%s / %s" % (_compact(rays), latex.fmt_int(bad)))
        body.append(row)
    body.append("midrule")
    row = ["Test binary passed"]
    for number in numbers:
        b = binaries.get(number)
        row.append(latex.DASH if b is None else
                   ("yes" if b["passed"] else "\\textbf{no}"))
    body.append(row)
    caption = ("The adversarial suite: rays tried / mismatches with brute "
               "force (closest hit: hit, triangle or $t$ differing; and any "
               "hit), summed over both triangle tests (watertight and fast), "
               "per preset and hard case. ``Passed'': the case's test "
               "binary held all its assertions (0 mismatches for every "
               "preset but the seed mode, which loses in-plane triangles "
               "by design and is only reported).")
    notes = ["Hard cases: " + "; ".join("%d.~%s" % (n, CASE_TITLES[n])
                                        for n in numbers) + "."]
    tex = latex.booktabs(header, body, align="l" + "r" * len(numbers),
                         caption=caption, label="tab:robust-cases",
                         notes=notes, size="footnotesize")
    return tex, total_rays, total_bad, seed_bad, len(presets) - (SEED in presets)


def _sphere_table(records):
    recs = [r for r in records if "random_rays" in r]
    body, rays_wt, miss_wt, miss_fast = [], 0, 0, 0
    for r in sorted(recs, key=lambda r: (r["case"], r["mode"] != "watertight")):
        rays = r["random_rays"] + r["vertex_rays"] + r["edge_midpoint_rays"]
        misses = (r["random_misses"] + r["vertex_misses"]
                  + r["edge_midpoint_misses"])
        if r["mode"] == "watertight":
            rays_wt += rays
            miss_wt += misses
        else:
            miss_fast += misses
        body.append([latex.escape(r["case"].split("/")[-1]),
                     latex.escape(r["mode"]),
                     latex.fmt_int(r["random_rays"]),
                     latex.fmt_int(r["random_misses"]),
                     latex.fmt_int(r["vertex_rays"]),
                     latex.fmt_int(r["vertex_misses"]),
                     latex.fmt_int(r["edge_midpoint_rays"]),
                     latex.fmt_int(r["edge_midpoint_misses"])])
    if not body:
        return "", 0, None, None
    header = ["Sphere", "Test", "Random rays", "Misses", "At vertices",
              "Misses", "At edge midpoints", "Misses"]
    caption = ("Watertightness: rays from inside a closed icosphere of "
               "81,920 triangles (radius 1 at the origin; radius 10 at "
               "$1.5\\cdot 10^5$ on every axis), random directions and rays "
               "aimed exactly at every vertex and edge midpoint. Every ray "
               "must hit.")
    return (latex.booktabs(header, body, align="llrrrrrr", caption=caption,
                           label="tab:robust-sphere", size="footnotesize"),
            rays_wt, miss_wt, miss_fast)


def _spawn_table(records):
    recs = [r for r in records if "self_hits" in r]
    mags = sorted({r["case"].split("/")[-1] for r in recs}, key=float)
    body, bound_self, fixed_self, fixed_skip = [], 0, 0, 0
    for m in mags:
        mine = [r for r in recs if r["case"].split("/")[-1] == m]
        bound = [r for r in mine if r.get("offset") == "error_bound"
                 and r["mode"] == "watertight"]
        none = [r for r in mine if r.get("offset") == "none"]
        fixed = [r for r in mine if r.get("offset") == "fixed_1e-4"]
        b_self = sum(r["self_hits"] for r in bound)
        b_skip = sum(r["occluder_skipped"] for r in bound)
        bound_self += b_self
        fixed_self += sum(r["self_hits"] for r in fixed)
        fixed_skip += sum(r["occluder_skipped"] for r in fixed)
        row = [latex.escape(m), latex.fmt_int(sum(r["shadow_rays"] for r in bound)),
               latex.fmt_int(b_self), latex.fmt_int(b_skip)]
        for sel in (none, fixed):
            row += ([latex.fmt_int(sum(r["self_hits"] for r in sel)),
                     latex.fmt_int(sum(r["occluder_skipped"] for r in sel))]
                    if sel else [latex.DASH, latex.DASH])
        body.append(row)
    if not body:
        return "", None, None, None
    header = ["Magnitude", "Shadow rays", "Self hits", "Occluder skipped",
              "Self hits", "Occluder skipped", "Self hits", "Occluder skipped"]
    groups = [("", 1), ("Error-bound offset, all presets", 3),
              ("No offset", 2), ("Fixed $10^{-4}$", 2)]
    caption = ("Self-intersection: shadow rays spawned from points on every "
               "triangle of one scene placed at vertex magnitudes from "
               "$10^{-8}$ to $10^{8}$. ``Self hits'': a shadow ray hits the "
               "triangle it left; ``occluder skipped'': a point under an "
               "occluder hovering $10^{-4}$ (relative) above the ground is "
               "lit. The error-bound offset (cc/geometry/spawn.h) is summed "
               "over every preset (watertight test); the two alternatives "
               "are the default preset only.")
    return (latex.booktabs(header, body, align="lrrrrrrr", caption=caption,
                           label="tab:robust-spawn", size="footnotesize",
                           groups=groups),
            bound_self, fixed_self, fixed_skip)


def _cost_table(records, allow_mixed_cpus):
    latest = {}
    for r in records:
        latest[(r["scene"], r["preset"], r["mode"])] = r
    cpus = sorted({r.get("cpu", "") for r in latest.values() if r.get("cpu")})
    if len(cpus) > 1 and not allow_mixed_cpus:
        raise ValueError("robust_cost.jsonl: timings from %d different CPUs "
                         "(%s); rerun on one kind of node, or pass "
                         "--allow_mixed_cpus" % (len(cpus), "; ".join(cpus)))
    pairs = []
    for (scene, preset, mode), fast in latest.items():
        if mode != "fast" or (scene, preset, "watertight") not in latest:
            continue
        pairs.append((scene, preset, fast, latest[(scene, preset,
                                                   "watertight")]))
    order = {p: i for i, p in enumerate(PRESETS)}
    pairs.sort(key=lambda x: (x[0] == "generated", x[0],
                              order.get(x[1], len(order))))
    body, costs, differing = [], [], 0
    for scene, preset, fast, wt in pairs:
        cost = 100.0 * (wt["seconds"] / fast["seconds"] - 1.0)
        if preset == "default":
            costs.append(cost)
        differing += int(wt["mismatches_between_modes"])
        body.append([latex.escape(scene),
                     latex.escape(PRESET_TITLES.get(preset, preset)),
                     latex.fmt_int(wt["triangles"]), latex.fmt_int(wt["rays"]),
                     latex.fmt_float(fast["rays_per_s"] / 1e6),
                     latex.fmt_float(wt["rays_per_s"] / 1e6),
                     ("+" if cost >= 0 else "$-$") + "%.1f\\%%" % abs(cost),
                     latex.fmt_int(wt["mismatches_between_modes"])])
    if not body:
        return "", costs, differing, cpus
    header = ["Scene", "Preset", "$N_{tri}$", "Rays", "Fast Mrays/s",
              "Watertight Mrays/s", "Cost", "Answers differing"]
    caption = ("What robustness costs: the same rays (the renderer's primary "
               "rays, then one shadow ray per hit and light) traced on the "
               "same tree with the fast (M\\\"oller--Trumbore) and the "
               "watertight triangle test, one thread, the fastest of "
               "alternating runs. ``Cost'': extra render time of the "
               "watertight test. ``Answers differing'': rays whose hit "
               "(triangle, or occlusion) differs between the two tests.")
    return (latex.booktabs(header, body, align="llrrrrrr", caption=caption,
                           label="tab:robust-cost", size="footnotesize"),
            costs, differing, cpus)


def generate(ctx):
    records = ctx.results(SUITE_FILE)
    cost_records = ctx.results(COST_FILE)
    dash = {n: (latex.DASH, True) for n in MACROS}
    if not records:
        ctx.write("robust_cases.tex", "\\emph{The adversarial suite was not "
                  "run (no results/robust.jsonl).}\n")
        for name in ("robust_sphere.tex", "robust_spawn.tex"):
            ctx.write(name, "")
        macros = dict(dash)
    else:
        binaries = {r["hard_case"]: r for r in records
                    if r.get("kind") == "binary"}
        tex, rays, bad, seed_bad, n_presets = _cases_table(records, binaries)
        ctx.write("robust_cases.tex", tex)
        sphere, s_rays, s_miss, s_fast = _sphere_table(records)
        ctx.write("robust_sphere.tex", sphere)
        spawn, b_self, f_self, f_skip = _spawn_table(records)
        ctx.write("robust_spawn.tex", spawn)

        def num(v):
            return (latex.DASH, True) if v is None else (latex.fmt_int(v), False)
        macros = dict(dash)
        macros.update({
            "RobustCases": num(len(binaries)),
            "RobustCasesPassed": num(sum(b["passed"] for b in binaries.values())),
            "RobustPresets": num(n_presets), "RobustRays": num(rays),
            "RobustMismatches": num(bad), "RobustSeedMismatches": num(seed_bad),
            "RobustSphereRays": num(s_rays), "RobustSphereMisses": num(s_miss),
            "RobustFastSphereMisses": num(s_fast),
            "RobustSelfHits": num(b_self), "RobustFixedSelfHits": num(f_self),
            "RobustFixedSkipped": num(f_skip)})
    cost, costs, differing, cpus = _cost_table(cost_records,
                                               getattr(ctx, "allow_mixed_cpus",
                                                       False))
    ctx.write("robust_cost.tex", cost or "\\emph{The robustness cost bench "
              "was not run (no results/robust_cost.jsonl).}\n")
    if costs:
        macros.update({
            "RobustCostScenes": (latex.fmt_int(len(costs)), False),
            "RobustCostMedian": ("%.1f\\%%" % statistics.median(costs), True),
            "RobustCostMin": ("%.1f\\%%" % min(costs), True),
            "RobustCostMax": ("%.1f\\%%" % max(costs), True),
            "RobustCostDiffering": (latex.fmt_int(differing), False),
            "RobustCostCpu": ("; ".join(cpus) or "unknown", False)})
    return macros
