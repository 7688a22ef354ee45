// libFuzzer target: the environment-file parser (env_file_fuzz.h). Aborts
// when a promise is broken.
//
// Built and run with clang by cc/robust/fuzz.sh (`bash cc/robust/fuzz.sh 3600
// env_file`; the Bazel toolchain is gcc, which has no libFuzzer).
//
// The deterministic smoke run inside `bazel test` is env_file_fuzz_test.cc.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "cc/robust/env_file_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (kdtree::EnvFileFuzzCase(data, size) != 0) {
    std::fprintf(stderr, "the environment-file parser broke a promise\n");
    std::abort();
  }
  return 0;
}
