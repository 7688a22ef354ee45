#include "cc/render/compare.h"

#include <cmath>

#include "absl/strings/str_format.h"
#include "cc/geometry/watertight.h"
#include "cc/render/exact_check.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

nlohmann::ordered_json KindJson(const KindDisagreements& k) {
  return {{"rays", k.rays},
          {"total", k.total()},
          {"grazing", k.grazing},
          {"at_origin", k.at_origin},
          {"t_guard", k.t_guard},
          {"other", k.other()},
          {"hit_miss", k.hit_miss},
          {"t_differs", k.t_differs},
          {"reference_wrong", k.reference_wrong},
          {"other_wrong", k.other_wrong}};
}

void Add(const KindDisagreements& k, KindDisagreements* sum) {
  sum->rays += k.rays;
  sum->hit_miss += k.hit_miss;
  sum->t_differs += k.t_differs;
  sum->grazing += k.grazing;
  sum->at_origin += k.at_origin;
  sum->t_guard += k.t_guard;
  sum->reference_wrong += k.reference_wrong;
  sum->other_wrong += k.other_wrong;
}

ExactTriangleHit Exact(const TriangleSoup& soup, const Ray& ray, const Hit& h) {
  return ExactIntersect(ray, soup.a(h.tri), soup.b(h.tri), soup.c(h.tri));
}

bool Grazing(const ExactTriangleHit& e) {
  return e.edge_distance <= kGrazingUlps * FloatUlp(e.magnitude);
}

bool AtOrigin(const ExactTriangleHit& e) {
  return e.plane_distance <= kAtOriginUlps * FloatUlp(e.magnitude);
}

// The watertight test alone on one triangle.
bool WatertightHits(const TriangleSoup& soup, const Ray& ray, uint32_t tri) {
  float t, u, v;
  return IntersectTriangleWatertight(MakeWatertightRay(ray), soup.a(tri), soup.b(tri),
                                     soup.c(tri), ray.tmin, ray.tmax, &t, &u, &v);
}

}  // namespace

nlohmann::ordered_json Disagreements::ToJson() const {
  nlohmann::ordered_json j = KindJson(all);
  for (int i = 0; i < kNumRayKinds; ++i) {
    j[RayKindName(static_cast<RayKind>(i))] = KindJson(by_kind[i]);
  }
  return j;
}

Disagreements CompareTracers(const std::vector<RayRecord>& records, const TriangleSoup& soup,
                             const Tracer& reference, const Tracer& other) {
  Disagreements d;
  for (size_t i = 0; i < records.size(); ++i) {
    const RayRecord& rec = records[i];
    KindDisagreements& k = d.by_kind[static_cast<int>(rec.kind)];
    ++k.rays;
    const Ray ray = rec.ray();
    bool hit_miss = false, t_differs = false;
    Hit mine;  // the other tracer's closest hit (primary rays)
    if (rec.kind == RayKind::kPrimary) {
      mine = other.Intersect(ray);
      if (mine.hit() != (rec.hit != 0)) {
        hit_miss = true;
      } else if (mine.hit() &&
                 std::fabs(mine.t - rec.t) > kCompareRelT * std::fmax(mine.t, rec.t)) {
        t_differs = true;
      }
    } else {
      hit_miss = other.Occluded(ray) != (rec.hit != 0);
    }
    if (!hit_miss && !t_differs) continue;
    k.hit_miss += hit_miss;
    k.t_differs += t_differs;
    const Hit a = reference.Intersect(ray);
    const Hit b = rec.kind == RayKind::kPrimary ? mine : other.Intersect(ray);
    ExactTriangleHit ea, eb;
    if (a.hit()) ea = Exact(soup, ray, a);
    if (b.hit()) eb = Exact(soup, ray, b);

    // Exact verdict: the claim of the nearer (or only) hit is checked.
    const bool ref_claims = rec.kind == RayKind::kPrimary
                                ? (rec.hit != 0 && (!mine.hit() || rec.t < mine.t))
                                : rec.hit != 0;
    const Hit& claim = ref_claims ? a : b;
    const ExactTriangleHit& eclaim = ref_claims ? ea : eb;
    const bool claim_right = claim.hit() && eclaim.hit;
    if (claim_right != ref_claims) {
      ++k.reference_wrong;
    } else {
      ++k.other_wrong;
    }

    const char* cls = "other";
    if ((a.hit() && Grazing(ea)) || (b.hit() && Grazing(eb))) {
      ++k.grazing;
      continue;
    } else if ((a.hit() && AtOrigin(ea)) || (b.hit() && AtOrigin(eb))) {
      ++k.at_origin;
      cls = "at_origin";
    } else if (!ref_claims && claim_right && !WatertightHits(soup, ray, claim.tri)) {
      ++k.t_guard;
      cls = "t_guard";
    }
    if (d.examples.size() < 20) {
      auto show = [](const Hit& h, const ExactTriangleHit& e) {
        if (!h.hit()) return std::string("miss");
        return absl::StrFormat(
            "tri %d t %.9g u %.6g v %.6g (exact: %s, t %.9g; edge distance %.3g, origin-plane "
            "distance %.3g = %.3g, %.3g ulps of %.6g)",
            h.tri, h.t, h.u, h.v, e.hit ? "hit" : "no hit", e.t, e.edge_distance,
            e.plane_distance, e.edge_distance / FloatUlp(e.magnitude),
            e.plane_distance / FloatUlp(e.magnitude), e.magnitude);
      };
      d.examples.push_back(absl::StrFormat(
          "record %d (%s, pixel %d) %s: %s %s; %s %s; recorded hit %d; wrong: %s", i,
          RayKindName(rec.kind), rec.pixel, cls, reference.name(), show(a, ea), other.name(),
          show(b, eb), rec.hit, claim_right != ref_claims ? reference.name() : other.name()));
    }
  }
  for (const KindDisagreements& k : d.by_kind) Add(k, &d.all);
  return d;
}

}  // namespace kdtree
