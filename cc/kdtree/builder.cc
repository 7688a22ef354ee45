#include "cc/kdtree/builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "cc/kdtree/build_budget.h"
#include "cc/kdtree/build_ref.h"
#include "cc/kdtree/collapse.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/parallel_build.h"
#include "cc/kdtree/recursive_builder.h"
#include "tbb/task_arena.h"

namespace kdtree {
namespace {

using build_internal::Builder;

// Depth cap: maxDepth, or 8 + 1.3 log2 N with autoDepth (config.h).
int EffectiveMaxDepth(const Config& config, size_t n) {
  if (!config.auto_depth) return config.max_depth;
  const double d = 8.0 + 1.3 * std::log2(static_cast<double>(std::max<size_t>(n, 1)));
  return std::min(60, static_cast<int>(d));
}

// True when no reference's box ever differs from its triangle's tight box
// (no clipping, no perfect splits) and the split strategy reads boxes only
// through BoxOf: the build then passes bare indices (IndexRef, build_ref.h).
bool UsesIndexRefs(const Config& config) {
  return !config.use_clipping && !config.perfect_splits &&
         (!config.use_binning || config.split_method == Config::SplitMethod::kBinned);
}

}  // namespace

absl::Status CheckBuildInput(const TriangleSoup& soup) {
  if (soup.v.size() % 3 != 0) {
    return absl::InvalidArgumentError("triangle soup size is not a multiple of 3");
  }
  if (soup.size() >= KdNode::kMaxIndex) {
    return absl::InvalidArgumentError(absl::StrCat("too many triangles: ", soup.size()));
  }
  for (size_t i = 0; i < soup.v.size(); ++i) {
    if (!IsFinite(soup.v[i])) {
      return absl::InvalidArgumentError(
          absl::StrCat("triangle ", i / 3, " has a non-finite vertex; drop it at load"));
    }
  }
  return absl::OkStatus();
}

absl::StatusOr<KdTree> BuildKdTree(const TriangleSoup& soup, const Config& config,
                                   const BuildLimits& limits) {
  if (absl::Status s = config.Validate(); !s.ok()) return s;
  if (absl::Status s = CheckBuildInput(soup); !s.ok()) return s;
  const auto start = std::chrono::steady_clock::now();
  KdTree tree;
  tree.config = config;
  tree.triangles = soup.size();
  const int threads = config.build_threads == 0
                          ? tbb::this_task_arena::max_concurrency()
                          : config.build_threads;
  Fragment root;
  BuildBudget budget(limits.max_bytes);
  const int max_depth = EffectiveMaxDepth(config, soup.size());
  const int parallel_depth = threads > 1 ? ParallelDepth(threads) : 0;
  absl::Status status;
  // The arena's threads build the report's tree of lists (list_tree.h), then
  // lay its leaves out as the finished tree's packets (leaf_layout.h).
  const auto build = [&] {
    if (UsesIndexRefs(config)) {
      status = Builder<IndexRef>(soup, config, &root, max_depth, parallel_depth, &budget)
                   .Run(threads > 1);
    } else {
      status = Builder<BuildRef>(soup, config, &root, max_depth, parallel_depth, &budget)
                   .Run(threads > 1);
    }
    if (!status.ok()) return;
    ListTree lists;
    if (root.children.empty()) {
      lists = std::move(root.tree);
    } else {
      lists.bounds = root.tree.bounds;
      if (!Stitch(root, &lists)) {
        status = absl::ResourceExhaustedError("kd-tree exceeds 2^30 nodes or references");
        return;
      }
    }
    root = Fragment();  // the fragments' lists, now copied into `lists`
    if (config.collapse) CollapseTree(config, &lists);
    tree.bounds = lists.bounds;
    tree.counters = lists.counters;
    if (!LayoutLeafTriangles(lists, soup.v.data(), threads > 1, &tree)) {
      status = absl::ResourceExhaustedError("kd-tree exceeds 2^30 - 1 leaf packets");
    }
  };
  if (threads > 1) {
    tbb::task_arena arena(threads);
    arena.execute(build);
  } else {
    build();
  }
  if (!status.ok()) return status;
  tree.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

}  // namespace kdtree
