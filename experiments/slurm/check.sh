#!/usr/bin/env bash
# Runs a profile's matrix twice, locally and through a live one-node SLURM
# cluster started here, and checks that every non-timing statistic agrees
# (one timed round each: only the statistics are compared).
# Stops every daemon it started (by PID), whatever happens.
#
#   PROFILE=quick bash experiments/slurm/check.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT="$(pwd)"
PROFILE="${PROFILE:-quick}"
OUT="${OUT:-$ROOT/out/slurm-check}"
PY=/usr/bin/python3

bash experiments/setup.sh --with-slurm
"$PY" data/fetch.py --profile "$PROFILE" || [ $? -eq 1 ]
bazel build --config=opt //cc/tools:kdrt
KDRT="$(bazel info --config=opt bazel-bin)/cc/tools/kdrt"

CLUSTER="$(mktemp -d /tmp/kdtree-slurm.XXXXXX)"
trap 'bash experiments/slurm/cluster.sh stop "$CLUSTER"' EXIT
eval "$(bash experiments/slurm/cluster.sh start "$CLUSTER")"

rm -rf "$OUT"
start=$(date +%s)
"$PY" experiments/run_matrix.py --profile "$PROFILE" --kdrt "$KDRT" \
  --out "$OUT/slurm" --backend slurm --embree off --repeats 1
slurm_s=$(( $(date +%s) - start ))
start=$(date +%s)
"$PY" experiments/run_matrix.py --profile "$PROFILE" --kdrt "$KDRT" \
  --out "$OUT/local" --backend local --embree off --repeats 1
local_s=$(( $(date +%s) - start ))
echo "slurm-check: profile $PROFILE: SLURM ${slurm_s} s, local ${local_s} s"
"$PY" experiments/compare_results.py "$OUT/local/results/kdtree.jsonl" \
  "$OUT/slurm/results/kdtree.jsonl"
