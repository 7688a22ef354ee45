#include "cc/kdtree/ray_setup.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>

#include "cc/geometry/ray_check.h"
#include "cc/kdtree/packet_rays.h"
#include "cc/kdtree/ray_packet.h"
#include "gtest/gtest.h"

namespace kdtree {
namespace {

uint32_t Bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

// Every field the traversal reads, bit for bit.
void ExpectSame(const RaySetup& a, const RaySetup& b, int ray) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(Bits(a.org[k]), Bits(b.org[k])) << ray;
    EXPECT_EQ(Bits(a.inv[k]), Bits(b.inv[k])) << ray;
    EXPECT_EQ(Bits(a.tol[k]), Bits(b.tol[k])) << ray;
    EXPECT_EQ(a.negative[k], b.negative[k]) << ray;
  }
  EXPECT_EQ(Bits(a.delta), Bits(b.delta)) << ray;
  EXPECT_EQ(Bits(a.t_entry), Bits(b.t_entry)) << ray;
  EXPECT_EQ(Bits(a.t_exit), Bits(b.t_exit)) << ray;
  EXPECT_EQ(Bits(a.slack), Bits(b.slack)) << ray;
  const WatertightRay &u = a.wray, &v = b.wray;
  EXPECT_EQ(u.kx, v.kx) << ray;
  EXPECT_EQ(u.ky, v.ky) << ray;
  EXPECT_EQ(u.kz, v.kz) << ray;
  EXPECT_EQ(Bits(u.ox), Bits(v.ox)) << ray;
  EXPECT_EQ(Bits(u.oy), Bits(v.oy)) << ray;
  EXPECT_EQ(Bits(u.oz), Bits(v.oz)) << ray;
  EXPECT_EQ(Bits(u.sx), Bits(v.sx)) << ray;
  EXPECT_EQ(Bits(u.sy), Bits(v.sy)) << ray;
  EXPECT_EQ(Bits(u.sz), Bits(v.sz)) << ray;
}

// A float of random sign and magnitude 2^-30 .. 2^30, sometimes an exact
// small integer or zero (axis-aligned and tied components).
float Wild(std::mt19937& rng) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-30, 30);
  switch (kind(rng)) {
    case 0:
      return 0.0f;
    case 1:
      return -0.0f;
    case 2:
      return static_cast<float>(std::uniform_int_distribution<int>(-3, 3)(rng));
    default:
      return std::ldexp(unit(rng), exponent(rng));
  }
}

// A box of two Wild corners, or every seventh time (by i) the unit cube.
AABB WildBox(std::mt19937& rng, int i) {
  AABB box;
  box.Extend(Vec3(Wild(rng), Wild(rng), Wild(rng)));
  box.Extend(Vec3(Wild(rng), Wild(rng), Wild(rng)));
  if (i % 7 == 0) box = AABB(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  return box;
}

TEST(RaySetup, SimdEqualsScalarBitForBit) {
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int compared = 0, hits = 0, simd = 0;
  for (int i = 0; i < 400000; ++i) {
    const AABB box = WildBox(rng, i);
    Ray ray;
    // Origins inside, on and outside the box; directions of every scale.
    ray.origin = i % 3 == 0 ? Vec3(unit(rng), unit(rng), unit(rng)) * 2.0f
                            : Vec3(Wild(rng), Wild(rng), Wild(rng));
    ray.dir = i % 5 == 0 ? Vec3(unit(rng), unit(rng), unit(rng))
                         : Vec3(Wild(rng), Wild(rng), Wild(rng));
    ray.tmin = i % 4 == 0 ? -1.0f : 0.0f;
    ray.tmax = i % 6 == 0 ? 3.0f : INFINITY;
    if (!SanitizeRay(&ray)) continue;
    simd += ray.dir.x != 0 && ray.dir.y != 0 && ray.dir.z != 0;
    RaySetup a, b;
    const bool ha = SetUpRay(ray, box, &a);
    const bool hb = SetUpRayScalar(ray, box, &b);
    ASSERT_EQ(ha, hb) << i;
    ++compared;
    if (!ha) continue;
    ++hits;
    ExpectSame(a, b, i);
    if (::testing::Test::HasFailure()) return;
  }
  // Both outcomes and both paths are exercised.
  EXPECT_GT(compared, 300000);
  EXPECT_GT(hits, 50000);
  EXPECT_LT(hits, compared - 50000);
  EXPECT_GT(simd, 200000);
}

// A component as rays come: mostly Wild, sometimes NaN, infinite or
// subnormal (which SanitizeRay rejects or flushes to zero).
float Raw(std::mt19937& rng) {
  switch (std::uniform_int_distribution<int>(0, 40)(rng)) {
    case 0:
      return NAN;
    case 1:
      return -INFINITY;
    case 2:
      return INFINITY;
    case 3:
      return std::numeric_limits<float>::denorm_min();
    case 4:
      return -std::numeric_limits<float>::min() / 2;
    case 5:
      return std::numeric_limits<float>::min();
    default:
      return Wild(rng);
  }
}

// The traversal's entry (SanitizeAndSetUpRay, whose common case skips
// SanitizeRay) against SanitizeRay then SetUpRayScalar, on rays as given:
// the same answer, the same sanitized ray, and every field bit for bit.
TEST(RaySetup, SanitizeAndSetUpEqualsScalarBitForBit) {
  std::mt19937 rng(20261206);
  int hits = 0, misses = 0, rejected = 0;
  for (int i = 0; i < 400000; ++i) {
    const AABB box = WildBox(rng, i);
    Ray ray;
    ray.origin = Vec3(Raw(rng), Raw(rng), Raw(rng));
    ray.dir = Vec3(Raw(rng), Raw(rng), Raw(rng));
    ray.tmin = i % 4 == 0 ? -1.0f : i % 97 == 0 ? NAN : 0.0f;
    ray.tmax = i % 6 == 0 ? 3.0f : i % 89 == 0 ? -2.0f : INFINITY;
    Ray a = ray, b = ray;
    RaySetup sa, sb;
    const bool ha = SanitizeAndSetUpRay(&a, box, &sa);
    const bool valid = SanitizeRay(&b);
    const bool hb = valid && SetUpRayScalar(b, box, &sb);
    ASSERT_EQ(ha, hb) << i;
    rejected += !valid;
    if (!ha) {
      misses += valid;
      continue;
    }
    ++hits;
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(Bits(a.origin[k]), Bits(b.origin[k])) << i;
      ASSERT_EQ(Bits(a.dir[k]), Bits(b.dir[k])) << i;
    }
    ExpectSame(sa, sb, i);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(hits, 50000);
  EXPECT_GT(misses, 50000);
  EXPECT_GT(rejected, 20000);
}

// SetUpCommonBoxRay (the BVH's shadow rays) on rays as given: true exactly
// for the rays SanitizeRay leaves as they are with no direction component
// zero, and then org, inv and negative bit for bit SetUpRayScalar's.
TEST(RaySetup, CommonBoxRayEqualsFullSetUpBitForBit) {
  std::mt19937 rng(20261208);
  int common = 0, other = 0;
  for (int i = 0; i < 400000; ++i) {
    Ray ray;
    ray.origin = Vec3(Raw(rng), Raw(rng), Raw(rng));
    ray.dir = Vec3(Raw(rng), Raw(rng), Raw(rng));
    ray.tmin = i % 4 == 0 ? -1.0f : i % 97 == 0 ? NAN : 0.0f;
    ray.tmax = i % 6 == 0 ? 3.0f : i % 89 == 0 ? -2.0f : INFINITY;
    RaySetup lean;
    const bool is_common = SetUpCommonBoxRay(ray, &lean);
    Ray sanitized = ray;
    const bool unchanged = SanitizeRay(&sanitized) && sanitized.dir.x != 0 &&
                           sanitized.dir.y != 0 && sanitized.dir.z != 0 &&
                           std::memcmp(&sanitized, &ray, sizeof(Ray)) == 0;
    ASSERT_EQ(is_common, unchanged) << i;
    if (!is_common) {
      ++other;
      continue;
    }
    ++common;
    // SetUpRayScalar's fields, which SetUpVector's equal (above).
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(Bits(lean.org[k]), Bits(ray.origin[k])) << i;
      ASSERT_EQ(Bits(lean.inv[k]), Bits(1.0f / ray.dir[k])) << i;
      ASSERT_EQ(lean.negative[k], std::signbit(ray.dir[k])) << i;
    }
  }
  EXPECT_GT(common, 100000);
  EXPECT_GT(other, 50000);
}

// The packet kernel's vector set-up (packet_internal::SetUpLanes, 16 lanes at
// every kernel width the machine runs) against SetUpRay on each ray: the same
// answer, and every field bit for bit where the ray reaches the box (the
// watertight axes rebuilt from the lane's key bits); and without the frames
// of a packet that no lane reaches, the same answer.
TEST(RaySetup, VectorLanesEqualOneRayBitForBit) {
  constexpr int kLanes = packet_internal::kLanes;
  std::mt19937 rng(20261202);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int groups = 0, hits = 0, targets = 0, dead = 0;
  for (const std::string& target : PacketKernelTargets()) {
    const ScopedPacketKernelTarget scoped(target);
    ASSERT_TRUE(scoped.ok()) << target;
    ++targets;
    for (int g = 0; g < 8000; ++g) {
      const AABB box = WildBox(rng, g);
      Ray rays[kLanes];
      packet_internal::PacketRays p;
      bool ok = true;
      for (int i = 0; i < kLanes && ok; ++i) {
        Ray& ray = rays[i];
        ray.origin = g % 3 == 0 ? Vec3(unit(rng), unit(rng), unit(rng)) * 2.0f
                                : Vec3(Wild(rng), Wild(rng), Wild(rng));
        ray.dir = g % 5 == 0 ? Vec3(unit(rng), unit(rng), unit(rng))
                             : Vec3(Wild(rng), Wild(rng), Wild(rng));
        ray.tmin = (g + i) % 4 == 0 ? -1.0f : 0.0f;
        ray.tmax = (g + i) % 6 == 0 ? 3.0f : INFINITY;
        ok = SanitizeRay(&ray) && ray.dir.x != 0 && ray.dir.y != 0 && ray.dir.z != 0;
        for (int k = 0; k < 3; ++k) {
          p.org[k][i] = ray.origin[k];
          p.dir[k][i] = ray.dir[k];
        }
        p.tmin[i] = ray.tmin;
        p.tmax[i] = ray.tmax;
      }
      if (!ok) continue;
      ++groups;
      packet_internal::PacketRays q = p;
      const uint32_t live = packet_internal::SetUpLanes(box, &p);
      // Without frames for a packet none of whose lanes is live: the same
      // lanes (and the frames when some lane is).
      ASSERT_EQ(packet_internal::SetUpLanes(box, &q, /*frames_if_none=*/false), live) << g;
      if (live != 0) {
        ASSERT_EQ(std::memcmp(q.sx, p.sx, sizeof(p.sx)), 0) << g;
      } else {
        ++dead;
      }
      for (int i = 0; i < kLanes; ++i) {
        RaySetup one;
        ASSERT_EQ(SetUpRay(rays[i], box, &one), (live >> i & 1) != 0) << g;
        if (!(live >> i & 1)) continue;
        ++hits;
        RaySetup lane;
        for (int k = 0; k < 3; ++k) {
          lane.org[k] = p.org[k][i];
          lane.inv[k] = p.inv[k][i];
          lane.tol[k] = p.tol[k][i];
          lane.negative[k] = packet_internal::LaneNegative(p, i, k);
        }
        lane.delta = p.delta[i];
        lane.t_entry = p.t_entry[i];
        lane.t_exit = p.t_exit[i];
        lane.slack = p.slack[i];
        const int kz = packet_internal::LaneKz(p, i);
        int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
        if (lane.negative[kz]) std::swap(kx, ky);
        lane.wray = packet_internal::LaneRay(p, kx, ky, kz, i);
        ExpectSame(lane, one, g);
        const float weight = watertight_internal::ShearWeight(one.wray);
        ASSERT_EQ(std::memcmp(&p.shear_weight[i], &weight, sizeof(float)), 0) << g;
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
  EXPECT_GE(targets, 2);
  EXPECT_GT(groups, 1000 * targets);
  EXPECT_GT(hits, 10000);
  EXPECT_LT(hits, kLanes * groups - 10000);
  EXPECT_GT(dead, 10);
}

}  // namespace
}  // namespace kdtree
