#!/usr/bin/env bash
# README command 2: set-up (idempotent) and every test, C++ and Python.
set -euo pipefail
cd "$(dirname "$0")/.."
# LaTeX too: //analysis:report_pdf_test builds the report from a fixture.
bash experiments/setup.sh --with-blender --with-report --with-fuzz
# Scenes the tests use when present (small ones; skipped with a message offline).
/usr/bin/python3 data/fetch.py --profile test || echo "test scenes unavailable; tests fall back to generated meshes"
# The Stanford bunny of the scene library joins the brute-force comparison
# when present (cc/kdtree/traversal_test.cc falls back to a generated mesh).
# No tracked file may send a reader outside the repository.
/usr/bin/python3 experiments/self_contained.py
# The libFuzzer targets are built by clang outside Bazel (cc/robust/fuzz.sh):
# they must still build and link (about a minute; the fuzzing itself is run
# by hand).
bash cc/robust/fuzz.sh --build-only
# Every test runs once, in the configuration the reproduction's numbers come
# from (.bazelrc's opt: -O3 -march=native), which the reproduction and the
# SLURM check then reuse. One thing differs in the default build (any x86-64):
# the single-ray traversal's leaf step tests one leaf packet at a time where
# the static target's vectors are 128 bits wide, two at once where they are
# 256 bits or wider (cc/kdtree/traversal.cc). So the traversal's checks
# against brute force run in the default build first, on the generated
# scenes (the bunny's 7e9-test reference is the slowest check of all and runs
# in the timed build). The packet kernel is picked at run time by the CPU, the
# same in both builds.
# shellcheck disable=SC2046
bazel test $(bazel query 'attr(name, "^traversal_.*_test$", tests(//cc/kdtree:all)) except //cc/kdtree:traversal_bunny_test') "$@"
bazel test --config=opt //... --test_env=KDTREE_SCENES="$PWD/data/cache/scenes" "$@"
