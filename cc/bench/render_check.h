// render_bench's validation, before anything is timed: every kd-tree variant
// must give the recorded render's answers exactly, and a sample of the
// recorded rays must agree with brute force.
#ifndef KDTREE_CC_BENCH_RENDER_CHECK_H_
#define KDTREE_CC_BENCH_RENDER_CHECK_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "cc/geometry/triangle.h"
#include "cc/kdtree/brute_force.h"
#include "cc/render/ray_record.h"
#include "cc/render/renderer.h"
#include "cc/render/tracer.h"
#include "cc/render/view.h"

namespace kdtree {
namespace bench {

// A traced way of rendering: a tracer and the renderer's modes.
struct RenderVariant {
  std::string name;
  const Tracer* tracer;
  bool packets = false;      // RenderOptions::packets
  bool skip_origin = false;  // RenderOptions::skip_origin
  // The packet kernel's Highway target ("AVX2", ...; ray_packet.h's
  // ScopedPacketKernelTarget); empty: the one Highway picks for the CPU.
  std::string kernel;
};

// Rays of `recs` on which `tracer` differs from the recorded result (hit
// flag; for primary rays also triangle, t, u, v).
uint64_t ExactMismatches(const std::vector<RayRecord>& recs, const Tracer& tracer);

// Brute-force check of `count` evenly spaced records; returns the
// mismatches and sets `checked`.
uint64_t BruteForceMismatches(const std::vector<RayRecord>& recs, const BruteForce& bf, int count,
                              uint64_t* checked);

// `v` against `recorded` (a recording render of the kd-tree with `base`):
// every recorded ray (ExactMismatches, returned in `mismatches`); with
// packets, its own render's primary hits bit for bit, shadow count and image;
// leaving origins untested, every recorded secondary ray from its primary
// hit's triangle and the image. Error: the first difference, naming scene
// and variant, or a kernel target this machine cannot run.
absl::Status CheckVariant(const std::string& scene, const TriangleSoup& soup, const View& view,
                          const RenderOptions& base, const RenderResult& recorded,
                          const RenderVariant& v, uint64_t* mismatches);

// What the camera sees: how many primary rays hit, and how many distinct
// triangles they hit. A render whose camera rays hit a handful of triangles
// times those, not the scene: until 2026-12-06 the camera of morse-trees and
// morse-buildings (737,856 and 457,936 triangles) saw only the outside of a
// sky box of 10 triangles around them (data/manifest.json, their notes).
struct CameraCoverage {
  uint64_t hits = 0;       // primary rays that hit a triangle
  uint64_t triangles = 0;  // distinct triangles those hits are on
};
CameraCoverage CameraCoverageOf(const std::vector<Hit>& primary_hits);

}  // namespace bench
}  // namespace kdtree

#endif  // KDTREE_CC_BENCH_RENDER_CHECK_H_
