#include "cc/bench/render_variants.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/env_file.h"
#include "cc/kdtree/traversal.h"
#include "cc/render/compare.h"

namespace kdtree {
namespace bench {

absl::StatusOr<std::unique_ptr<SceneTrees>> BuildSceneTrees(
    const TriangleSoup& soup, const Config& config, const std::vector<std::string>& env_paths,
    const std::string& env_variant, bool triangle_bvh) {
  if (env_variant != "kd" && env_variant != "kd_packet_origin" && env_variant != "kd_bvh" &&
      env_variant != "kd_bvh_packet") {
    return absl::InvalidArgumentError(absl::StrCat("unknown environment-tree variant ", env_variant));
  }
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, config);
  if (!tree.ok()) return tree.status();
  auto trees = std::make_unique<SceneTrees>();
  trees->tree = *std::move(tree);
  trees->kd = std::make_unique<KdTreeTracer>(trees->tree);
  const absl::Time start = absl::Now();
  absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> bvh = KdTreeBvhTracer::Build(trees->tree);
  if (!bvh.ok()) return bvh.status();
  trees->bvh = *std::move(bvh);
  trees->bvh_build_seconds = absl::ToDoubleSeconds(absl::Now() - start);
  if (triangle_bvh) {
    absl::StatusOr<std::unique_ptr<TriangleBvhTracer>> tri = TriangleBvhTracer::Build(soup);
    if (!tri.ok()) return tri.status();
    trees->tri_bvh = *std::move(tri);
  }
  for (const std::string& path : env_paths) {
    absl::StatusOr<EnvResult> env = LoadEnvironmentFile(path, config);
    if (!env.ok()) return env.status();
    absl::StatusOr<KdTree> t = BuildKdTree(soup, env->config);
    if (!t.ok()) return t.status();
    SceneTrees::EnvTree e;
    e.name = absl::StrCat("env:", path.substr(path.find_last_of('/') + 1));  // npos + 1 == 0
    e.tree = std::make_unique<KdTree>(*std::move(t));
    if (env_variant == "kd_bvh" || env_variant == "kd_bvh_packet") {
      absl::StatusOr<std::unique_ptr<KdTreeBvhTracer>> t = KdTreeBvhTracer::Build(*e.tree);
      if (!t.ok()) return t.status();
      e.tracer = *std::move(t);
    } else {
      e.tracer = std::make_unique<KdTreeTracer>(*e.tree);
    }
    trees->envs.push_back(std::move(e));
  }
  return trees;
}

absl::StatusOr<std::vector<Entry>> VariantEntries(const SceneTrees& trees,
                                                  const std::vector<std::string>& names,
                                                  const std::string& env_variant) {
  std::vector<Entry> entries;
  for (const std::string& name : names) {
    // NAME@TARGET: the variant with the packet kernel on that Highway target.
    const std::string v = name.substr(0, name.find('@'));
    if (v == "kd") {
      entries.emplace_back(v, trees.kd.get());
    } else if (v == "kd_packet") {
      entries.emplace_back(v, trees.kd.get(), true);
    } else if (v == "kd_origin") {
      entries.emplace_back(v, trees.kd.get(), false, true);
    } else if (v == "kd_packet_origin") {
      entries.emplace_back(v, trees.kd.get(), true, true);
    } else if (v == "kd_bvh") {
      entries.emplace_back(v, trees.bvh.get(), false, true);
    } else if (v == "kd_bvh_packet") {
      entries.emplace_back(v, trees.bvh.get(), true, true);
    } else if (v == "tri_bvh" || v == "tri_bvh_packet") {
      if (trees.tri_bvh == nullptr) {
        return absl::FailedPreconditionError(
            absl::StrCat(v, ": the triangle BVH was not built (BuildSceneTrees's triangle_bvh)"));
      }
      entries.emplace_back(v, trees.tri_bvh.get(), v == "tri_bvh_packet", true);
    } else {
      return absl::InvalidArgumentError(absl::StrCat("unknown variant ", v));
    }
    entries.back().name = name;
    if (name.size() > v.size()) entries.back().kernel = name.substr(v.size() + 1);
  }
  for (const SceneTrees::EnvTree& e : trees.envs) {
    entries.emplace_back(e.name, e.tracer.get(),
                         env_variant == "kd_packet_origin" || env_variant == "kd_bvh_packet",
                         env_variant != "kd");
  }
  return entries;
}

absl::StatusOr<std::unique_ptr<EmbreeTracer>> AddEmbree(const TriangleSoup& soup,
                                                        const EmbreeOptions& options,
                                                        const std::string& name, bool packets,
                                                        const std::vector<RayRecord>& rays,
                                                        const Tracer& kd,
                                                        std::vector<Entry>* entries,
                                                        Json* disagree) {
  absl::StatusOr<std::unique_ptr<EmbreeTracer>> embree = EmbreeTracer::Create(soup, options);
  if (!embree.ok()) return embree.status();
  *disagree = CompareTracers(rays, soup, kd, **embree).ToJson();
  entries->emplace_back(name, embree->get());
  if (packets) entries->emplace_back(absl::StrCat(name, "_packet"), embree->get(), true);
  return embree;
}

}  // namespace bench
}  // namespace kdtree
