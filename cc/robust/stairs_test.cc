// Hard case 3: stairs of axis-aligned treads and risers, rays along the axes
// (down, up, forward, backward, sideways; +0/-0 in the zero components) at
// every tread height and riser depth, one float either side of them, and
// between them. In watertight mode every ray must hit exactly the analytic
// step, at exactly the analytic distance (t = fl(o - plane), one rounding);
// the fast mode's misses and t errors are reported. Every preset against
// brute force too, in both modes.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cc/kdtree/builder.h"
#include "cc/kdtree/traversal.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

struct StairsCase {
  const char* name;
  int steps;
  float tread, rise, width;
};

struct Expected {
  bool hit;
  double t;
};

// Neighbours of each value, one float apart, and the value itself.
std::vector<float> AroundEach(const std::vector<float>& values) {
  std::vector<float> out;
  for (float v : values) {
    out.push_back(std::nextafter(v, -INFINITY));
    out.push_back(v);
    out.push_back(std::nextafter(v, INFINITY));
  }
  return SortedUnion({out, WithMidpoints(values)});
}

class Stairs : public ::testing::TestWithParam<StairsCase> {};

TEST_P(Stairs, AxisRaysHitAtTheAnalyticDistance) {
  const StairsCase c = GetParam();
  const TriangleSoup soup = robust::Stairs(c.steps, c.tread, c.rise, c.width);
  std::vector<float> ys, zs;
  for (int k = 0; k <= c.steps; ++k) {
    ys.push_back(StairY(k, c.rise));
    zs.push_back(StairZ(k, c.tread));
  }
  const std::vector<float> grid_y = AroundEach(ys), grid_z = AroundEach(zs);
  const std::vector<float> grid_x = AroundEach({0.0f, c.width * 0.37f, c.width});
  const float top = ys.back(), back = zs.back();
  const float above = top + 1, below = -1, front = -1, behind = back + 1;
  std::vector<Ray> rays;
  std::vector<Expected> expected;
  auto inside = [](float v, float lo, float hi) { return lo <= v && v <= hi; };
  for (float x : grid_x) {
    const bool in_x = inside(x, 0, c.width);
    for (int zeros = 0; zeros < 4; ++zeros) {
      const float zx = (zeros & 1) ? -0.0f : 0.0f, zz = (zeros & 2) ? -0.0f : 0.0f;
      for (float z : grid_z) {
        // Down: the highest tread whose depth range holds z; up: the lowest.
        int hi_k = -1, lo_k = -1;
        for (int k = 0; k < c.steps; ++k) {
          if (inside(z, zs[k], zs[k + 1])) {
            hi_k = k;
            if (lo_k < 0) lo_k = k;
          }
        }
        rays.push_back(Ray{{x, above, z}, {zx, -1, zz}});
        expected.push_back({in_x && hi_k >= 0, hi_k < 0 ? 0 : double(above) - ys[hi_k + 1]});
        rays.push_back(Ray{{x, below, z}, {zx, 1, zz}});
        expected.push_back({in_x && lo_k >= 0, lo_k < 0 ? 0 : double(ys[lo_k + 1]) - below});
      }
      for (float y : grid_y) {
        // Forward (+z): the nearest riser whose height range holds y;
        // backward: the farthest. Treads are parallel to these rays.
        int lo_k = -1, hi_k = -1;
        for (int k = 0; k < c.steps; ++k) {
          if (inside(y, ys[k], ys[k + 1])) {
            hi_k = k;
            if (lo_k < 0) lo_k = k;
          }
        }
        rays.push_back(Ray{{x, y, front}, {zx, zz, 1}});
        expected.push_back({in_x && lo_k >= 0, lo_k < 0 ? 0 : double(zs[lo_k]) - front});
        rays.push_back(Ray{{x, y, behind}, {zx, zz, -1}});
        expected.push_back({in_x && hi_k >= 0, hi_k < 0 ? 0 : double(behind) - zs[hi_k]});
      }
    }
  }
  // Sideways (+-x) rays are parallel to every tread and riser: all miss.
  for (float y : grid_y) {
    for (float z : grid_z) {
      for (float s : {1.0f, -1.0f}) {
        rays.push_back(Ray{{s > 0 ? -1.0f : c.width + 1, y, z}, {s, 0.0f, -0.0f}});
        expected.push_back({false, 0});
      }
    }
  }
  std::printf("%s: %zu triangles, %zu axis rays\n", c.name, soup.size(), rays.size());

  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    for (const std::string& name : CheckedPresets()) {
      absl::StatusOr<KdTree> tree = BuildKdTree(soup, *ConfigFor(name));
      ASSERT_TRUE(tree.ok()) << tree.status();
      int wrong_hit = 0, wrong_t = 0;
      double max_rel = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        const Hit h = Intersect(*tree, rays[i], WithTest(mode));
        if (h.hit() != expected[i].hit) {
          if (++wrong_hit <= 3 && mode == IntersectionMode::kWatertight) {
            ADD_FAILURE() << c.name << " " << name << " " << IntersectionModeName(mode) << " ray "
                          << i << " (" << rays[i].origin.x << ", " << rays[i].origin.y << ", "
                          << rays[i].origin.z << ") dir (" << rays[i].dir.x << ", "
                          << rays[i].dir.y << ", " << rays[i].dir.z << "): hit " << h.hit()
                          << ", expected " << expected[i].hit;
          }
          continue;
        }
        if (!h.hit()) continue;
        const double rel = std::fabs(h.t - expected[i].t) / expected[i].t;
        if (rel > max_rel) max_rel = rel;
        const bool exact = h.t == static_cast<float>(expected[i].t);
        if (!exact) ++wrong_t;
      }
      if (mode == IntersectionMode::kWatertight) {  // the fast mode is only reported
        EXPECT_EQ(wrong_hit, 0) << c.name << " " << name;
        EXPECT_EQ(wrong_t, 0) << c.name << " " << name;
      }
      std::printf("ROBUST_JSON {\"case\": \"stairs_analytic/%s\", \"preset\": \"%s\", \"mode\": "
                  "\"%s\", \"rays\": %zu, \"wrong_hit\": %d, \"wrong_t\": %d, "
                  "\"max_rel_t_error\": %.3g}\n",
                  c.name, name.c_str(), IntersectionModeName(mode), rays.size(), wrong_hit,
                  wrong_t, max_rel);
    }
    CheckOptions options;
    options.include_seed = true;
    ExpectNoMismatches(std::string("stairs/") + c.name,
                       CheckAllPresets(std::string("stairs/") + c.name, soup, rays, mode, nullptr,
                                       options));
  }
}

INSTANTIATE_TEST_SUITE_P(Flights, Stairs,
                         ::testing::Values(StairsCase{"dyadic", 16, 0.5f, 0.25f, 2.0f},
                                           StairsCase{"decimal", 16, 0.3f, 0.17f, 1.3f},
                                           StairsCase{"steep", 40, 0.01f, 3.7f, 0.7f}),
                         [](const ::testing::TestParamInfo<StairsCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace robust
}  // namespace kdtree
