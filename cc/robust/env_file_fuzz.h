// One fuzz case for the environment-file parser (env_file.h; issue "Hard
// cases stay numerically stable", input hygiene). Used by the libFuzzer target
// env_file_fuzzer.cc and the smoke test env_file_fuzz_test.cc.
#ifndef KDTREE_CC_ROBUST_ENV_FILE_FUZZ_H_
#define KDTREE_CC_ROBUST_ENV_FILE_FUZZ_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "cc/kdtree/env_file.h"

namespace kdtree {

// Parses the bytes as an environment file named "fuzz.env". Returns the
// number of broken promises: an accepted file whose Config is invalid or does
// not survive ToEnvironment() and parsing again, or an error whose message
// does not start with the file name. Crashes and hangs are the fuzzer's.
inline size_t EnvFileFuzzCase(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const absl::StatusOr<EnvResult> r = ParseEnvironment(text, "fuzz.env");
  if (!r.ok()) return r.status().message().rfind("fuzz.env", 0) != 0;
  if (!r->config.Validate().ok()) return 1;
  const absl::StatusOr<EnvResult> again = ParseEnvironment(r->config.ToEnvironment(), "again.env");
  return !again.ok() || !(again->config == r->config);
}

}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_ENV_FILE_FUZZ_H_
