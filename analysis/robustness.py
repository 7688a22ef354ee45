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

The cost table (issue 22) reads robust_cost_bench's paired records, the
newest of each (scene, preset): a warm-up of each test excluded, then rounds
alternating the two tests, each round's watertight / fast ratio paired. It
shows the median of those ratios as the cost, with the lowest and highest
round, and says "within noise" where that range includes 1 (the difference
lies within the measured spread) instead of printing a cost. Records of the
old unpaired format (one per test) are left out, with a note. Both files are
refused when their records come from more than one code (source tree,
compilation mode) or CPU, and the cost file when its timings come from a
binary not built for timing (analysis/provenance.py; make_all's
--allow_mixed_provenance, --allow_mixed_cpus, --allow_unoptimized_timings
override, read from the context with getattr, default False).
"""

import statistics

from analysis import kdtree_results as kr
from analysis import latex
from analysis import provenance

SUITE_FILE = "robust.jsonl"
COST_FILE = "robust_cost.jsonl"
GENERATED = "generated"  # the cost bench's own scene (every preset)

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
# The BVH of whole triangles (cc/robust/preset_check.h kTriangleBvhRow): the
# baseline the Embree section sets beside the kd-tree, checked with the
# watertight test; a row of its own, not a preset, kept out of the totals.
BASELINE = "triangle-bvh"
PRESET_TITLES = dict(kr.TITLES, **{"default": "Default",
                                   SEED: "Pruning, seed mode",
                                   BASELINE: "BVH of whole triangles (baseline)"})

MACROS = ["RobustCases", "RobustCasesPassed", "RobustPresets",
          "RobustRays", "RobustMismatches", "RobustSeedMismatches",
          "RobustSphereRays", "RobustSphereMisses", "RobustFastSphereMisses",
          "RobustSelfHits", "RobustFixedSelfHits", "RobustFixedSkipped",
          "RobustCostScenes", "RobustCostMedian", "RobustCostMin",
          "RobustCostMax", "RobustCostDiffering", "RobustCostCpu",
          "RobustCostWithinNoise", "RobustBaselineRays", "RobustBaselineMismatches"]


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


def _ray_stride(records):
    """The suite's ray stride (robust_suite.py --ray_stride; 1 = every ray)."""
    suites = [r for r in records if r.get("kind") == "suite"]
    return int(suites[-1].get("ray_stride", 1)) if suites else 1


def _cases_table(records, binaries):
    comps = _comparisons(records)
    # The report's presets in order, then any others the suite ran (newer
    # builders), the seed mode last.
    found = {r["preset"] for r in comps}
    presets = list(PRESETS) + sorted(found - set(PRESETS) - {SEED, BASELINE})
    if SEED in found:
        presets.append(SEED)
    if BASELINE in found:
        presets.append(BASELINE)
    numbers = sorted(CASE_TITLES)
    header = ["Preset"] + ["%d" % n for n in numbers]
    body, total_rays, total_bad, seed_bad = [], 0, 0, 0
    baseline = [0, 0]  # rays, mismatches
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
            elif p == BASELINE:
                baseline[0] += rays
                baseline[1] += bad
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
               "by design and is only reported). The last row is not a "
               "preset: the BVH of whole triangles that Section~\\ref{sec:embree} "
               "sets beside the kd-tree, watertight test only, outside the "
               "totals.")
    notes = ["Hard cases: " + "; ".join("%d.~%s" % (n, CASE_TITLES[n])
                                        for n in numbers) + "."]
    stride = _ray_stride(records)
    if stride > 1:
        notes.append("This run checked every %d\\textsuperscript{th} packet "
                     "of 16 of each case's rays (a quick profile); the full "
                     "profile and \\texttt{bazel test} check every ray."
                     % stride)
    tex = latex.booktabs(header, body, align="l" + "r" * len(numbers),
                         caption=caption, label="tab:robust-cases",
                         notes=notes, size="footnotesize")
    n_presets = len(presets) - (SEED in presets) - (BASELINE in presets)
    return tex, total_rays, total_bad, seed_bad, n_presets, baseline


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


def _paired(rec):
    """A cost record of robust_cost_bench's paired format (one per scene and
    preset, both tests timed in rounds), not the old one-per-test format."""
    return (isinstance(rec.get("paired_ratio_runs"), list)
            and rec["paired_ratio_runs"] and isinstance(rec.get("fast"), dict)
            and isinstance(rec.get("watertight"), dict)
            and rec.get("scene") and rec.get("preset"))


def _signed_pct(ratio):
    """Watertight / fast as a signed percentage of extra time: +5.2\\%."""
    cost = 100.0 * (ratio - 1.0)
    return ("+" if cost >= 0 else "$-$") + "%.1f\\%%" % abs(cost)


def cost_verdict(runs):
    """(paired median ratio, lowest, highest, within noise?) of a cost
    record's paired_ratio_runs (watertight / fast per round). Within noise:
    the range over the rounds includes 1, so the two tests' difference lies
    within the measured spread. One round measures no spread: never within
    noise, and the table says it was one round."""
    ratio = statistics.median(runs)
    lo, hi = min(runs), max(runs)
    return ratio, lo, hi, len(runs) >= 2 and lo <= 1.0 <= hi


def _cost_cell(runs):
    ratio, lo, hi, noise = cost_verdict(runs)
    rng = "%s to %s" % (_signed_pct(lo), _signed_pct(hi))
    if noise:
        return "within noise (%s)" % rng
    if len(runs) < 2:
        return "%s (one round)" % _signed_pct(ratio)
    return "%s (%s)" % (_signed_pct(ratio), rng)


def _cost_table(ctx, records):
    """The cost table from the newest paired record of each (scene, preset);
    refuses records of different provenance or from a binary not built for
    timing (analysis/provenance.py, overridden by the context's flags)."""
    latest, old = {}, 0
    for r in records:
        if _paired(r):
            latest[(r["scene"], r["preset"])] = r
        else:
            old += 1
    recs = list(latest.values())
    what = "%s (what robustness costs)" % COST_FILE
    grouped = provenance.check_one_provenance(
        recs, getattr(ctx, "allow_mixed_provenance", False),
        getattr(ctx, "allow_mixed_cpus", False), what)
    provenance.check_timing_builds(
        recs, getattr(ctx, "allow_unoptimized_timings", False), what)
    cpus = provenance.cpus(grouped)
    order = {p: i for i, p in enumerate(PRESETS)}
    rows = sorted(latest.items(), key=lambda x: (
        x[0][0] == GENERATED, x[0][0], order.get(x[0][1], len(order))))
    body, costs, noise, differing = [], [], 0, 0
    for (scene, preset), r in rows:
        runs = [float(x) for x in r["paired_ratio_runs"]]
        ratio, _, _, within = cost_verdict(runs)
        if preset == "default":
            costs.append(100.0 * (ratio - 1.0))
            noise += within
        differing += int(r["mismatches_between_modes"])
        body.append([latex.escape(scene),
                     latex.escape(PRESET_TITLES.get(preset, preset)),
                     latex.fmt_int(r["triangles"]), latex.fmt_int(r["rays"]),
                     latex.fmt_int(len(runs)),
                     latex.fmt_float(r["rays"] / r["fast"]["seconds"] / 1e6),
                     latex.fmt_float(r["rays"] / r["watertight"]["seconds"]
                                     / 1e6),
                     _cost_cell(runs),
                     latex.fmt_int(r["mismatches_between_modes"])])
    if not body:
        return "", costs, noise, differing, cpus, old
    header = ["Scene", "Preset", "$N_{tri}$", "Rays", "Rounds",
              "Fast Mrays/s", "Watertight Mrays/s", "Cost (range)",
              "Answers differing"]
    caption = ("What robustness costs: the same rays (the renderer's primary "
               "rays, then one shadow ray per hit and light) traced on the "
               "same tree, its leaf packets and its vector leaf step, with "
               "the fast (M\\\"oller--Trumbore) and the "
               "watertight triangle test, one thread: a warm-up of each "
               "(not counted), then rounds in which both run, their order "
               "swapping every round, alone on the machine (timing lock). "
               "Mrays/s: of the median run. ``Cost'': extra time of the "
               "watertight test, the median over the rounds of its time "
               "over the fast test's in the same round, with the lowest and "
               "highest round; ``within noise'' when that range includes no "
               "difference. ``Answers differing'': rays whose hit "
               "(triangle, or occlusion) differs between the two tests.")
    notes = None
    if old:
        notes = ["%d records of the old unpaired format (one per test) in "
                 "%s are left out." % (old, latex.escape(COST_FILE))]
    return (latex.booktabs(header, body, align="llrrrrrlr", caption=caption,
                           label="tab:robust-cost", notes=notes,
                           size="footnotesize"),
            costs, noise, differing, cpus, old)


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
        # Not timings: one code and one CPU, whatever the build.
        provenance.check_one_provenance(
            records, getattr(ctx, "allow_mixed_provenance", False),
            getattr(ctx, "allow_mixed_cpus", False),
            "%s (the adversarial suite)" % SUITE_FILE)
        binaries = {r["hard_case"]: r for r in records
                    if r.get("kind") == "binary"}
        tex, rays, bad, seed_bad, n_presets, baseline = _cases_table(records, binaries)
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
            "RobustFixedSkipped": num(f_skip),
            "RobustBaselineRays": num(baseline[0] if baseline[0] else None),
            "RobustBaselineMismatches": num(baseline[1] if baseline[0] else None)})
    cost, costs, noise, differing, cpus, old = _cost_table(ctx, cost_records)
    ctx.write("robust_cost.tex", cost or (
        "\\emph{The robustness cost bench was not run (no paired records in "
        "results/robust\\_cost.jsonl%s).}\n"
        % ("; %d of the old unpaired format left out" % old if old else "")))
    if costs:
        median = "%s" % _signed_pct(1.0 + statistics.median(costs) / 100.0)
        if noise:
            median += " (within noise on %d of %d scenes)" % (noise, len(costs))
        macros.update({
            "RobustCostScenes": (latex.fmt_int(len(costs)), False),
            "RobustCostMedian": (median, True),
            "RobustCostMin": (_signed_pct(1.0 + min(costs) / 100.0), True),
            "RobustCostMax": (_signed_pct(1.0 + max(costs) / 100.0), True),
            "RobustCostDiffering": (latex.fmt_int(differing), False),
            "RobustCostCpu": ("; ".join(cpus) or "unknown", False),
            "RobustCostWithinNoise": (latex.fmt_int(noise), False)})
    return macros
