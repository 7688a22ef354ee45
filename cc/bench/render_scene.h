// One scene of render_bench (render_bench.cc says what it measures and how):
// load, build, validate, then per thread count the timed rounds of every
// tracer and one JSON record.
#ifndef KDTREE_CC_BENCH_RENDER_SCENE_H_
#define KDTREE_CC_BENCH_RENDER_SCENE_H_

#include <cstdio>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "cc/base/timing_lock.h"
#include "cc/bench/bench_record.h"

namespace kdtree {
namespace bench {

// render_bench's flags (the same names).
struct RenderBenchOptions {
  std::string repo;       // '' = the workspace
  std::string cache_dir;  // relative to repo unless absolute; '' = none
  std::string preset;
  std::vector<int> threads;
  int tile = 16;
  int repeats = 5;
  int warmup = 1;
  int check_rays = 300;
  std::vector<std::string> variants;
  std::vector<std::string> envs;  // environment files, as given
  std::string embree;             // quality, or "off"
  std::string env_variant = "kd";  // how the --envs trees are traced
  bool embree_packets = true;
  bool embree_robust = true;
  bool replay = true;
  bool twice = false;
  bool classes = false;
};

// Where the run's numbers come from, and the lock its timed rounds hold.
struct RenderBenchContext {
  TimingLock* lock;
  Json provenance;
};

// The scene's records, one per thread count, to stdout and `out` (may be
// null). An error: the scene could not be loaded or built, a variant or the
// brute-force sample disagreed with the kd-tree, or a record could not be
// written.
absl::Status RunScene(const std::string& scene, const RenderBenchOptions& o,
                      const RenderBenchContext& ctx, FILE* out);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_RENDER_SCENE_H_
