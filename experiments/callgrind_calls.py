#!/usr/bin/python3
"""Instructions per call, from valgrind's callgrind: the README's count of
the instructions a ray takes through our code and through Embree's.

A cost profile by the clock needs the machine's performance counters, which
these VMs lack; callgrind counts the instructions exactly, the same on every
run. It runs no AVX-512, so build render_bench for AVX2 in an output base of
its own (the timed build is untouched; GCC's -march=haswell lacks AES, which
Highway's AVX2 target needs) and run it under callgrind; Highway's and
Embree's dispatch then both choose their AVX2 code:

    bazel --output_base=/tmp/bz_avx2 build -c opt --copt=-O3 \\
        --copt=-march=haswell --copt=-maes //cc/bench:render_bench
    cp -L bazel-bin/cc/bench/render_bench /tmp/rb_avx2
    # bazel-bin and bazel-out back to the timed build, which bench.py and
    # the runners run from bazel-out/k8-opt/bin:
    bazel build --config=opt //cc/bench:render_bench
    valgrind --tool=callgrind --callgrind-out-file=/tmp/city2.cg \\
        /tmp/rb_avx2 --scenes city2 --preset sah-packet \\
        --variants kd_bvh,kd_bvh_packet --threads 1 --repeats 1 --warmup 0 \\
        --check_rays 0 --embree_robust=false --replay=false
    /usr/bin/python3 experiments/callgrind_calls.py /tmp/city2.cg \\
        'Tracer::(Intersect|Occluded)(Packet)?\\('

For each function whose name matches the pattern, it prints the calls made
to it and the instructions (callgrind's Ir) they took, inclusive, and their
ratio. The tracers' calls (KdTreeBvhTracer, EmbreeTracer) are one ray or one
packet each, so the ratio is instructions per ray or per packet; the
renderer calls each tracer once per render and ray, so the counts cover
several renders of the same rays. (The README's counts of one traversal
function, before and after a change, came from a scratch build that held
both in one binary, with callgrind's --toggle-collect on that function.)
"""

import argparse
import collections
import re
import sys


def calls_per_function(lines):
    """{callee name: (calls, inclusive Ir)} from a callgrind output file's
    lines (its name compression resolved; the cost lines' position columns
    from its `positions:` header, Ir's column from `events:`)."""
    names = {}
    calls = collections.Counter()
    cost = collections.Counter()
    callee = None
    pending = None
    positions = 1  # "line"; "instr line" with --dump-instr=yes
    ir = 0

    def name(text):
        m = re.match(r"\((\d+)\)(?: (.*))?$", text)
        if not m:
            return text
        if m.group(2) is not None:
            names[m.group(1)] = m.group(2)
        return names.get(m.group(1), text)

    for line in lines:
        line = line.rstrip("\n")
        if line.startswith("positions:"):
            positions = len(line.split()) - 1
        elif line.startswith("events:"):
            ir = line.split()[1:].index("Ir")
        elif line.startswith("fn="):
            name(line[3:])
            callee = None
        elif line.startswith("cfn="):
            callee = name(line[4:])
        elif line.startswith("calls="):
            pending = int(line[len("calls="):].split()[0])
        elif pending is not None and line[:1] and (line[0].isdigit() or line[0] in "+-*"):
            fields = line.split()
            if callee is None:  # calls= without a callee: not callgrind's output
                pending = None
                continue
            calls[callee] += pending
            column = positions + ir  # a cost line may omit its trailing zeros
            cost[callee] += int(fields[column]) if len(fields) > column else 0
            pending = None
    return {f: (calls[f], cost[f]) for f in calls}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("profile", help="callgrind's output file")
    ap.add_argument("pattern", help="regular expression for the functions' names")
    args = ap.parse_args(argv)
    try:
        with open(args.profile, errors="replace") as f:
            table = calls_per_function(f)
    except OSError as e:
        print("%s: %s" % (args.profile, e.strerror), file=sys.stderr)
        return 2
    pattern = re.compile(args.pattern)
    rows = sorted((f for f in table if pattern.search(f)), key=lambda f: -table[f][1])
    if not rows:
        print("no function matching %r in %s" % (args.pattern, args.profile), file=sys.stderr)
        return 1
    for f in rows:
        n, ir = table[f]
        print("%12d calls %15d Ir %10.1f Ir/call  %s" % (n, ir, ir / max(n, 1), f))
    return 0


if __name__ == "__main__":
    sys.exit(main())
