#!/usr/bin/python3
"""In-process A/B: two tracers of one render_bench process, paired per round.
The method behind the code comments' "in-process A/B (the change on AVX3_DL
against the old code on AVX3, 7 paired rounds)": put the change under
`#if HWY_TARGET == HWY_AVX3_DL` (the old code on the other targets), build,
and time `kd_bvh_packet@AVX3` against `kd_bvh_packet@AVX3_DL` in the same
rounds of one process, so that the machine's slow and fast stretches fall on
both. The control is the same code on both targets; a change must clear its
spread.

    /usr/bin/python3 experiments/pair_variants.py \\
        --base kd_bvh_packet@AVX3 --variant kd_bvh_packet@AVX3_DL \\
        --scenes bunny,city2 --out out/ab.jsonl [--repeats 7] [--run]

With --run it first runs render_bench once per scene (one thread, sah-packet,
Embree off, only the two tracers; with --alone also the replays), appending
to --out; without, it reads --out. Per scene it prints the median over the
rounds of the variant's time over the base's, with the min..max: whole
renders (T_R) and each pass (camera, shadow), as the comments quote them;
with --alone each pass by its tracing time alone (the replay of its mode
subtracted, round by round), which a change moves further but which is
noisier where the renderer's own work is most of a pass. Below 1: the
variant is faster.
"""

import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_tables import key_runs, per_round_ratio, tracing_runs  # noqa: E402
from provenance import opt_binary  # noqa: E402
import jsonl  # noqa: E402  (the results files' one reader)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COLUMNS = (("T_R", "T_R_runs"), ("camera", "primary_s_runs"), ("shadow", "secondary_s_runs"))


def pair(record, base, variant, alone=False):
    """{column: (median, min, max) of variant / base per round, or None};
    alone: each pass's tracing time alone (None without the replays)."""
    t = record.get("tracers", {})
    out = {}
    for label, key in COLUMNS:
        runs_of = tracing_runs(key) if alone and key != "T_R_runs" else key_runs(key)
        # per_round_ratio: per round, its first group's time over its second's.
        out[label] = per_round_ratio(t, (variant,), (base,), runs_of)
    return out


def lines(records, base, variant, alone=False):
    out = []
    for r in records:
        if base not in r.get("tracers", {}) or variant not in r.get("tracers", {}):
            continue
        cells = []
        for label, v in pair(r, base, variant, alone).items():
            cells.append("%s -" % label if v is None else
                         "%s %.3f [%.3f..%.3f]" % (label, v[0], v[1], v[2]))
        mismatches = r.get("validation", {}).get("variants_vs_kd_mismatches", {})
        bad = {k: n for k, n in mismatches.items() if n}
        out.append("%-24s %s%s" % (r.get("scene", "?"), "  ".join(cells),
                                   "  MISMATCHES %s" % bad if bad else ""))
    return out


def run(args):
    binary = args.render_bench or opt_binary("cc", "bench", "render_bench")
    for scene in args.scenes.split(","):
        subprocess.run([binary, "--repo", ROOT, "--scenes", scene, "--preset", args.preset,
                        "--threads", "1", "--repeats", str(args.repeats), "--warmup", "1",
                        "--variants", "%s,%s" % (args.base, args.variant), "--embree", "off",
                        "--embree_robust=false", "--embree_packets=false",
                        "--replay=%s" % ("true" if args.alone else "false"),
                        "--out", args.out], check=True, stdout=subprocess.DEVNULL)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--base", required=True, help="render_bench tracer name (the old code)")
    p.add_argument("--variant", required=True, help="render_bench tracer name (the change)")
    p.add_argument("--out", required=True, help="render_bench's JSON lines (read; --run appends)")
    p.add_argument("--run", action="store_true", help="run render_bench first")
    p.add_argument("--scenes", default="bunny", help="comma-separated, with --run")
    p.add_argument("--repeats", type=int, default=7, help="paired rounds, with --run")
    p.add_argument("--preset", default="sah-packet")
    p.add_argument("--alone", action="store_true",
                   help="each pass by its tracing time alone (render_bench --replay)")
    p.add_argument("--render_bench", help="binary (default: the --config=opt build's)")
    args = p.parse_args(argv)
    if args.run:
        run(args)
    if not os.path.exists(args.out):
        sys.exit("pair_variants: no file %s" % args.out)
    try:
        records = jsonl.read(args.out)
    except ValueError as e:  # a line that is not a record
        sys.exit("pair_variants: %s" % e)
    print("\n".join(lines(records, args.base, args.variant, args.alone))
          or "no record has both tracers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
