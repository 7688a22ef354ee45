#include "cc/render/compare.h"

#include <cmath>

#include "absl/strings/str_format.h"

namespace kdtree {
namespace {

std::string KindJson(const KindDisagreements& k) {
  return absl::StrFormat(
      "{\"rays\": %d, \"total\": %d, \"grazing\": %d, \"other\": %d, \"hit_miss\": %d, "
      "\"t_differs\": %d}",
      k.rays, k.total(), k.grazing, k.other(), k.hit_miss, k.t_differs);
}

void Add(const KindDisagreements& k, KindDisagreements* sum) {
  sum->rays += k.rays;
  sum->hit_miss += k.hit_miss;
  sum->t_differs += k.t_differs;
  sum->grazing += k.grazing;
}

}  // namespace

bool NearEdge(const Hit& hit) {
  return hit.hit() && std::fmin(hit.u, std::fmin(hit.v, 1.0f - hit.u - hit.v)) < kGrazingBary;
}

std::string Disagreements::ToJson() const {
  std::string k = KindJson(all);
  k.pop_back();  // the closing brace: the per-kind objects go inside
  for (int i = 0; i < kNumRayKinds; ++i) {
    absl::StrAppendFormat(&k, ", \"%s\": %s", RayKindName(static_cast<RayKind>(i)),
                          KindJson(by_kind[i]));
  }
  return k + "}";
}

Disagreements CompareTracers(const std::vector<RayRecord>& records, const Tracer& reference,
                             const Tracer& other) {
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
    if (NearEdge(a) || NearEdge(b)) {
      ++k.grazing;
    } else if (d.examples.size() < 20) {
      d.examples.push_back(absl::StrFormat(
          "record %d (%s, pixel %d): %s tri %d t %.9g u %.6g v %.6g; %s tri %d t %.9g u %.6g "
          "v %.6g; recorded hit %d",
          i, RayKindName(rec.kind), rec.pixel, reference.name(), a.tri, a.t, a.u, a.v,
          other.name(), b.tri, b.t, b.u, b.v, rec.hit));
    }
  }
  for (const KindDisagreements& k : d.by_kind) Add(k, &d.all);
  return d;
}

}  // namespace kdtree
