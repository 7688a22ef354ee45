// Whitted-style ray casting of a view with any Tracer (the report's
// "Results": one primary ray per pixel, one shadow ray per primary hit).
//
// Rays, in this order, each effect over the whole image before the next:
//  1. primary: one closest-hit ray per pixel centre (camera.h);
//  2. shadow:  one any-hit ray per primary hit and per light, only when the
//              view has lights and `cast_shadow_rays` is on (the report's
//              RTCore.castShadowRays); a view without lights traces none;
//  3. ao:      `samples` any-hit rays per primary hit, only when the view asks
//              for ambient occlusion;
//  4. shading: two-sided Lambert (|n . l| on the side facing the viewer) with
//              shadows, plus a dim ambient term scaled by the unoccluded AO
//              fraction; without lights, a headlight (|n . view|). Then gamma
//              1/2.2 to 8-bit RGB.
// Secondary ray origins and directions: secondary_rays.h.
//
// Timing: T_R (`seconds`) is the wall time of all four steps (ray generation,
// tracing, shading); each effect's `seconds` is the wall time of its step.
// The tracer is used as given: for the kd-tree that is the non-counting fast
// path. Traversal counts (N_IT, N_TR) come from a separate counting pass over
// the recorded rays (traversal_counts.h), so counting never touches T_R.
//
// Pixel order: every ray pass, single rays or packets, visits the pixels in
// 4x4 blocks, left to right along bands of 4 rows (tiles: within each tile),
// so the two modes differ in how they trace and not in which rays come
// together.
//
// Threads: 1 (default) runs plain loops on the calling thread. threads > 1
// runs each step as tbb::parallel_for over square tiles of `tile_size` pixels
// (over whole rows when recording rays, or when tile_size is 0), capped with
// tbb::global_control. Every pixel's rays depend only on the pixel, and
// counts are integer sums, so image, counts and recorded rays are identical
// for any thread count and tile size.
#ifndef KDTREE_CC_RENDER_RENDERER_H_
#define KDTREE_CC_RENDER_RENDERER_H_

#include <cstdint>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"
#include "cc/render/ray_record.h"
#include "cc/render/tracer.h"
#include "cc/render/view.h"

namespace kdtree {

struct RenderOptions {
  // Worker threads; 1 = no TBB at all.
  int threads = 1;
  // Side of the square tiles rendered in parallel (threads > 1, not
  // recording); 0 = whole rows.
  int tile_size = 16;
  // RTCore.castShadowRays: shadow rays when the view has lights.
  bool cast_shadow_rays = true;
  // Trace primary and shadow rays in packets of 4x4 pixels (per light, the
  // block's shadow rays together) through Tracer::IntersectPacket and
  // OccludedPacket (the kd-tree's packet traversal, cc/kdtree/ray_packet.h;
  // Embree's rtcIntersect16 / rtcOccluded16). AO rays stay single. Results,
  // hence the image, are the single-ray ones. Ignored when recording rays.
  bool packets = false;
  // Beyond the report: shadow and AO rays tell Tracer::Occluded (and, with
  // packets, Tracer::OccludedPacket) the primary hit's triangle, which the
  // kd-tree then leaves untested (it can never hit it:
  // TraversalOptions::origin_tri) and searches the ray from its end, the
  // light for a shadow ray (TraversalOptions::from_end; KdTreeTracer).
  // Results, hence the image, are unchanged. Off: every triangle met is tested, as the
  // counting pass (traversal_counts.h) counts them.
  bool skip_origin = false;
  // Keep every ray and its result in RenderResult::rays (primary rays in pixel
  // order, then shadow rays by pixel and light, then AO rays by pixel and
  // sample). Costs time and memory: leave off for timed runs.
  bool record_rays = false;
  // Shading: fraction of the light that is ambient, surface and background
  // colours (linear RGB in [0, 1]).
  float ambient = 0.15f;
  Vec3 albedo{0.80f, 0.78f, 0.74f};
  Vec3 background{0.10f, 0.11f, 0.14f};
};

struct EffectStats {
  uint64_t rays = 0;
  double seconds = 0;  // wall time of the effect's step
};

struct RenderResult {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;       // width * height * 3, top row first
  std::vector<Hit> primary_hits;  // one per pixel, row-major
  uint64_t p_hit = 0, p_miss = 0;    // primary rays
  uint64_t s_hit = 0, s_miss = 0;    // shadow rays: hit = occluded
  uint64_t ao_hit = 0, ao_miss = 0;  // AO rays: hit = occluded
  EffectStats primary, shadow, ao;
  double seconds = 0;  // T_R
  std::vector<RayRecord> rays;  // when RenderOptions::record_rays

  uint64_t total_rays() const { return primary.rays + shadow.rays + ao.rays; }
};

// The bytes Render allocates for `view` with `options`, at worst (every
// primary ray hits): per pixel a Hit, 3 image bytes and a 16-bit AO count,
// an occlusion flag per pixel and light, and with record_rays three
// RayRecords per ray (per-row buffers grown by doubling, then the result).
// What a caller checks against its memory budget before rendering.
uint64_t RenderBytes(const View& view, const RenderOptions& options);

// `view` must be valid; `tracer` must have been built on `soup` (triangle
// indices are used to find normals).
RenderResult Render(const TriangleSoup& soup, const Tracer& tracer, const View& view,
                    const RenderOptions& options);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_RENDERER_H_
