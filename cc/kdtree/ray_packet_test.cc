// The packet traversal (ray_packet.h) against the single-ray traversal, bit
// for bit (triangle, t, u, v and any hit), and against brute force, for every
// preset on scenes with shared edges, split planes through vertices, slivers
// and a flat box. Packets: 4x4 camera blocks (coherent), rays from one point
// with jittered directions, random rays forced to the same direction signs
// (divergent lanes), random rays with any signs (several groups per packet),
// axis-parallel rays with origins in split planes, and packets with invalid
// rays or fewer than 16 rays. The kernel is checked at every width this
// machine runs (Highway targets: SSE4, AVX2, AVX-512). Shadow rays leaving their
// origin triangles (OccludedPacket with origin_tris) against the single-ray traversal told
// the same triangle, also when the "origin" is the triangle the ray hits. Any-hit
// queries also from the rays' ends (TraversalOptions::from_end), packets and single rays.
// And the counts (PacketCounters::lanes): every lane visits the inner nodes and
// leaves of its ray's single-ray traversal, and for the closest hit tests its
// triangles, on every kernel width.
#include "cc/kdtree/ray_packet.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cc/geometry/spawn.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/test_scenes.h"
#include "cc/kdtree/traversal.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

using testing::BitwiseSameHit;

struct PacketSet {
  std::vector<Ray> rays;  // packets of kRayPacketSize consecutive rays...
  std::vector<int> sizes;  // ...of which the first sizes[k] are traced
};

void AddPacket(PacketSet* s, const std::vector<Ray>& rays) {
  std::vector<Ray> r = rays;
  s->sizes.push_back(static_cast<int>(r.size()));
  r.resize(kRayPacketSize);
  s->rays.insert(s->rays.end(), r.begin(), r.end());
}

PacketSet MakePackets(const TriangleSoup& soup, uint32_t seed) {
  PacketSet s;
  const AABB box = soup.Bounds();
  const Vec3 ext = box.Extent();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto point = [&](float margin) {
    return Vec3(box.lo.x - margin * ext.x + (1 + 2 * margin) * ext.x * unit(rng),
                box.lo.y - margin * ext.y + (1 + 2 * margin) * ext.y * unit(rng),
                box.lo.z - margin * ext.z + (1 + 2 * margin) * ext.z * unit(rng));
  };
  // 4x4 blocks of a 48x48 camera.
  const int side = 48;
  const std::vector<Ray> cam = testing::CameraRays(soup, side, side);
  for (int y = 0; y < side; y += 4) {
    for (int x = 0; x < side; x += 4) {
      std::vector<Ray> p;
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) p.push_back(cam[(y + j) * side + x + i]);
      }
      AddPacket(&s, p);
    }
  }
  // One origin, jittered directions towards a random point.
  for (int k = 0; k < 75; ++k) {
    const Vec3 o = point(0.3f), target = point(0.0f);
    std::vector<Ray> p;
    for (int l = 0; l < kRayPacketSize; ++l) {
      const Vec3 jitter(0.02f * (unit(rng) - 0.5f), 0.02f * (unit(rng) - 0.5f),
                        0.02f * (unit(rng) - 0.5f));
      p.push_back(Ray{o, target - o + jitter * Length(ext)});
    }
    AddPacket(&s, p);
  }
  // Random origins and directions with one shared sign pattern (lanes diverge).
  for (int k = 0; k < 75; ++k) {
    const Vec3 sign(unit(rng) < 0.5f ? -1.0f : 1.0f, unit(rng) < 0.5f ? -1.0f : 1.0f,
                    unit(rng) < 0.5f ? -1.0f : 1.0f);
    std::vector<Ray> p;
    for (int l = 0; l < kRayPacketSize; ++l) {
      const Vec3 d(sign.x * (0.01f + unit(rng)), sign.y * (0.01f + unit(rng)),
                   sign.z * (0.01f + unit(rng)));
      p.push_back(Ray{point(0.2f), d});
    }
    AddPacket(&s, p);
  }
  // Random origins and directions of any signs (several groups per packet).
  for (int k = 0; k < 25; ++k) {
    std::vector<Ray> p;
    for (int l = 0; l < kRayPacketSize; ++l) {
      p.push_back(Ray{point(0.2f), Vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f)});
    }
    AddPacket(&s, p);
  }
  // Axis-parallel rays (a +0 or -0 component) from origins on vertex
  // coordinates, which are split planes of many trees.
  for (int k = 0; k < 78; ++k) {
    const int zero_axis = k % 3;
    const float zero = (k / 3) % 2 ? -0.0f : 0.0f;
    std::vector<Ray> p;
    for (int l = 0; l < kRayPacketSize; ++l) {
      const size_t v = rng() % soup.v.size();
      Vec3 o = point(0.1f);
      o[zero_axis] = soup.v[v][zero_axis];
      if (l == 1) o[(zero_axis + 1) % 3] = soup.v[v][(zero_axis + 1) % 3];
      Vec3 d(0.3f + unit(rng), 0.3f + unit(rng), 0.3f + unit(rng));
      for (int a = 0; a < 3; ++a) d[a] = (soup.v[v][a] >= o[a] ? 1.0f : -1.0f) * d[a];
      d[zero_axis] = zero;
      p.push_back(Ray{o, d});
    }
    // One sign pattern for the packet path: copy lane 0's signs.
    for (int l = 1; l < kRayPacketSize; ++l) {
      for (int a = 0; a < 3; ++a) p[l].dir[a] = std::copysign(p[l].dir[a], p[0].dir[a]);
    }
    AddPacket(&s, p);
  }
  // Fewer than 16 rays; invalid rays among valid ones; a bounded interval.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int k = 0; k < 48; ++k) {
    const Vec3 o = point(0.3f), target = point(0.0f);
    std::vector<Ray> p;
    for (int l = 0; l < kRayPacketSize; ++l) {
      p.push_back(Ray{o, target - o + Vec3(0.01f * l, 0.0f, 0.0f) * Length(ext)});
    }
    if (k % 4 == 0) p[1].dir = Vec3(nan, 1, 1);
    if (k % 4 == 1) { p[2].tmin = 1.0f; p[2].tmax = 0.5f; }
    if (k % 4 == 2) p[0].dir = Vec3(0, 0, 0);
    if (k % 4 == 3) { p[3].tmin = 0.4f; p[3].tmax = 0.6f; }
    p.resize(1 + k % kRayPacketSize);
    AddPacket(&s, p);
  }
  return s;
}

struct Counts {
  size_t packets = 0, closest = 0, any = 0, brute = 0, hits = 0;
};

// With `brute`, also against brute force.
Counts Check(const TriangleSoup& soup, const KdTree& tree, const PacketSet& s, bool brute = true) {
  const BruteForce bf(soup);
  Counts c;
  for (size_t k = 0; k < s.sizes.size(); ++k) {
    const Ray* rays = &s.rays[k * kRayPacketSize];
    const int n = s.sizes[k];
    Hit hits[kRayPacketSize];
    bool occ[kRayPacketSize], occ_end[kRayPacketSize];
    IntersectPacket(tree, rays, n, hits);
    OccludedPacket(tree, rays, n, nullptr, occ);
    TraversalOptions from_end;
    from_end.from_end = true;
    OccludedPacket(tree, rays, n, nullptr, occ_end, from_end);
    ++c.packets;
    for (int i = 0; i < n; ++i) {
      const Hit single = Intersect(tree, rays[i]);
      c.closest += !BitwiseSameHit(hits[i], single);
      const bool any = Occluded(tree, rays[i]);
      c.any += (occ[i] != any) + (occ_end[i] != any) + (Occluded(tree, rays[i], from_end) != any);
      if (!brute) continue;
      const Hit ref = bf.Intersect(rays[i]);
      c.brute += ref.hit() ? !BitwiseSameHit(hits[i], ref) : hits[i].hit();
      c.hits += ref.hit();
    }
  }
  return c;
}

TriangleSoup SceneNamed(const std::string& name) {
  if (name == "sphere") return testing::BumpySphere(4, 1);
  if (name == "voxels") return testing::VoxelGrid(10, 6, 10, 2);
  if (name == "thin") return testing::ThinSoup(2000, 3);
  return testing::FlatScene(1500, 4);
}

// The parameter's scene (soup_) and its tree under the parameter's preset
// (tree_).
class PacketVsSingle : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {
 protected:
  void SetUp() override {
    const auto& [scene, preset] = GetParam();
    soup_ = SceneNamed(scene);
    absl::StatusOr<Config> config = Preset(preset);
    ASSERT_TRUE(config.ok()) << config.status();
    absl::StatusOr<KdTree> tree = BuildKdTree(soup_, *config);
    ASSERT_TRUE(tree.ok()) << tree.status();
    tree_ = *std::move(tree);
  }

  TriangleSoup soup_;
  KdTree tree_;
};

TEST_P(PacketVsSingle, EveryLaneIsTheSingleRayResult) {
  const TriangleSoup& soup = soup_;
  const PacketSet s = MakePackets(soup, 7);
  const Counts c = Check(soup, tree_, s);
  EXPECT_EQ(c.closest, 0u);
  EXPECT_EQ(c.any, 0u);
  EXPECT_EQ(c.brute, 0u);
  // The packet path must really run, and there must be hits to compare.
  EXPECT_TRUE(PacketPathApplies(tree_));
  EXPECT_GT(c.hits, 100u);
}

// The same on every kernel width (Highway target) this machine runs, for two
// presets: the report's final variant and ours.
TEST_P(PacketVsSingle, EveryKernelWidth) {
  const std::string& preset = std::get<1>(GetParam());
  if (preset != "clipping-pruning" && preset != "sah-packet") GTEST_SKIP();
  const PacketSet s = MakePackets(soup_, 9);
  std::vector<std::string> ran;
  for (const std::string& target : PacketKernelTargets()) {
    const ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    ran.push_back(PacketKernelTarget());
    const Counts c = Check(soup_, tree_, s, /*brute=*/false);
    EXPECT_EQ(c.closest + c.any, 0u) << ran.back();
  }
  // At least the 4- and the 16-lane kernels on a machine with AVX-512.
  EXPECT_GE(ran.size(), 2u);
  std::string names;
  for (const std::string& n : ran) names += n + " ";
  std::printf("kernel targets checked: %s\n", names.c_str());
}

// The packet kernel's per-lane counts (PacketCounters::lanes) against the
// single-ray traversal's counters on the same rays: each lane visits the
// nodes and leaves its ray's traversal visits, and for the closest hit tests
// the same triangles. Any hit: front to back, from the end, and leaving each
// ray's closest-hit triangle untested.
void ExpectSameCounts(const KdTree& tree, const PacketSet& s, const std::string& where) {
  TraversalCounters single[4];
  PacketCounters packet[4];
  TraversalOptions from_end;
  from_end.from_end = true;
  for (size_t k = 0; k < s.sizes.size(); ++k) {
    const Ray* rays = &s.rays[k * kRayPacketSize];
    const int n = s.sizes[k];
    Hit hits[kRayPacketSize];
    bool occ[kRayPacketSize];
    uint32_t origins[kRayPacketSize];
    IntersectPacket(tree, rays, n, hits, TraversalOptions(), &packet[0]);
    OccludedPacket(tree, rays, n, nullptr, occ, TraversalOptions(), &packet[1]);
    OccludedPacket(tree, rays, n, nullptr, occ, from_end, &packet[2]);
    for (int i = 0; i < n; ++i) origins[i] = hits[i].tri;
    OccludedPacket(tree, rays, n, origins, occ, from_end, &packet[3]);
    for (int i = 0; i < n; ++i) {
      Intersect(tree, rays[i], TraversalOptions(), &single[0]);
      Occluded(tree, rays[i], TraversalOptions(), &single[1]);
      Occluded(tree, rays[i], from_end, &single[2]);
      TraversalOptions own = from_end;
      own.origin_tri = hits[i].tri;
      Occluded(tree, rays[i], own, &single[3]);
    }
  }
  const char* query[4] = {"closest", "any", "any from the end", "any without the hit"};
  for (int q = 0; q < 4; ++q) {
    const TraversalCounters& lanes = packet[q].lanes;
    EXPECT_EQ(lanes.rays, single[q].rays) << where << query[q];
    EXPECT_EQ(lanes.inner_visits, single[q].inner_visits) << where << query[q];
    EXPECT_EQ(lanes.leaf_visits, single[q].leaf_visits) << where << query[q];
    if (q == 0) {
      EXPECT_EQ(lanes.triangle_tests, single[q].triangle_tests) << where << query[q];
    }
    // The kernel's steps: at least one lane each, at most a vector's worth.
    EXPECT_LE(packet[q].inner_steps, lanes.inner_visits) << where << query[q];
    EXPECT_LE(lanes.inner_visits, packet[q].inner_steps * kRayPacketSize) << where << query[q];
  }
  EXPECT_GT(single[0].inner_visits, 0u) << where;
  EXPECT_GT(packet[0].triangle_steps, 0u) << where;
}

TEST_P(PacketVsSingle, EveryLaneVisitsItsRaysNodes) {
  const std::string& preset = std::get<1>(GetParam());
  const PacketSet s = MakePackets(soup_, 11);
  ExpectSameCounts(tree_, s, PacketKernelTarget() + std::string(" "));
  if (preset != "clipping-pruning" && preset != "sah-packet") return;
  for (const std::string& target : PacketKernelTargets()) {
    const ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    ExpectSameCounts(tree_, s, target + " ");
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllPresets, PacketVsSingle,
    ::testing::Combine(::testing::Values("sphere", "voxels", "thin", "flat"),
                       ::testing::ValuesIn(AllPresetNames())),
    [](const auto& info) {
      std::string n = std::get<0>(info.param) + "_" + std::get<1>(info.param);
      for (char& ch : n) {
        if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return n;
    });

// Per lane origin triangles: packets of 16 shadow rays spawned (spawn.h) from
// points on one triangle towards one light, told their true origin (never hit:
// the answer is Occluded's) or, adversarially, the triangle their closest hit
// is on (skipping it changes answers). Every lane must be the single-ray
// traversal's with TraversalOptions::origin_tri, and IntersectPacket with an
// origin_tri the single-ray Intersect with it.
TEST_P(PacketVsSingle, OriginTrianglesPerLane) {
  const std::string& scene = std::get<0>(GetParam());
  const TriangleSoup& soup = soup_;
  const BruteForce bf(soup);
  const AABB box = soup.Bounds();
  const Vec3 lights[2] = {box.hi + box.Extent() * 0.3f,
                          Vec3(box.lo.x, box.hi.y, box.lo.z) - box.Extent() * 0.2f};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  size_t packets = 0, differ = 0, skipped_hits = 0, brute = 0, shadowed = 0;
  for (uint32_t t = 0; t < soup.size(); t += 1 + soup.size() / 300) {
    const Vec3 n = GeometricNormal(soup.a(t), soup.b(t), soup.c(t));
    if (n.x == 0 && n.y == 0 && n.z == 0) continue;
    for (const Vec3& light : lights) {
      Ray rays[kRayPacketSize];
      uint32_t origin[kRayPacketSize], hit_tri[kRayPacketSize];
      for (int l = 0; l < kRayPacketSize; ++l) {
        float u = unit(rng), v = unit(rng);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const BoundedPoint p = HitPointWithError(soup.a(t), soup.b(t), soup.c(t), u, v);
        rays[l] = SpawnShadowRay(p, n, light);
        origin[l] = t;
        hit_tri[l] = Intersect(tree_, rays[l]).tri;
      }
      ++packets;
      for (const uint32_t* tris : {origin, hit_tri}) {
        bool occ[kRayPacketSize], occ_end[kRayPacketSize];
        OccludedPacket(tree_, rays, kRayPacketSize, tris, occ);
        TraversalOptions from_end;
        from_end.from_end = true;
        OccludedPacket(tree_, rays, kRayPacketSize, tris, occ_end, from_end);
        for (int l = 0; l < kRayPacketSize; ++l) {
          TraversalOptions o;
          o.origin_tri = tris[l];
          differ += occ[l] != Occluded(tree_, rays[l], o);
          differ += occ_end[l] != occ[l];
          o.from_end = true;
          differ += Occluded(tree_, rays[l], o) != occ[l];
          o.from_end = false;
          Hit hits[kRayPacketSize];
          IntersectPacket(tree_, &rays[l], 1, hits, o);
          differ += !BitwiseSameHit(hits[0], Intersect(tree_, rays[l], o));
          if (tris == origin) {
            brute += occ[l] != bf.Occluded(rays[l]);
            shadowed += occ[l];
          } else {
            skipped_hits += tris[l] != kNoHit;
          }
        }
      }
    }
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(brute, 0u);
  EXPECT_GT(packets, 10u);
  if (scene != "flat") {
    // (In the flat scene every triangle lies in one plane: a ray leaving it
    // meets nothing.)
    EXPECT_GT(shadowed, 0u);
    EXPECT_GT(skipped_hits, 0u);
  }
}

TEST(RayPacket, MixedSignsAndFallBacks) {
  const TriangleSoup soup = testing::BumpySphere(3, 2);
  absl::StatusOr<KdTree> tree = BuildKdTree(soup, Config());
  ASSERT_TRUE(tree.ok());
  EXPECT_TRUE(PacketPathApplies(*tree));
  EXPECT_FALSE(PacketPathApplies(*tree, WithTest(IntersectionMode::kFast)));
  EXPECT_FALSE(PacketPathApplies(KdTree()));
  // From inside the sphere (so every ray reaches the tree): all 8 sign
  // patterns and all 3 dominant axes in one packet. Results are the
  // single-ray ones on every path.
  const Vec3 c = (soup.Bounds().lo + soup.Bounds().hi) * 0.5f;
  std::vector<Ray> mixed;
  for (int i = 0; i < kRayPacketSize; ++i) {
    Vec3 d(i & 1 ? -1.0f : 1.0f, i & 2 ? -1.0f : 1.0f, i & 4 ? -1.0f : 1.0f);
    d[i % 3] *= 3.0f;
    mixed.push_back(Ray{c, d});
  }
  // The packet path, then the fallback (the fast test: one ray at a time).
  for (const TraversalOptions& o : {TraversalOptions(), WithTest(IntersectionMode::kFast)}) {
    Hit hits[kRayPacketSize];
    bool occ[kRayPacketSize];
    IntersectPacket(*tree, mixed.data(), kRayPacketSize, hits, o);
    OccludedPacket(*tree, mixed.data(), kRayPacketSize, nullptr, occ, o);
    for (int i = 0; i < kRayPacketSize; ++i) {
      EXPECT_TRUE(BitwiseSameHit(hits[i], Intersect(*tree, mixed[i], o)));
      EXPECT_TRUE(hits[i].hit());
      EXPECT_EQ(occ[i], Occluded(*tree, mixed[i], o));
    }
  }
}

}  // namespace
}  // namespace kdtree
