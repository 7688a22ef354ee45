// libFuzzer target: the environment-file parser (env_file_fuzz.h). Aborts
// when a promise is broken.
//
// Needs clang's libFuzzer runtime; the Bazel toolchain is gcc, so it is built
// by hand from the workspace root:
//
//   clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -I. \
//     cc/robust/env_file_fuzzer.cc cc/kdtree/env_file.cc cc/kdtree/config.cc \
//     $(pkg-config --libs absl_statusor absl_str_format absl_strings) -o /tmp/env_file_fuzzer
//   mkdir -p /tmp/env_corpus && cp experiments/presets/*.env /tmp/env_corpus/
//   /tmp/env_file_fuzzer -max_total_time=3600 -max_len=1024 /tmp/env_corpus
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
