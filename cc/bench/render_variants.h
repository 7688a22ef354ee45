// render_bench's kd-tree variants: the trees and tracers of one scene, and
// the timed entries that --variants names.
#ifndef KDTREE_CC_BENCH_RENDER_VARIANTS_H_
#define KDTREE_CC_BENCH_RENDER_VARIANTS_H_

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/bench/render_times.h"
#include "cc/embree/embree_tracer.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/tree.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/ray_record.h"

namespace kdtree {
namespace bench {

// The preset's tree and one tree per environment file (the preset with the
// file on top), each with its tracers. Not movable: the tracers point at the
// trees.
struct SceneTrees {
  struct EnvTree {
    std::string name;  // env:<file name>
    std::unique_ptr<KdTree> tree;
    std::unique_ptr<KdTreeTracer> tracer;
  };
  KdTree tree;
  std::unique_ptr<KdTreeTracer> kd;
  // The same tree's leaves under a BVH (kd_bvh; cc/kdtree/leaf_bvh.h), and
  // the seconds its build took.
  std::unique_ptr<KdTreeBvhTracer> bvh;
  double bvh_build_seconds = 0;
  // A BVH over whole triangles traced by the same kernels (tri_bvh;
  // cc/kdtree/triangle_bvh.h), built only when asked for (its build's
  // seconds: build_seconds()).
  std::unique_ptr<TriangleBvhTracer> tri_bvh;
  std::vector<EnvTree> envs;
};

// Builds them for `soup`; `env_paths` are environment files (env_file.h),
// whose trees are traced as `env_variant`: "kd", "kd_packet_origin",
// "kd_bvh" or "kd_bvh_packet" (their tracers are the BVH over the leaves
// then); with `triangle_bvh`, also the BVH over whole triangles
// (SceneTrees::tri_bvh); else an error.
absl::StatusOr<std::unique_ptr<SceneTrees>> BuildSceneTrees(
    const TriangleSoup& soup, const Config& config, const std::vector<std::string>& env_paths,
    const std::string& env_variant = "kd", bool triangle_bvh = false);

// The entries `names` ask for ("kd", "kd_packet", "kd_origin",
// "kd_packet_origin", "kd_bvh" (single rays through the BVH over the
// leaves, secondary rays as kd_origin's), "kd_bvh_packet" (the same in
// packets of 4x4 pixels), "tri_bvh" and "tri_bvh_packet" (the same
// through the BVH over whole triangles, which `trees` must hold), each
// optionally NAME@TARGET: the packet kernel on that Highway target), then
// one per environment tree, traced as `env_variant` (BuildSceneTrees's).
// Error: an unknown name, or a tri_bvh variant without its BVH.
absl::StatusOr<std::vector<Entry>> VariantEntries(const SceneTrees& trees,
                                                  const std::vector<std::string>& names,
                                                  const std::string& env_variant);

// Embree built on `soup` with `options`, appended to *entries as tracer
// `name` (single rays) and, with `packets`, `name`_packet (16-ray packets);
// *disagree gets its disagreements with `kd` on the recorded rays
// (compare.h). Errors: Embree's.
absl::StatusOr<std::unique_ptr<EmbreeTracer>> AddEmbree(const TriangleSoup& soup,
                                                        const EmbreeOptions& options,
                                                        const std::string& name, bool packets,
                                                        const std::vector<RayRecord>& rays,
                                                        const Tracer& kd,
                                                        std::vector<Entry>* entries,
                                                        Json* disagree);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_RENDER_VARIANTS_H_
