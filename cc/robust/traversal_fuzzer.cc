// libFuzzer target: kd-tree traversal against brute force on fuzzed scenes
// and rays (traversal_fuzz.h). Aborts on the first disagreement.
//
// Needs clang's libFuzzer runtime (libclang_rt.fuzzer, from LLVM 14 here);
// the Bazel toolchain is gcc, so it is built by hand from the workspace root:
//
//   clang++ -std=c++17 -O1 -g -ffp-contract=off -fsanitize=fuzzer,address,undefined \
//     -I. cc/robust/traversal_fuzzer.cc cc/robust/traversal_fuzz.cc \
//     cc/kdtree/{binned_sah,builder,clipping,median_split,pruning,stats,traversal,brute_force,config}.cc \
//     -labsl_statusor -labsl_status -labsl_str_format_internal -labsl_strings \
//     -labsl_strings_internal -labsl_cord -labsl_cordz_info -labsl_cord_internal \
//     -labsl_cordz_functions -labsl_cordz_handle -labsl_synchronization -labsl_time \
//     -labsl_int128 -labsl_throw_delegate -labsl_raw_logging_internal -labsl_base \
//     -labsl_spinlock_wait -labsl_stacktrace -labsl_symbolize -labsl_malloc_internal \
//     -labsl_debugging_internal -labsl_demangle_internal -labsl_graphcycles_internal \
//     -labsl_exponential_biased -labsl_bad_optional_access -labsl_time_zone \
//     -labsl_civil_time -labsl_strerror -labsl_log_severity -labsl_hash -labsl_city \
//     -labsl_low_level_hash -labsl_raw_hash_set -labsl_hashtablez_sampler \
//     -labsl_bad_variant_access -o /tmp/traversal_fuzzer
//   /tmp/traversal_fuzzer -max_total_time=3600 -max_len=2048 /tmp/traversal_corpus
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
