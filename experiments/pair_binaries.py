#!/usr/bin/python3
"""Paired build and render timings of kdrt binaries: is a speed change
outside the noise? (The README's "How the numbers are measured"; render_bench pairs
tracers in one process, this pairs whole binaries.)

    /usr/bin/python3 experiments/pair_binaries.py \
        --binaries OLD,NEW,OLD_COPY --scenes bunny,city [--rounds 5] \
        [--preset sah-packet] [--out pairs.jsonl]

Each round runs every binary once per scene, one process at a time, the
order rotated per round (kdrt --repeats 3 --fast_render --embree off, so a
record holds T_B, T_R, the fast mode's T_R and that of its packets through
the BVH over the tree's leaves, fast_render.packets_bvh, each the median of
its process's runs); round 0 is a warm-up and is dropped. Per scene and
binary after the first, it prints the median over the rounds of (this
binary's time / the first's in the same round) with the min..max, for T_B,
T_R, the fast mode and its BVH packets ("n/a" where a binary's records lack
them). Give a copy of the old binary as the
last one: its ratios are the control, the noise a real change must clear.
Every record goes to --out (one JSON line per run, with the image hash: the
binaries must render the same image).
"""

import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import jsonl  # noqa: E402  (the results files' one appender)
import run_matrix  # noqa: E402  (run_kdrt: one kdrt process, its record)


COLUMNS = ("T_B", "T_R", "fast", "fast_bvh")


def ratios(times, reference):
    """Per round, time / the reference's time in that round, for each column
    (T_B, T_R, the fast mode, ...): [(t_b ratio, t_r ratio, ...)]; None
    where either time is None."""
    return [tuple(None if a is None or b is None else a / b for a, b in zip(t, r))
            for t, r in zip(times, reference)]


def summary(pairs):
    """(median, min, max) of each column of ratios(), over its rounds with a
    ratio; None for a column with none."""
    out = []
    for c in zip(*pairs):
        c = [x for x in c if x is not None]
        out.append((statistics.median(c), min(c), max(c)) if c else None)
    return out


def row(rec):
    """A record's times, in COLUMNS' order (None: not in the record)."""
    fast = rec["fast_render"]
    return (rec["T_B"], rec["T_R"], fast["T_R"], fast.get("packets_bvh", {}).get("T_R"))


def run(binary, scene, preset):
    returncode, stderr, records, _, cmd = run_matrix.run_kdrt(
        [binary, "--scene", scene, "--preset", preset, "--repeats", "3", "--threads", "1",
         "--embree", "off", "--fast_render"])
    if returncode != 0 or not records:
        raise RuntimeError("%s failed (%d): %s" % (" ".join(cmd), returncode, stderr[-500:]))
    return records[-1]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--binaries", required=True, help="comma-separated; the first is the reference")
    p.add_argument("--scenes", required=True)
    p.add_argument("--rounds", type=int, default=5, help="kept rounds (a warm-up round runs first)")
    p.add_argument("--preset", default="sah-packet")
    p.add_argument("--out", default="pair_binaries.jsonl")
    args = p.parse_args(argv)
    bins, scenes = args.binaries.split(","), args.scenes.split(",")
    times = {(s, b): [] for s in scenes for b in bins}
    images = {s: set() for s in scenes}
    for r in range(args.rounds + 1):
        for s in scenes:
            for b in bins[r % len(bins):] + bins[:r % len(bins)]:
                rec = run(b, s, args.preset)
                images[s].add(rec["image_fnv64"])
                times_now = row(rec)
                jsonl.append(args.out, {"round": r, "scene": s, "binary": b,
                                        **dict(zip(COLUMNS, times_now)),
                                        "image_fnv64": rec["image_fnv64"]})
                if r > 0:
                    times[(s, b)].append(times_now)
    for s in scenes:
        for b in bins[1:]:
            cols = summary(ratios(times[(s, b)], times[(s, bins[0])]))
            print("%s %s %s" % (s, b, " | ".join(
                "%s n/a" % name if c is None else "%s %.3f [%.3f..%.3f]" % (name, *c)
                for name, c in zip(COLUMNS, cols))))
        if len(images[s]) != 1:
            print("%s: the binaries rendered %d different images" % (s, len(images[s])))
    return 0 if all(len(v) == 1 for v in images.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
