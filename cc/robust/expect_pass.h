// gtest assertions over CheckAllPresets() results: every required preset has
// 0 mismatches.
#ifndef KDTREE_CC_ROBUST_EXPECT_PASS_H_
#define KDTREE_CC_ROBUST_EXPECT_PASS_H_

#include <string>
#include <vector>

#include "absl/strings/str_join.h"
#include "cc/robust/preset_check.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {

inline void ExpectNoMismatches(const std::string& case_name,
                               const std::vector<CheckResult>& results) {
  for (const CheckResult& r : results) {
    if (r.informational) continue;
    EXPECT_EQ(r.mismatches, 0u) << case_name << " " << r.preset << " "
                                << IntersectionModeName(r.mode) << ": closest-hit mismatches, rays "
                                << absl::StrJoin(r.examples, ", ");
    EXPECT_EQ(r.any_hit_mismatches, 0u) << case_name << " " << r.preset << " "
                                        << IntersectionModeName(r.mode)
                                        << ": any-hit mismatches, rays "
                                        << absl::StrJoin(r.examples, ", ");
  }
}

// Names a suite's instances after their scene (robust_scenes.h SmallSceneNames).
struct SceneParamName {
  std::string operator()(const ::testing::TestParamInfo<std::string>& info) const {
    return info.param;
  }
};

}  // namespace robust
}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_EXPECT_PASS_H_
