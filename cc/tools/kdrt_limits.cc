#include "cc/tools/kdrt_limits.h"

#include <cstdint>

#include "absl/strings/str_format.h"
#include "cc/base/memory_budget.h"
#include "cc/geometry/vec3.h"
#include "cc/render/renderer.h"

namespace kdtree {

absl::StatusOr<uint64_t> CheckRunMemory(const View& view, bool shadows, size_t triangles,
                                        double budget_gb) {
  RenderOptions recording;
  recording.cast_shadow_rays = shadows;
  recording.record_rays = true;
  RenderOptions lane = recording;
  lane.record_rays = false;
  const uint64_t need = RenderBytes(view, recording) + 3 * RenderBytes(view, lane) +
                        uint64_t{triangles} * 3 * sizeof(Vec3);
  const uint64_t budget = budget_gb <= 0    ? DefaultMemoryBudget()
                          : budget_gb >= 1e9 ? ~uint64_t{0}
                                             : static_cast<uint64_t>(budget_gb * 1e9);
  absl::Status st = CheckMemoryBudget(need, budget,
                           absl::StrFormat("rendering %dx%d with %zu lights%s and recording every ray",
                                           view.width, view.height, view.lights.size(),
                                           view.ao.enabled() ? " and ambient occlusion" : ""),
                           "kdrt --memory_budget_gb");
  if (!st.ok()) return st;
  return budget - need;
}

}  // namespace kdtree
