#!/usr/bin/python3
"""The report's "visible artifacts", tested: a voxel world (every face lies
exactly in an integer plane, where split planes fall) built with each of the
nine variants in the seed-compatible mode (its strict partition loses
triangles that lie in a split plane) and in our default mode (loses none).

    /usr/bin/python3 experiments/run_planar.py [--kdrt PATH] [--scene lost-empire]

--kdrt defaults to bazel-out/k8-opt/bin/cc/tools/kdrt, the --config=opt build's.

Writes OUT/results/planar.jsonl (one kdrt record per variant and mode,
append-only; a (scene, variant, mode) already recorded is not rerun), the
images to OUT/images/planar/<scene>_<variant>_<mode>.png and the seed mode's
cost images to OUT/costs/planar/<scene>_<variant>_seed.npy.gz.
"""

import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))

import jsonl  # noqa: E402
import provenance  # noqa: E402
import run_matrix  # noqa: E402

RESULTS_FILE = "planar.jsonl"
MODES = {"seed": "on", "default": "off"}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    run_matrix.add_kdrt_flag(p)
    p.add_argument("--scene", default="lost-empire")
    p.add_argument("--out", default=os.path.join(ROOT, "out"))
    args = p.parse_args(argv)
    if run_matrix.kdrt_missing(args.kdrt, "run_planar"):
        return 2
    results = os.path.join(args.out, "results")
    images = os.path.join(args.out, "images", "planar")
    os.makedirs(results, exist_ok=True)
    os.makedirs(images, exist_ok=True)
    path = os.path.join(results, RESULTS_FILE)
    # Done: recorded from the same code (experiments/provenance.py).
    tree = provenance.pin()["source_tree"]
    done = {(r["scene"], r["preset"], r["mode"]) for r in jsonl.read_resuming(path, "resume")
            if provenance.record_source_tree(r) == tree}
    failures = 0
    for variant in run_matrix.load_matrix()["variants"]:
        for mode, flag in MODES.items():
            if (args.scene, variant, mode) in done:
                continue
            label = "%s_%s" % (variant, mode)
            image = os.path.join(images, "%s_%s.png" % (args.scene, label))
            cmd = [args.kdrt, "--scene", args.scene, "--preset", variant,
                   "--seed_compatible", flag, "--label", label,
                   "--repeats", "1", "--image", image]
            if mode == "seed":
                # The seed mode's cost images (analysis/cost_images.py).
                cmd += ["--cost_image", os.path.join(
                    args.out, "costs", "planar", "%s_%s.npy.gz" % (args.scene, label))]
            returncode, stderr, lines, _, _ = run_matrix.run_kdrt(cmd)
            if returncode != 0 or not lines:
                failures += 1
                print("planar: %s %s failed: %s" % (variant, mode,
                      stderr[-500:]), file=sys.stderr)
                continue
            rec = lines[-1]
            rec.update({"mode": mode, "preset": variant, "ok": True})
            jsonl.append(path, rec)
            print("planar: %s %-18s %-7s lost %s, P_hit %s"
                  % (args.scene, variant, mode, rec.get("N_lost_planar"),
                     rec.get("P_hit")), file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
