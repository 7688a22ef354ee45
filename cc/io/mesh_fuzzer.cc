// libFuzzer target: the mesh loader on fuzzed OBJ, OFF and PLY files, plain
// and gzipped (mesh_fuzz.h). Aborts when a promise of LoadMesh is broken; crashes and
// hangs are what libFuzzer reports itself.
//
// Needs clang's libFuzzer runtime; the Bazel toolchain is gcc, so it is built
// by hand from the workspace root (assimp, zlib and Abseil from Debian):
//
//   clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -I. \
//     cc/io/mesh_fuzzer.cc cc/io/mesh_fuzz.cc cc/io/mesh_loader.cc cc/io/mesh_input.cc \
//     cc/base/read_file.cc cc/io/mesh_syntax.cc cc/io/ply_syntax.cc \
//     -lassimp -lz $(pkg-config --libs absl_statusor absl_str_format absl_strings) \
//     -o /tmp/mesh_fuzzer
//   mkdir -p /tmp/mesh_corpus && /tmp/mesh_fuzzer -max_total_time=3600 -max_len=4096 \
//     -timeout=10 /tmp/mesh_corpus
//
// (assimp itself is not instrumented: findings inside it show as crashes
// without coverage guidance. Its OBJ importer leaks on some malformed files,
// found in 6 minutes on 2026-12-03: add -detect_leaks=0 for long runs.) The deterministic smoke run inside
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
