#!/usr/bin/python3
"""Tree fingerprints of every preset on a set of scenes, at 1 and 2 build
threads, and their comparison: the check that a change to the builder (or to
anything it reads) leaves every tree byte for byte as it was.

    /usr/bin/python3 experiments/tree_fingerprints.py \\
        --build_bench bazel-out/k8-opt/bin/cc/bench/build_bench --out before.json
    ... (change, rebuild) ... --out after.json
    /usr/bin/python3 experiments/tree_fingerprints.py --compare before.json after.json

build_bench builds each (scene, preset) once per thread count, untimed for
this purpose (one build, no warm-up, no brute-force rays), and itself fails
when two builds of one preset differ; this script keeps
{"scene/preset/threads": fingerprint}, or "failed: <build_bench's last
line>" for a build that fails (pruning-seed, the seed's float pruning, fails
its validation on the engine). --compare exits 0 when both files hold
the same keys with the same fingerprints, 1 otherwise, listing the
differences.

The fingerprint's definition changed at 4c5d23d (it hashes the nodes and the
leaf packets; before, also the report's lists and a second node array, which
the tree no longer keeps): compare files written on the same side of it.
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import jsonl  # noqa: E402  (the results files' one reader)

REPO = Path(__file__).resolve().parent.parent
SCENES = REPO / "data" / "cache" / "scenes"
# Eight scenes of the quick profile, 5k to 250k triangles: scans, CAD, a
# city, foliage, a hairball and instanced teapots.
DEFAULT_SCENES = ("bunny", "armadillo", "engine", "city", "fforest", "hairball-small",
                  "teapots", "lost-empire")


def scene_path(name):
    found = sorted(p for p in SCENES.glob(name + ".*") if p.suffix != ".mtl")
    if not found:
        sys.exit(f"tree_fingerprints: no scene '{name}' in {SCENES} (fetch it first)")
    return found[0]


def collect(args):
    if not args.presets:  # every preset the builder knows (KnownPresetNames)
        args.presets = subprocess.run([args.build_bench, "--list_presets"], check=True,
                                      stdout=subprocess.PIPE, text=True).stdout.strip()
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        records = Path(tmp) / "builds.jsonl"
        for scene in args.scenes.split(","):
            print(f"tree_fingerprints: {scene} ...", file=sys.stderr, flush=True)
            for preset in args.presets.split(","):
                cmd = [args.build_bench, f"--mesh={scene_path(scene)}", f"--name={scene}",
                       f"--presets={preset}", f"--threads={args.threads}", "--repeats=1",
                       "--warmup=0", "--check_rays=0", f"--out={records}"]
                proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                      text=True, cwd=REPO)
                if proc.returncode != 0:  # kept as a result: it must fail the same way
                    why = (proc.stdout.strip().splitlines() or ["?"])[-1]
                    for threads in args.threads.split(","):
                        out[f"{scene}/{preset}/{threads}"] = "failed: " + why
        for r in jsonl.read(records):
            out[f"{r['scene']}/{r['preset']}/{r['threads']}"] = r["tree_fingerprint"]
    Path(args.out).write_text(json.dumps(out, indent=1, sort_keys=True) + "\n")
    failed = sum(1 for v in out.values() if v.startswith("failed"))
    print(f"tree_fingerprints: {len(out)} trees ({failed} builds failed) -> {args.out}",
          file=sys.stderr)


def compare(a_path, b_path):
    a = json.loads(Path(a_path).read_text())
    b = json.loads(Path(b_path).read_text())
    bad = [k for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    for k in bad:
        print(f"{k}: {a.get(k, 'missing')} != {b.get(k, 'missing')}")
    print(f"{len(a)} and {len(b)} trees, {len(bad)} differences")
    return 1 if bad else 0


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build_bench", help="the build_bench binary (an opt build)")
    p.add_argument("--out", help="where to write the fingerprints (JSON)")
    p.add_argument("--scenes", default=",".join(DEFAULT_SCENES))
    p.add_argument("--presets", default="",
                   help="comma-separated (default: every preset, build_bench --list_presets)")
    p.add_argument("--threads", default="1,2")
    p.add_argument("--compare", nargs=2, metavar=("A", "B"))
    args = p.parse_args()
    if args.compare:
        return compare(*args.compare)
    if not args.build_bench or not args.out:
        p.error("--build_bench and --out (or --compare A B)")
    collect(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
