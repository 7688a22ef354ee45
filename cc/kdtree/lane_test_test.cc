// The packet kernel's per-lane watertight test (lane_test-inl.h) on the cases
// that pick its branches: rays through interior points (the vector path),
// exactly through shared vertices and edges (undecided signs: the scalar
// test), duplicated triangles (ties at equal t, broken by Closer), triangles
// of zero area and slivers, and rays leaving a point of the surface
// (triangles across the origin's depth) or lying in its plane, and rays with
// denormal direction components or none valid. Every lane must
// be the single-ray traversal's result bit for bit, and brute force's, on
// every kernel width this machine runs. (Rays near a zero-area triangle have
// undecided signs: decided edge functions cannot agree on it, as its exact
// edge functions sum to zero; so the vector path's near-zero area check,
// which mirrors Finish's, sends no lane of these to the scalar test.) The
// fast test's lanes (lane_fast_test-inl.h) get the same cases.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "gtest/gtest.h"
#include "hwy/highway.h"
// The build's static target, as traversal.cc includes it.
#include "cc/kdtree/lane_fast_test-inl.h"

namespace kdtree {
namespace {

using testing::BitwiseSameHit;

// A grid of n x n quads (two triangles each) in the plane z = 0, with
// shared edges; every fifth triangle again (a tie at every t), reversed
// every other time; a zero-area triangle and a sliver in each row.
TriangleSoup Grid(int n) {
  TriangleSoup s;
  auto p = [](int i, int j) { return Vec3(0.37f * i, 0.29f * j, 0.0f); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      s.Add(p(i, j), p(i + 1, j), p(i + 1, j + 1));
      s.Add(p(i, j), p(i + 1, j + 1), p(i, j + 1));
      if ((i + j) % 5 == 0) {
        if (i % 2) {
          s.Add(p(i, j), p(i + 1, j + 1), p(i + 1, j));
        } else {
          s.Add(p(i, j), p(i + 1, j), p(i + 1, j + 1));
        }
      }
    }
    // Zero area: c is exactly the midpoint of a and b (the shear may round
    // the three apart); a sliver beside it.
    const float y = 0.5f * j;
    const Vec3 a(0.25f, y, 0.5f), b(3.25f, y + 1.5f, -1.0f), c(1.75f, y + 0.75f, -0.25f);
    s.Add(a, b, c);
    s.Add(a, b, c + Vec3(0, 0, 1e-6f));
  }
  return s;
}

// Whether triangle t is one of Grid's zero-area or sliver triangles.
bool Degenerate(const TriangleSoup& s, size_t t) { return s.a(t).x == 0.25f; }

// Packets of rays from one point above the grid to vertices, edge points
// and centroids of its triangles (every other ray of every other packet to
// a zero-area triangle or a sliver); from points on the grid up, down and
// along it; with tmin 0 and above.
std::vector<Ray> Rays(const TriangleSoup& s, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Ray> rays;
  for (int k = 0; k < 400; ++k) {
    const Vec3 eye(4 * unit(rng) - 1, 4 * unit(rng) - 1, 0.5f + 3 * unit(rng));
    for (int l = 0; l < kRayPacketSize; ++l) {
      size_t t = rng() % s.size();
      while (k % 2 == 0 && l % 2 == 0 && !Degenerate(s, t)) t = rng() % s.size();
      const float w = unit(rng);
      Vec3 target;
      switch ((k + l) % 3) {
        case 0: target = s.v[3 * t + l % 3]; break;                     // a vertex
        case 1: target = s.a(t) * w + s.b(t) * (1 - w); break;          // an edge
        default: target = (s.a(t) + s.b(t) + s.c(t)) * (1.0f / 3); break;  // inside
      }
      rays.push_back(Ray{eye, target - eye});
    }
  }
  for (int k = 0; k < 200; ++k) {
    for (int l = 0; l < kRayPacketSize; ++l) {
      const size_t t = rng() % s.size();
      const float u = unit(rng) * 0.5f, v = unit(rng) * 0.5f;
      const Vec3 o = s.a(t) * (1 - u - v) + s.b(t) * u + s.c(t) * v;
      Vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, k % 4 == 0 ? 0.0f : unit(rng) - 0.5f);
      if (k % 2) d.z = std::fabs(d.z) + 0.01f;
      Ray r{o, d};
      r.tmin = k % 3 == 0 ? 0.0f : 1e-4f;
      rays.push_back(r);
    }
  }
  // Direction components below the smallest normal float (SanitizeRay makes
  // them zeros of their sign), a direction of only such components (no
  // ray), and invalid rays, among valid ones.
  for (int k = 0; k < 40; ++k) {
    for (int l = 0; l < kRayPacketSize; ++l) {
      const size_t t = rng() % s.size();
      // From a vertex's x or y (a split plane of many trees), nearly along it.
      Vec3 eye(4 * unit(rng) - 1, 4 * unit(rng) - 1, 1.0f + unit(rng));
      if (l % 4 == 0) eye.x = s.a(t).x;
      if (l % 4 == 1) eye.y = s.a(t).y;
      Ray r{eye, (s.a(t) + s.b(t) + s.c(t)) * (1.0f / 3) - eye};
      const float tiny = (l % 2 ? -1 : 1) * 1e-40f;
      if (l % 4 == 0) r.dir.x = tiny;
      if (l % 4 == 1) r.dir.y = tiny;
      if (l == 2) r.dir = Vec3(tiny, -tiny, tiny);
      if (l == 6) r.tmin = 2, r.tmax = 1;
      rays.push_back(r);
    }
  }
  return rays;
}

TEST(LaneTest, EveryBranchOnEveryKernelWidth) {
  const TriangleSoup soup = Grid(14);
  const BruteForce bf(soup);
  const std::vector<Ray> rays = Rays(soup, 5);
  for (const char* preset : {"sah-packet", "clipping-pruning"}) {
    absl::StatusOr<Config> config = Preset(preset);
    ASSERT_TRUE(config.ok());
    absl::StatusOr<KdTree> tree = BuildKdTree(soup, *config);
    ASSERT_TRUE(tree.ok()) << tree.status();
    ASSERT_TRUE(PacketPathApplies(*tree));
    std::vector<Hit> single(rays.size());
    size_t brute = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      single[i] = Intersect(*tree, rays[i]);
      const Hit ref = bf.Intersect(rays[i]);
      // Bit for bit, u and v too: the single-ray traversal runs the lane
      // test as well, so brute force's scalar test is the independent check.
      brute += ref.hit() ? !BitwiseSameHit(single[i], ref) : single[i].hit();
      hits += ref.hit();
    }
    EXPECT_EQ(brute, 0u) << preset;
    EXPECT_GT(hits, rays.size() / 3) << preset;
    for (const std::string& target : PacketKernelTargets()) {
      const ScopedPacketKernelTarget scoped(target);
      ASSERT_TRUE(scoped.ok()) << target;
      size_t closest = 0, any = 0;
      for (size_t i = 0; i < rays.size(); i += kRayPacketSize) {
        Hit out[kRayPacketSize];
        bool occ[kRayPacketSize];
        IntersectPacket(*tree, &rays[i], kRayPacketSize, out);
        OccludedPacket(*tree, &rays[i], kRayPacketSize, nullptr, occ);
        for (int l = 0; l < kRayPacketSize; ++l) {
          closest += !BitwiseSameHit(out[l], single[i + l]);
          any += occ[l] != Occluded(*tree, rays[i + l]);
        }
      }
      EXPECT_EQ(closest, 0u) << preset << " on " << target;
      EXPECT_EQ(any, 0u) << preset << " on " << target;
    }
  }
}

// The fast test in vectors (lane_fast_test-inl.h, the build's static target,
// as traversal.cc compiles it: 8 lanes where it has 256-bit vectors, else 4)
// on the same hard cases: rays exactly through
// shared vertices and edges (u, v at 0 or u + v at 1, inclusive), ties,
// zero-area triangles, rays leaving the surface. Every lane must be the
// scalar IntersectTriangle's verdict and t, u, v, bit for bit, for each
// triangle against each ray. (Traversals in the fast mode are checked
// against brute force in traversal_test.)
TEST(LaneTest, FastLanesAreTheScalarFastTest) {
  namespace hn = hwy::HWY_NAMESPACE;
  namespace lane = packet_internal::HWY_NAMESPACE;
  using D = hn::CappedTag<float, 2 * kPacketLanes>;
  const D d;
  const size_t n = hn::Lanes(d);
  ASSERT_GE(n, 1u);
  const TriangleSoup soup = Grid(14);
  const std::vector<Ray> rays = Rays(soup, 7);
  size_t tests = 0, hits = 0, differ = 0;
  for (const Ray& ray : rays) {
    const lane::RayLanes<D> r(d, ray);
    for (size_t first = 0; first < soup.size(); first += n) {
      HWY_ALIGN float x[3][2 * kPacketLanes], y[3][2 * kPacketLanes], z[3][2 * kPacketLanes];
      for (size_t l = 0; l < n; ++l) {
        const size_t tri = std::min(first + l, soup.size() - 1);
        for (int v = 0; v < 3; ++v) {
          x[v][l] = soup.v[3 * tri + v].x;
          y[v][l] = soup.v[3 * tri + v].y;
          z[v][l] = soup.v[3 * tri + v].z;
        }
      }
      lane::LaneTriangle<D> t;
      for (int v = 0; v < 3; ++v) {
        t.x[v] = hn::Load(d, x[v]);
        t.y[v] = hn::Load(d, y[v]);
        t.z[v] = hn::Load(d, z[v]);
      }
      lane::LaneHits lh;
      lane::FastLanes(d, r, t, ray.tmin, ray.tmax, (1u << n) - 1, &lh);
      EXPECT_EQ(lh.scalar, 0u);
      for (size_t l = 0; l < n && first + l < soup.size(); ++l) {
        const size_t tri = first + l;
        const Vec3* p = &soup.v[3 * tri];
        float tt = 0, uu = 0, vv = 0;
        const TriAccel acc = MakeTriAccel(p[0], p[1], p[2]);
        const bool want = IntersectTriangle(ray, acc, ray.tmin, ray.tmax, &tt, &uu, &vv);
        const bool got = (lh.hit >> l) & 1;
        ++tests;
        hits += want;
        const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof(a)) == 0; };
        if (got != want ||
            (want && !(same(lh.t[l], tt) && same(lh.u[l], uu) && same(lh.v[l], vv)))) {
          ++differ;
        }
      }
    }
  }
  EXPECT_EQ(differ, 0u) << "of " << tests;
  EXPECT_GT(hits, rays.size() / 3);
}

}  // namespace
}  // namespace kdtree
