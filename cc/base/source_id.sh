#!/bin/sh
# The code identity of a checkout, one line: COMMIT DIRTY SOURCE_TREE.
#
#   sh cc/base/source_id.sh [REPO_ROOT]
#
# COMMIT: HEAD. DIRTY: "true" when the working tree (tracked files and
# untracked files that are not ignored) differs from HEAD, else "false".
# SOURCE_TREE: a 40-hex id of the working tree's paths that build and
# configure the tools, SOURCE_PATHS below (the C++ sources, the build files,
# the presets and the scene manifest with its cameras): two checkouts with the
# same id build the same binaries and run them on the same inputs, whatever
# their commits and whatever else (analysis, report, README) differs. Edits not
# yet committed count: the working tree is staged into a temporary index, never
# into the repository's own.
#
# The one implementation: cc/base/provenance.cc (the C++ records) and
# experiments/provenance.py (the runners' job keys) both run this script.
# Exit 1, with a message, outside a git checkout.
set -eu
cd "${1:-.}"
SOURCE_PATHS="cc .bazelrc WORKSPACE BUILD experiments/presets data/manifest.json"
commit=$(git rev-parse --verify -q HEAD 2>/dev/null) || { echo "source_id: $(pwd): not a git checkout with a commit" >&2; exit 1; }
index=$(mktemp)
trap 'rm -f "$index"' EXIT
cp "$(git rev-parse --git-path index)" "$index" 2>/dev/null || rm -f "$index"
GIT_INDEX_FILE="$index" git add -A . 2>/dev/null
tree=$(GIT_INDEX_FILE="$index" git write-tree)
dirty=false
[ "$tree" = "$(git rev-parse "HEAD^{tree}")" ] || dirty=true
# shellcheck disable=SC2086
source_tree=$(git ls-tree "$tree" -- $SOURCE_PATHS | git hash-object --stdin)
echo "$commit $dirty $source_tree"
