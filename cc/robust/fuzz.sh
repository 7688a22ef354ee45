#!/bin/bash
# Builds the libFuzzer targets with clang and runs each for a while, keeping a
# record of every run (issue 24: long fuzzing runs, documented).
#
#   cc/robust/fuzz.sh [SECONDS] [FUZZER ...]
#   cc/robust/fuzz.sh --build-only [FUZZER ...]
#
# SECONDS per fuzzer (default 600); FUZZER any of traversal, mesh, env_file
# (default all three, one after the other). Needs clang 14 and libclang-rt
# (libFuzzer, ASan, UBSan; `experiments/setup.sh --with-fuzz`) beside the
# Debian packages of setup.sh. The Bazel toolchain is gcc, which has no
# libFuzzer, so the targets are built here by clang, from the sources of the
# Bazel library each target wraps (bazel query: a file added to one of its
# dependencies is compiled here too). --build-only builds them and runs
# nothing: experiments/test.sh does that, so a fuzzer that stops linking
# fails the tests. Corpora stay in out/fuzz/corpus/NAME (reused by
# the next run), logs in out/fuzz/NAME.log, crashes in out/fuzz/NAME/, and
# one JSON line per run goes to out/fuzz/runs.jsonl (date, commit, fuzzer,
# seconds, executions, exit code, findings). Nothing here is committed.
#
# The deterministic smoke runs of the same cases are in `bazel test`
# (traversal_fuzz_test, mesh_fuzz_test, env_file_fuzz_test).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_ONLY=0
if [ "${1:-}" = --build-only ]; then
  BUILD_ONLY=1
  shift
else
  SECONDS_EACH="${1:-600}"
  shift || true
fi
FUZZERS=("$@")
[ ${#FUZZERS[@]} -eq 0 ] && FUZZERS=(traversal mesh env_file)
if ! command -v clang++ > /dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a > /dev/null 2>&1; then
  echo "fuzz.sh: needs clang and libFuzzer: apt-get install clang-14 libclang-rt-14-dev" >&2
  exit 2
fi
OUT=out/fuzz
mkdir -p "$OUT/bin"

# The .cc files of a Bazel target and of everything it depends on in this
# repository.
sources_of() {
  bazel query "kind('source file', deps($1))" 2> /dev/null |
    grep '^//.*\.cc$' | sed 's#^//##; s#:#/#' || true
}
ABSL="$(pkg-config --libs absl_status absl_statusor absl_str_format absl_strings \
  absl_synchronization absl_hash absl_raw_hash_set)"
# Every system library any of the targets needs (unused ones cost nothing).
LIBS=(-ltbb -lhwy -lassimp -lz $ABSL)
FLAGS=(-std=c++17 -O1 -g -ffp-contract=off -fsanitize=fuzzer,address,undefined -I.)
# --build-only checks that the targets build and link, which is all CI can
# afford (the sanitizers' builds take 8 minutes on 2 cores): no sanitizers
# but libFuzzer's, no optimisation.
[ "$BUILD_ONLY" = 1 ] && FLAGS=(-std=c++17 -O0 -ffp-contract=off -fsanitize=fuzzer -I.)

build() {
  local name="$1" main target
  case "$name" in
    traversal) main=cc/robust/traversal_fuzzer.cc target=//cc/robust:traversal_fuzz ;;
    mesh) main=cc/io/mesh_fuzzer.cc target=//cc/io:mesh_fuzz ;;
    env_file) main=cc/robust/env_file_fuzzer.cc target=//cc/robust:env_file_fuzz ;;
    *) echo "fuzz.sh: unknown fuzzer $name (traversal, mesh, env_file)" >&2; exit 2 ;;
  esac
  local srcs
  srcs=$(sources_of "$target")
  [ -n "$srcs" ] || { echo "fuzz.sh: bazel query found no sources for $target" >&2; exit 1; }
  # shellcheck disable=SC2086
  clang++ "${FLAGS[@]}" "$main" $srcs "${LIBS[@]}" -o "$OUT/bin/${name}_fuzzer"
}

# Options per fuzzer: the largest input and the per-input time limit. (assimp,
# not instrumented, leaks on some malformed OBJ files: leaks are not
# findings of ours.)
options() {
  case "$1" in
    traversal) echo "-max_len=2048 -timeout=20" ;;
    mesh) echo "-max_len=4096 -timeout=10 -detect_leaks=0" ;;
    env_file) echo "-max_len=1024 -timeout=10" ;;
  esac
}

if [ "$BUILD_ONLY" = 1 ]; then
  for name in "${FUZZERS[@]}"; do build "$name"; done
  echo "fuzz.sh: built ${FUZZERS[*]} in $OUT/bin (nothing run)"
  exit 0
fi

for name in "${FUZZERS[@]}"; do
  build "$name"
  corpus="$OUT/corpus/$name"
  mkdir -p "$corpus" "$OUT/$name"
  [ "$name" = env_file ] && cp -n experiments/presets/*.env "$corpus/" 2>/dev/null || true
  start=$(date -u +%Y-%m-%dT%H:%M:%SZ)
  t0=$(date +%s)
  commit=$(git rev-parse --short HEAD 2>/dev/null || echo none)  # what was built
  set +e
  # shellcheck disable=SC2046
  scratch="$(mktemp -d)"  # the mesh cases write their files here
  TMPDIR="$scratch" "$OUT/bin/${name}_fuzzer" -max_total_time="$SECONDS_EACH" \
    -artifact_prefix="$OUT/$name/" $(options "$name") "$corpus" > "$OUT/$name.log" 2>&1
  code=$?
  rm -rf "$scratch"
  set -e
  elapsed=$(( $(date +%s) - t0 ))
  # libFuzzer's last words: "Done N runs in S second(s)", or the last "#N" status line.
  execs=$(grep -o 'Done [0-9]* runs' "$OUT/$name.log" | grep -o '[0-9]*' || true)
  [ -z "$execs" ] && execs=$(grep -o '^#[0-9]*' "$OUT/$name.log" | tail -1 | tr -d '#')
  findings=$(ls "$OUT/$name" | wc -l)
  printf '{"date": "%s", "commit": "%s", "fuzzer": "%s", "seconds": %s, "executions": %s, "exit_code": %s, "findings": %s, "corpus_files": %s}\n' \
    "$start" "$commit" "$name" "$elapsed" \
    "${execs:-0}" "$code" "$findings" "$(ls "$corpus" | wc -l)" | tee -a "$OUT/runs.jsonl"
done
