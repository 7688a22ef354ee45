#include "cc/bench/render_check.h"

#include <algorithm>
#include <optional>

#include "absl/strings/str_cat.h"
#include "cc/kdtree/ray_packet.h"

namespace kdtree {
namespace bench {
namespace {

// Packets: every primary hit bit for bit, the shadow count and the image.
uint64_t PacketDifferences(const TriangleSoup& soup, const View& view, const RenderOptions& base,
                           const RenderResult& recorded, const RenderVariant& v) {
  RenderOptions po = base;
  po.packets = true;
  po.skip_origin = v.skip_origin;
  const RenderResult r = Render(soup, *v.tracer, view, po);
  uint64_t differ = r.s_hit != recorded.s_hit || r.rgb != recorded.rgb;
  for (size_t p = 0; p < r.primary_hits.size(); ++p) {
    const Hit& a = r.primary_hits[p];
    const Hit& b = recorded.primary_hits[p];
    differ += !(a.tri == b.tri && a.t == b.t && a.u == b.u && a.v == b.v);
  }
  return differ;
}

// Origins untested: every recorded shadow and AO ray, from its primary hit's
// triangle, and the image.
uint64_t OriginDifferences(const TriangleSoup& soup, const View& view, const RenderOptions& base,
                           const RenderResult& recorded, const RenderVariant& v) {
  uint64_t differ = 0;
  for (const RayRecord& rec : recorded.rays) {
    if (rec.kind == RayKind::kPrimary) continue;
    const uint32_t origin = recorded.primary_hits[rec.pixel].tri;
    differ += v.tracer->Occluded(rec.ray(), origin) != (rec.hit != 0);
  }
  RenderOptions so = base;
  so.skip_origin = true;
  const RenderResult r = Render(soup, *v.tracer, view, so);
  differ += r.s_hit != recorded.s_hit || r.rgb != recorded.rgb;
  return differ;
}

}  // namespace

uint64_t ExactMismatches(const std::vector<RayRecord>& recs, const Tracer& tracer) {
  uint64_t bad = 0;
  for (const RayRecord& r : recs) {
    if (r.kind == RayKind::kPrimary) {
      const Hit h = tracer.Intersect(r.ray());
      const bool same = h.hit() == (r.hit != 0) &&
                        (!h.hit() || (h.tri == r.tri && h.t == r.t && h.u == r.u && h.v == r.v));
      bad += !same;
    } else {
      bad += tracer.Occluded(r.ray()) != (r.hit != 0);
    }
  }
  return bad;
}

uint64_t BruteForceMismatches(const std::vector<RayRecord>& recs, const BruteForce& bf, int count,
                              uint64_t* checked) {
  *checked = 0;
  if (count <= 0 || recs.empty()) return 0;
  const size_t step = std::max<size_t>(1, recs.size() / count);
  uint64_t bad = 0;
  for (size_t i = 0; i < recs.size(); i += step) {
    const RayRecord& r = recs[i];
    ++*checked;
    if (r.kind == RayKind::kPrimary) {
      const Hit h = bf.Intersect(r.ray());
      bad += !(h.hit() == (r.hit != 0) && (!h.hit() || (h.tri == r.tri && h.t == r.t)));
    } else {
      bad += bf.Occluded(r.ray()) != (r.hit != 0);
    }
  }
  return bad;
}

absl::Status CheckVariant(const std::string& scene, const TriangleSoup& soup, const View& view,
                          const RenderOptions& base, const RenderResult& recorded,
                          const RenderVariant& v, uint64_t* mismatches) {
  std::optional<ScopedPacketKernelTarget> kernel;
  if (!v.kernel.empty() && !kernel.emplace(v.kernel).ok()) {
    return absl::InvalidArgumentError(absl::StrCat(v.name, ": no packet kernel '", v.kernel,
                                                   "' on this machine"));
  }
  *mismatches = ExactMismatches(recorded.rays, *v.tracer);
  if (*mismatches != 0) {
    return absl::InternalError(
        absl::StrCat(scene, ": ", v.name, " differs from kd on ", *mismatches, " rays"));
  }
  if (v.packets && PacketDifferences(soup, view, base, recorded, v) != 0) {
    return absl::InternalError(absl::StrCat(scene, ": ", v.name, " packets differ from kd"));
  }
  if (v.skip_origin && OriginDifferences(soup, view, base, recorded, v) != 0) {
    return absl::InternalError(absl::StrCat(scene, ": ", v.name, " differs from kd"));
  }
  return absl::OkStatus();
}

CameraCoverage CameraCoverageOf(const std::vector<Hit>& primary_hits) {
  std::vector<uint32_t> tris;
  for (const Hit& h : primary_hits) {
    if (h.hit()) tris.push_back(h.tri);
  }
  CameraCoverage c;
  c.hits = tris.size();
  std::sort(tris.begin(), tris.end());
  c.triangles = static_cast<uint64_t>(std::unique(tris.begin(), tris.end()) - tris.begin());
  return c;
}

}  // namespace bench
}  // namespace kdtree
