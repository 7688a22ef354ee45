"""Turns raw results into everything report/main.tex inputs.

    /usr/bin/python3 -m analysis.make_all --results out/results \
        --manifest data/manifest.json --out report/generated

Each module in GENERATORS has `generate(ctx) -> {Macro: (value, raw)}` and
writes its own files (see analysis/context.py). The output directory is
rebuilt from scratch on every run (in a temporary directory, swapped in only
when every generator succeeded), so the report never picks up a stale table
from an earlier run, and a failing generator leaves no half-made directory.

Records of different provenance (code, compilation mode, CPU) never share a
table, and timings of a binary not built for timing are never shown
(analysis/provenance.py), unless --allow_mixed_provenance, --allow_mixed_cpus
or --allow_unoptimized_timings says otherwise.

To add Table N or a figure: write analysis/<name>.py with generate(ctx),
append it to GENERATORS, \\input its file in report/main.tex.
"""

import argparse
import os
import shutil
import sys

# Run as a script (python3 analysis/make_all.py) as well as with -m.
if __package__ in (None, ""):
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
        __file__))))

from analysis import accuracy  # noqa: E402
from analysis import claims  # noqa: E402
from analysis import clipping_errata  # noqa: E402
from analysis import context  # noqa: E402
from analysis import cost_images  # noqa: E402
from analysis import embree  # noqa: E402
from analysis import embree_build  # noqa: E402
from analysis import embree_passes  # noqa: E402
from analysis import embree_structure  # noqa: E402
from analysis import figures  # noqa: E402
from analysis import gallery  # noqa: E402
from analysis import kdtree_figures  # noqa: E402
from analysis import kdtree_tables  # noqa: E402
from analysis import latex  # noqa: E402
from analysis import machine  # noqa: E402
from analysis import planar  # noqa: E402
from analysis import provenance_macros  # noqa: E402
from analysis import robustness  # noqa: E402
from analysis import row18  # noqa: E402
from analysis import seed_tables  # noqa: E402
from analysis import table1  # noqa: E402
from analysis import tree_memory  # noqa: E402

# Order matters only for readability of macros.tex.
GENERATORS = [
    machine,
    provenance_macros,
    table1,
    seed_tables,
    row18,
    clipping_errata,
    planar,
    figures,
    kdtree_tables,
    kdtree_figures,
    cost_images,
    claims,
    embree,
    embree_build,
    embree_passes,
    embree_structure,
    tree_memory,
    accuracy,
    robustness,
    gallery,
]

MARKER = ".generated-by-analysis"


def make_all(results_dir, manifest_path, out_dir, generators=None,
             allow_mixed_cpus=False, allow_mixed_provenance=False,
             allow_unoptimized_timings=False):
    """Runs every generator into a fresh out_dir; returns the files written.
    The allow_* flags override analysis/provenance.py's refusals."""
    generators = GENERATORS if generators is None else generators
    out_dir = os.path.abspath(out_dir)
    if os.path.isdir(out_dir) and os.listdir(out_dir) and not os.path.exists(
            os.path.join(out_dir, MARKER)):
        raise RuntimeError("%s exists and was not made by make_all; refusing "
                           "to replace it" % out_dir)
    staging = out_dir + ".new"
    if os.path.exists(staging):
        shutil.rmtree(staging)
    os.makedirs(staging)
    try:
        ctx = context.Context(
            results_dir, manifest_path, staging,
            allow_mixed_provenance=allow_mixed_provenance,
            allow_mixed_cpus=allow_mixed_cpus,
            allow_unoptimized_timings=allow_unoptimized_timings)
        macros = {}
        for gen in generators:
            for name, value in gen.generate(ctx).items():
                if name in macros:
                    raise RuntimeError("macro \\%s defined twice (%s)"
                                       % (name, gen.__name__))
                macros[name] = value
        ctx.write("macros.tex", latex.macros_file(
            macros, header="Results: %s\nManifest: %s"
            % (os.path.abspath(results_dir), os.path.abspath(manifest_path))))
        latex.write_text(os.path.join(staging, MARKER),
                         "".join(f + "\n" for f in ctx.written))
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    if os.path.exists(out_dir):
        shutil.rmtree(out_dir)
    os.rename(staging, out_dir)
    return list(ctx.written)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="out/results",
                        help="directory of raw results (scenes.jsonl, ...)")
    parser.add_argument("--manifest", default="data/manifest.json")
    parser.add_argument("--out", default="report/generated")
    parser.add_argument("--allow_mixed_cpus", action="store_true",
                        help="put timings from different CPUs in one table")
    parser.add_argument("--allow_mixed_provenance", action="store_true",
                        help="put records of different code (source tree, "
                        "compilation mode) in one table")
    parser.add_argument("--allow_unoptimized_timings", action="store_true",
                        help="show timings from binaries not built for "
                        "timing (provenance timing_build false)")
    args = parser.parse_args(argv)
    try:
        written = make_all(
            args.results, args.manifest, args.out,
            allow_mixed_cpus=args.allow_mixed_cpus,
            allow_mixed_provenance=args.allow_mixed_provenance,
            allow_unoptimized_timings=args.allow_unoptimized_timings)
    except (RuntimeError, ValueError, OSError) as e:
        print("make_all: error: %s" % e, file=sys.stderr)
        return 1
    for f in written:
        print(os.path.join(args.out, f))
    return 0


if __name__ == "__main__":
    sys.exit(main())
