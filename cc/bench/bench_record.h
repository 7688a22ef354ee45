// What build_bench and render_bench share: writing one JSON record per line
// (the line itself: cc/base/json_line.h; paths: cc/tools/paths.h).
#ifndef KDTREE_CC_BENCH_BENCH_RECORD_H_
#define KDTREE_CC_BENCH_BENCH_RECORD_H_

#include <cstdio>
#include <string>

#include "nlohmann/json.hpp"

namespace kdtree {
namespace bench {

using Json = nlohmann::ordered_json;

// Writes the line and a newline to `out` (when not null) and flushes; false
// when the write failed.
inline bool WriteLine(std::FILE* out, const std::string& line) {
  if (out == nullptr) return true;
  return std::fprintf(out, "%s\n", line.c_str()) >= 0 && std::fflush(out) == 0;
}

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_BENCH_RECORD_H_
