#include "cc/robust/soup_cleaner.h"

#include "cc/io/mesh_loader.h"

namespace kdtree {

TriangleSoup CleanSoup(const TriangleSoup& soup, CleanReport* report) {
  CleanReport local;
  CleanReport& r = report != nullptr ? *report : local;
  r = CleanReport();
  TriangleSoup out;
  out.v.reserve(soup.v.size());
  for (size_t t = 0; t < soup.size(); ++t) {
    const Vec3 &a = soup.a(t), &b = soup.b(t), &c = soup.c(t);
    if (!IsSaneTriangle(a, b, c)) {
      ++r.dropped_nonfinite;
    } else if (IsDegenerateTriangle(a, b, c)) {
      ++r.dropped_degenerate;
    } else {
      out.Add(a, b, c);
      r.original_index.push_back(static_cast<uint32_t>(t));
    }
  }
  r.kept = out.size();
  return out;
}

}  // namespace kdtree
