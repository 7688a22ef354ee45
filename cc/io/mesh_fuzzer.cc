// libFuzzer target: the mesh loader on fuzzed OBJ, OFF and PLY files, plain
// and gzipped (mesh_fuzz.h). Aborts when a promise of LoadMesh is broken; crashes and
// hangs are what libFuzzer reports itself.
//
// Built and run with clang by cc/robust/fuzz.sh (`bash cc/robust/fuzz.sh 3600
// mesh`; the Bazel toolchain is gcc, which has no libFuzzer).
//
// (assimp itself is not instrumented: findings inside it show as crashes
// without coverage guidance. Its OBJ importer leaks on some malformed files,
// found in 6 minutes on 2026-12-03: fuzz.sh passes -detect_leaks=0.) The deterministic smoke run inside
// `bazel test` is mesh_fuzz_test.cc.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cc/io/mesh_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const char* dir = std::getenv("TMPDIR");
  if (kdtree::MeshFuzzCase(data, size, dir != nullptr ? dir : "/tmp") != 0) {
    std::fprintf(stderr, "LoadMesh broke a promise on this input\n");
    std::abort();
  }
  return 0;
}
