"""The code identity the runners key their finished jobs on: the commit, whether
the checkout is dirty, and the source tree id of cc/base/source_id.sh (the
tools' sources, build files, presets and scene manifest, uncommitted edits
included). The same script gives the C++ records their provenance
(cc/base/provenance.cc), so a record's provenance.source_tree and the runner's
key agree; pin() fixes it for a whole run ($KDTREE_SOURCE_ID). $KDTREE_GIT_COMMIT and $KDTREE_SOURCE_TREE replace the commit and the
source tree when set, as in the C++ tools (tests, SLURM tasks).

It also names the machine as the C++ records do (cc/base/provenance.cc
CpuIdentity, CpuCaches; the same formats, provenance_test checking the cases
of cc/base/provenance_test.cc): machine() for the runners that write their
own records (experiments/run_scenes.py's machine.json,
cc/robust/robust_suite.py).

Standard library only.
"""

import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = os.path.join("cc", "base", "source_id.sh")
# The identity a runner pinned when the tools were built (the script's line):
# every record of the run names that code, even if the checkout is edited
# while it runs. Read here and by cc/base/provenance.cc.
PIN = "KDTREE_SOURCE_ID"


def opt_binary(*parts, root=ROOT):
    """The path of a tool in the optimised build, the one the timings need:
    bazel-out/k8-opt/bin/PARTS, where --config=opt builds (and -c opt, with
    other flags: reproduce.sh builds with --config=opt and asks `bazel info
    --config=opt bazel-bin` for this directory; k8: the tools are x86 only).
    Not bazel-bin, which follows whichever configuration was built last (a
    test build, say)."""
    return os.path.join(root, "bazel-out", "k8-opt", "bin", *parts)


def pin(root=ROOT):
    """Pins the checkout's identity now (unless already pinned) for this
    process and the tools it starts; returns code_identity()."""
    if not os.environ.get(PIN):
        try:
            os.environ[PIN] = subprocess.run(
                ["sh", os.path.join(root, SCRIPT), root], stdout=subprocess.PIPE,
                stderr=subprocess.DEVNULL, text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            pass
    return code_identity(root)


def code_identity(root=ROOT):
    """{"commit", "dirty", "source_tree"}; commit and source_tree are None
    outside a git checkout."""
    ident = {"commit": None, "dirty": False, "source_tree": None}
    try:
        out = os.environ.get(PIN, "").split() or subprocess.run(
            ["sh", os.path.join(root, SCRIPT), root], stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL, text=True, check=True).stdout.split()
        if len(out) == 3:
            ident = {"commit": out[0], "dirty": out[1] == "true",
                     "source_tree": out[2]}
    except (OSError, subprocess.CalledProcessError):
        pass
    if os.environ.get("KDTREE_GIT_COMMIT"):
        ident["commit"] = os.environ["KDTREE_GIT_COMMIT"]
    if os.environ.get("KDTREE_SOURCE_TREE"):
        ident["source_tree"] = os.environ["KDTREE_SOURCE_TREE"]
    return ident


def record_source_tree(rec):
    """The source tree a result record was made from, or None."""
    prov = rec.get("provenance")
    return prov.get("source_tree") if isinstance(prov, dict) else None


def short(ident):
    """'0123456789ab' or '0123456789ab+dirty <tree[:12]>' for messages."""
    commit = (ident.get("commit") or "unknown")[:12]
    if ident.get("dirty"):
        return "%s+dirty %s" % (commit, (ident.get("source_tree") or "?")[:12])
    return commit


# --- the machine -------------------------------------------------------------

def cpu_value(key, cpuinfo="/proc/cpuinfo"):
    """The value of cpuinfo's first line whose key is exactly `key` ("model"
    is not "model name"), None when there is none or the file is
    unreadable (provenance.cc CpuInfoValue)."""
    try:
        # newline="\n": lines end where std::getline ends them.
        with open(cpuinfo, encoding="utf-8", errors="replace", newline="\n") as f:
            for line in f:
                name, colon, value = line.partition(":")
                if colon and name.rstrip(" \t") == key:
                    return value.lstrip(" \t").rstrip("\n") or None
    except OSError:
        pass
    return None


def cpu_id(cpuinfo="/proc/cpuinfo"):
    """"GenuineIntel family 6 model 106 stepping 6" (provenance.cc
    CpuIdentity), None without a family and a model."""
    def get(key):
        return cpu_value(key, cpuinfo)
    family, model = get("cpu family"), get("model")
    if not family or not model:
        return None
    vendor, stepping = get("vendor_id"), get("stepping")
    text = (vendor + " " if vendor else "") + "family %s model %s" % (family, model)
    return text + (" stepping " + stepping if stepping else "")


def cpu_caches(cache_dir="/sys/devices/system/cpu/cpu0/cache"):
    """"L1d 48K, L1i 32K, L2 1280K, L3 49152K" from sysfs (provenance.cc
    CpuCaches: index0, index1, ... up to the first without a level or a
    size), None when there is none."""
    def first_line(path):
        try:
            with open(path, encoding="utf-8", errors="replace", newline="\n") as f:
                return f.readline().rstrip("\n")
        except OSError:
            return ""
    parts = []
    for i in range(16):
        d = os.path.join(cache_dir, "index%d" % i)
        level, size = first_line(os.path.join(d, "level")), first_line(os.path.join(d, "size"))
        if not level or not size:
            break
        suffix = {"Data": "d", "Instruction": "i"}.get(first_line(os.path.join(d, "type")), "")
        parts.append("L%s%s %s" % (level, suffix, size))
    return ", ".join(parts) or None


def cores():
    """The CPUs this process may run on (the C++ records' "cores")."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 0


def machine(cpuinfo="/proc/cpuinfo", cache_dir="/sys/devices/system/cpu/cpu0/cache"):
    """The machine fields of a record's provenance, as the C++ records name
    them: cpu_model (/proc/cpuinfo's "model name", as written), cpu_id,
    cpu_caches and cores."""
    return {"cpu_model": cpu_value("model name", cpuinfo), "cpu_id": cpu_id(cpuinfo),
            "cpu_caches": cpu_caches(cache_dir), "cores": cores()}
