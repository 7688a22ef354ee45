#!/usr/bin/env bash
# README command 2: set-up (idempotent) and every test, C++ and Python.
set -euo pipefail
cd "$(dirname "$0")/.."
# LaTeX too: //analysis:report_pdf_test builds the report from a fixture.
bash experiments/setup.sh --with-blender --with-report
# Scenes the tests use when present (small ones; skipped with a message offline).
/usr/bin/python3 data/fetch.py --profile test || echo "test scenes unavailable; tests fall back to generated meshes"
# The Stanford bunny of the scene library joins the brute-force comparison
# when present (cc/kdtree/traversal_test.cc falls back to a generated mesh).
# No tracked file may send a reader outside the repository.
/usr/bin/python3 experiments/self_contained.py
# The timed builds (.bazelrc's opt: -march=native) compile the single-ray
# traversal's leaf step for this machine's vectors (two leaf packets at once
# with 256-bit or wider ones: cc/kdtree/traversal.cc), the default build below
# for any x86-64 (one at a time). So the traversal's checks against brute
# force, and the adversarial suite, also run in the timed configuration.
# shellcheck disable=SC2046
bazel test --config=opt \
  $(bazel query 'attr(name, "^(traversal|ray_packet).*_test$", tests(//cc/kdtree:all))') \
  //cc/robust:all --test_env=KDTREE_SCENES="$PWD/data/cache/scenes" "$@"
bazel test //... --test_env=KDTREE_SCENES="$PWD/data/cache/scenes" "$@"
