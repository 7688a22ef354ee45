// What kdrt refuses before it builds anything (issue 24): a run whose renders
// would not fit the memory budget. What is left of the budget bounds the
// kd-tree's build (builder.h BuildLimits). (The scene's scale is checked by
// CheckSceneScale, cc/render/view.h; the mesh's size by the loader.)
#ifndef KDTREE_CC_TOOLS_KDRT_LIMITS_H_
#define KDTREE_CC_TOOLS_KDRT_LIMITS_H_

#include <cstddef>
#include <cstdint>

#include "absl/status/statusor.h"
#include "cc/render/view.h"

namespace kdtree {

// What kdrt's renders hold at once: the recording render with every ray
// (renderer.h RenderBytes), the last image of each of up to three timed lanes
// (the kd-tree, its fast mode, Embree), and the soup; against `budget_gb`
// (<= 0: cc/base/memory_budget.h's default). The message says what the run
// would need and names --memory_budget_gb. Returns the bytes of the budget
// left for the trees.
absl::StatusOr<uint64_t> CheckRunMemory(const View& view, bool shadows, size_t triangles,
                                        double budget_gb);

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_KDRT_LIMITS_H_
