"""The code identity the runners key their finished jobs on: the commit, whether
the checkout is dirty, and the source tree id of cc/base/source_id.sh (the
tools' sources, build files, presets and scene manifest, uncommitted edits
included). The same script gives the C++ records their provenance
(cc/base/provenance.cc), so a record's provenance.source_tree and the runner's
key agree; pin() fixes it for a whole run ($KDTREE_SOURCE_ID). $KDTREE_GIT_COMMIT and $KDTREE_SOURCE_TREE replace the commit and the
source tree when set, as in the C++ tools (tests, SLURM tasks).

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
