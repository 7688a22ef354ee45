#!/usr/bin/env bash
# README command 1: the whole reproduction, from scenes to out/report.pdf.
#
#   PROFILE=quick bash experiments/reproduce.sh     # test|quick|standard|full
#
# Runs from anywhere; idempotent and resumable (set-up installs nothing twice,
# fetched scenes are cached, scenes already measured are skipped).
# Raw results: out/results/ (append-only). Report: out/report.pdf.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
PROFILE="${PROFILE:-quick}"
PY=/usr/bin/python3
OUT="$ROOT/out"
RESULTS="$OUT/results"

START_S=$(date +%s)
# Each step prints the wall time since the start, so a log shows what took long.
step() { printf '\n==> [%s, +%d s] %s\n' "$(date +%T)" $(( $(date +%s) - START_S )) "$*"; }

step "set-up (Debian packages, idempotent)"
bash experiments/setup.sh --with-report --with-blender

step "fetch scenes (profile $PROFILE)"
# Exit 1 means some scene could not be obtained: go on with the others.
# Any other failure (crash, bad usage) stops here.
fetch_rc=0
"$PY" data/fetch.py --profile "$PROFILE" || fetch_rc=$?
if [ "$fetch_rc" -eq 1 ]; then
  echo "reproduce: some scenes of profile '$PROFILE' could not be obtained;" \
       "continuing with those that were" >&2
elif [ "$fetch_rc" -ne 0 ]; then
  echo "reproduce: data/fetch.py failed (exit $fetch_rc)" >&2
  exit "$fetch_rc"
fi

step "build tools"
# One configuration for everything timed (.bazelrc's opt: -c opt -O3
# -march=native), the one the benchmarks use, so that a ratio means the same
# whichever tool measured it.
bazel build --config=opt //cc/tools:scene_info //cc/tools:kdrt //cc/seed:row18_tool
BIN="$(bazel info --config=opt bazel-bin)"
# The bazel-bin symlink follows whichever configuration was built last: ask
# for the opt output directory instead of trusting it.
SCENE_INFO="$BIN/cc/tools/scene_info"
# The code these binaries were built from, pinned for every step's records
# and job keys (cc/base/provenance.h), whatever happens to the checkout later.
KDTREE_SOURCE_ID="$(sh cc/base/source_id.sh "$ROOT")"
export KDTREE_SOURCE_ID
echo "reproduce: code $KDTREE_SOURCE_ID (commit, dirty, source tree)"
# Binaries built later in the run (the robustness step's) must be the code
# the records name: refuse to build them from a checkout whose sources
# changed since the pin above.
same_sources() {
  local now
  now="$(sh cc/base/source_id.sh "$ROOT")"
  if [ "${now##* }" != "${KDTREE_SOURCE_ID##* }" ]; then
    echo "reproduce: the sources changed since this run began (source tree" \
      "${KDTREE_SOURCE_ID##* }, now ${now##* }); $1 would not be the code the" \
      "records name. Rerun reproduce.sh once the checkout is settled." >&2
    return 1
  fi
}

step "load scenes (scene_info)"
"$PY" experiments/run_scenes.py --profile "$PROFILE" --out "$OUT" \
  --scene_info "$SCENE_INFO"

step "scene 18 in the seed-compatible mode (row18.jsonl)"
# Blender makes Suzanne headless; deterministic, so it is rerun every time.
mkdir -p "$RESULTS"
ROW18_TMP="$(mktemp -d)"
"$BIN/cc/seed/row18_tool" --work_dir "$ROW18_TMP" \
  --expected "$ROOT/data/seed/row18.csv" > "$RESULTS/row18.jsonl.new"
mv "$RESULTS/row18.jsonl.new" "$RESULTS/row18.jsonl"
rm -rf "$ROW18_TMP"

step "kd-tree matrix: the report's nine variants, sah-packet and sah-packet-binned on every scene ($PROFILE)"
# Resumable: finished (scene, variant) runs are not rerun.
"$PY" experiments/run_matrix.py --profile "$PROFILE" --kdrt "$BIN/cc/tools/kdrt" \
  --out "$OUT"

step "in-plane triangles: seed-compatible vs default mode on a voxel world"
"$PY" experiments/run_planar.py --kdrt "$BIN/cc/tools/kdrt" --out "$OUT" || \
  echo "reproduce: some planar runs failed (see above)" >&2

step "robustness: the adversarial suite and what the watertight test costs"
# Nothing is rebuilt or rerun that the results hold for this code (the source
# tree id of cc/base/source_id.sh): the suite when robust.jsonl holds a
# complete, passing run of it for this profile, a cost run when
# robust_cost.jsonl holds that (scene, preset) with as many rounds; the script
# says what it skips. Else: the case binaries (untimed checks, one per core),
# then the cost bench alone (a warm-up of each triangle test, then rounds
# alternating them under the timing lock, ratios paired per round). Built
# with --config=opt like the tools above, so their libraries are not rebuilt
# (-c opt and --config=opt share bazel-out/k8-opt with different flags: mixing
# them rebuilds everything each time).
# Rounds per cost run: 3 in test and quick, 5 (the report's repeats) else.
# Rays of the suite: test and quick check every 4th packet of each case's
# rays (every preset, mode and scene still runs; the report says so), the
# other profiles and bazel test every ray.
case "$PROFILE" in test|quick) COST_REPEATS=3; RAY_STRIDE=4 ;; *) COST_REPEATS=5; RAY_STRIDE=1 ;; esac
ROBUST_ARGS=(--out "$RESULTS/robust.jsonl" --cost_out "$RESULTS/robust_cost.jsonl"
  --profile "$PROFILE" --repeats "$COST_REPEATS" --ray_stride "$RAY_STRIDE")
ROBUST_TARGETS="$("$PY" cc/robust/robust_suite.py "${ROBUST_ARGS[@]}" --cost --print_targets)" || \
  ROBUST_TARGETS="//cc/robust:robust_suite //cc/robust:robust_cost_bench"
if [ -n "$ROBUST_TARGETS" ]; then
  same_sources "the robustness binaries" || exit 1
  # shellcheck disable=SC2086
  bazel build --config=opt $ROBUST_TARGETS
  ROBUST_BIN="$BIN/cc/robust"
  "$PY" cc/robust/robust_suite.py "${ROBUST_ARGS[@]}" --bin_dir "$ROBUST_BIN" \
    --compilation_mode opt --cost_bench "$ROBUST_BIN/robust_cost_bench" \
    --jobs "$(nproc)" || echo "reproduce: some robustness runs failed (see above)" >&2
fi

step "accuracy versus time: what each step of tree accuracy costs ($PROFILE)"
# experiments/accuracy.json; resumable (finished (scene, step) runs are skipped).
"$PY" experiments/run_accuracy.py --profile "$PROFILE" --kdrt "$BIN/cc/tools/kdrt" \
  --out "$OUT" || echo "reproduce: some accuracy runs failed (see above)" >&2

step "analysis (tables, figures, macros)"
"$PY" -m analysis.make_all --results "$RESULTS" \
  --manifest data/manifest.json --out report/generated

step "report (LaTeX)"
mkdir -p report/build
latexmk -pdf -cd -interaction=nonstopmode -halt-on-error \
  -output-directory=build report/main.tex
cp report/build/main.pdf "$OUT/report.pdf"
# Every table at 80 % of the body font or more, no figure shrunk below 80 %
# (issue 25); a table or figure below is listed and the run says so, but the
# PDF is kept (//analysis:report_pdf_test fails on it).
"$PY" -m analysis.table_scale report/build/main.log --body_pt 11 --strict ||
  echo "reproduce: a table or figure of the report is set below 80 % (listed above)" >&2
echo
echo "reproduce: report at $OUT/report.pdf ($(( $(date +%s) - START_S )) s in all)"
