// Hard case 6: scale invariance. The same scene scaled by 1e-4, 1 and 1e4
// (every coordinate multiplied in double and rounded once; ray origins and aim
// points likewise, directions of aimed rays recomputed, t range scaled) must
// give the same hit mask. Scenes: a voxel-world block scene (axis-aligned
// faces; axis rays through vertex coordinates decide on exact predicates) and
// a closed icosphere (rays from inside aimed at every vertex and edge
// midpoint). Rays: axis-parallel at vertex coordinates and midpoints, random,
// a 150x150 camera. Every preset against brute force at every scale, both
// modes; the mask must not change in watertight mode (the fast mode's changes
// are reported).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/robust/expect_pass.h"
#include "cc/robust/preset_check.h"
#include "cc/robust/robust_scenes.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace robust {
namespace {

// A ray at unit scale: aimed rays keep their target, so that at every scale the
// direction is recomputed from the scaled end points.
struct RaySpec {
  Ray ray;
  bool aimed = false;
  Vec3 target;
};

Vec3 ScalePoint(const Vec3& p, double s) {
  return Vec3(static_cast<float>(p.x * s), static_cast<float>(p.y * s),
              static_cast<float>(p.z * s));
}

std::vector<Ray> ScaleRays(const std::vector<RaySpec>& specs, double s) {
  std::vector<Ray> out;
  out.reserve(specs.size());
  for (const RaySpec& spec : specs) {
    Ray r = spec.ray;
    r.origin = ScalePoint(spec.ray.origin, s);
    if (spec.aimed) r.dir = ScalePoint(spec.target, s) - r.origin;
    r.tmin = static_cast<float>(spec.ray.tmin * s);
    r.tmax = static_cast<float>(spec.ray.tmax * s);
    out.push_back(r);
  }
  return out;
}

std::vector<RaySpec> CommonRays(const TriangleSoup& soup) {
  std::vector<RaySpec> specs;
  AxisGrid grid;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    grid.points[a] = GridPoints(WithMidpoints(Sample(VertexCoordinates(soup, b), 60)),
                                WithMidpoints(Sample(VertexCoordinates(soup, c), 60)), 6000, 8);
  }
  const auto free_ray = [&specs](const Ray& r) { specs.push_back(RaySpec{r, false, Vec3()}); };
  for (const Ray& r : AxisParallelRays(soup.Bounds(), grid)) free_ray(r);
  for (const Ray& r : testing::RandomRays(soup, 10000, 61)) free_ray(r);
  for (const Ray& r : testing::CameraRays(soup, 150, 150)) free_ray(r);
  return specs;
}

void CheckScales(const std::string& name, const TriangleSoup& soup,
                 const std::vector<RaySpec>& specs) {
  const double scales[] = {1e-4, 1.0, 1e4};
  std::printf("%s: %zu triangles, %zu rays per scale\n", name.c_str(), soup.size(), specs.size());
  for (IntersectionMode mode : {IntersectionMode::kWatertight, IntersectionMode::kFast}) {
    std::vector<std::vector<Hit>> refs;
    for (double s : scales) {
      const TriangleSoup scaled = Scaled(soup, s);
      const std::vector<Ray> rays = ScaleRays(specs, s);
      refs.push_back(BruteForceHits(scaled, rays, mode));
      const std::string case_name = absl::StrCat("scale/", name, "/", s);
      ExpectNoMismatches(case_name, CheckAllPresets(case_name, scaled, rays, mode, &refs.back()));
    }
    size_t mask_changes = 0, triangle_changes = 0, hits = 0;
    for (size_t i = 0; i < specs.size(); ++i) {
      hits += refs[1][i].hit();
      for (int k : {0, 2}) {
        if (refs[k][i].hit() != refs[1][i].hit()) {
          ++mask_changes;
        } else if (refs[k][i].tri != refs[1][i].tri) {
          ++triangle_changes;
        }
      }
    }
    std::printf("ROBUST_JSON {\"case\": \"scale/%s\", \"mode\": \"%s\", \"rays\": %zu, \"hits\": "
                "%zu, \"hit_mask_changes\": %zu, \"same_mask_other_triangle\": %zu}\n",
                name.c_str(), IntersectionModeName(mode), specs.size(), hits, mask_changes,
                triangle_changes);
    if (mode == IntersectionMode::kWatertight) {
      EXPECT_EQ(mask_changes, 0u) << name << ": the hit mask depends on the scale";
    }
  }
}

TEST(ScaleInvariance, BlockWorld) {
  const TriangleSoup soup = testing::VoxelGrid(10, 6, 10, 5);
  CheckScales("blocks", soup, CommonRays(soup));
}

TEST(ScaleInvariance, ClosedSphere) {
  const double centre[3] = {0.3, -0.2, 0.1};
  const TriangleSoup soup = Icosphere(3, 1.0, centre);
  std::vector<RaySpec> specs = CommonRays(soup);
  const Vec3 inside(0.3f, -0.2f, 0.1f), off_centre(0.1f, 0.05f, -0.2f);
  for (const Vec3& origin : {inside, off_centre}) {
    for (const std::vector<Vec3>& targets : {UniqueVertices(soup), EdgeMidpoints(soup)}) {
      for (const Vec3& p : targets) {
        RaySpec spec;
        spec.ray = Ray{origin, p - origin};
        spec.aimed = true;
        spec.target = p;
        specs.push_back(spec);
      }
    }
  }
  CheckScales("sphere", soup, specs);
}

}  // namespace
}  // namespace robust
}  // namespace kdtree
