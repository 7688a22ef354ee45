// libFuzzer target: kd-tree traversal against brute force on fuzzed scenes
// and rays (traversal_fuzz.h). Aborts on the first disagreement.
//
// Built and run with clang by cc/robust/fuzz.sh (`bash cc/robust/fuzz.sh 3600
// traversal`; the Bazel toolchain is gcc, which has no libFuzzer).
//
// The deterministic smoke run inside `bazel test` is traversal_fuzz_test.cc.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "cc/robust/traversal_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (kdtree::robust::TraversalFuzzCase(data, size) != 0) {
    std::fprintf(stderr, "kd-tree and brute force disagree\n");
    std::abort();
  }
  return 0;
}
