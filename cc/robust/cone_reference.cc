#include "cc/robust/cone_reference.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "cc/robust/preset_check.h"

namespace kdtree {
namespace robust {

namespace {

constexpr double kMargin = 1e-5;  // radians, on each cone

struct Dir {
  double x, y, z;
};

Dir Normalized(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

double Angle(const Dir& a, const Dir& b) {
  const double c = a.x * b.x + a.y * b.y + a.z * b.z;
  return std::acos(std::clamp(c, -1.0, 1.0));
}

// The direction through point (u, v) of cube face `face` (axis face / 2,
// negative when face is odd).
Dir FaceDir(int face, double u, double v) {
  double d[3];
  const int f = face / 2;
  d[f] = (face & 1) ? -1.0 : 1.0;
  d[(f + 1) % 3] = u;
  d[(f + 2) % 3] = v;
  return Normalized(d[0], d[1], d[2]);
}

}  // namespace

absl::StatusOr<ConeReference> ConeReference::Make(const TriangleSoup& soup, const Vec3& origin,
                                                  int cells_per_face) {
  ConeReference r;
  r.origin_ = origin;
  r.n_ = cells_per_face;
  const int n = cells_per_face;
  const double ox = origin.x, oy = origin.y, oz = origin.z;
  // Triangle cones.
  const size_t count = soup.size();
  std::vector<Dir> axis(count);
  std::vector<double> cos_t(count), sin_t(count);
  for (size_t t = 0; t < count; ++t) {
    const Vec3* v[3] = {&soup.a(t), &soup.b(t), &soup.c(t)};
    double cx = 0, cy = 0, cz = 0;
    for (const Vec3* p : v) {
      cx += (p->x - ox) / 3;
      cy += (p->y - oy) / 3;
      cz += (p->z - oz) / 3;
    }
    axis[t] = Normalized(cx, cy, cz);
    double half = 0;
    for (const Vec3* p : v) {
      half = std::max(half, Angle(axis[t], Normalized(p->x - ox, p->y - oy, p->z - oz)));
    }
    if (!(half < 1.5)) {
      return absl::InvalidArgumentError(
          absl::StrCat("triangle ", t, " subtends too wide an angle from the origin"));
    }
    half += kMargin;
    cos_t[t] = std::cos(half);
    sin_t[t] = std::sin(half);
  }
  // Cell cones and their candidates.
  const int cells = 6 * n * n;
  r.candidates_.assign(cells, {});
  ParallelFor(cells, [&](size_t begin, size_t end) {
    for (size_t cell = begin; cell < end; ++cell) {
      const int face = static_cast<int>(cell) / (n * n);
      const int iu = static_cast<int>(cell) / n % n, iv = static_cast<int>(cell) % n;
      const double u0 = -1 + 2.0 * iu / n, u1 = -1 + 2.0 * (iu + 1) / n;
      const double v0 = -1 + 2.0 * iv / n, v1 = -1 + 2.0 * (iv + 1) / n;
      const Dir centre = FaceDir(face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
      double half = 0;
      for (double u : {u0, u1}) {
        for (double v : {v0, v1}) half = std::max(half, Angle(centre, FaceDir(face, u, v)));
      }
      half += kMargin;
      const double cos_c = std::cos(half), sin_c = std::sin(half);
      std::vector<uint32_t>& list = r.candidates_[cell];
      for (size_t t = 0; t < count; ++t) {
        // Cones meet when angle(axes) <= half_t + half_c.
        const double dot = axis[t].x * centre.x + axis[t].y * centre.y + axis[t].z * centre.z;
        const double cos_sum = cos_t[t] * cos_c - sin_t[t] * sin_c;
        if (dot >= cos_sum) list.push_back(static_cast<uint32_t>(t));
      }
    }
  });
  return r;
}

int ConeReference::Cell(const Vec3& dir) const {
  const double d[3] = {dir.x, dir.y, dir.z};
  int f = 0;
  if (std::fabs(d[1]) > std::fabs(d[f])) f = 1;
  if (std::fabs(d[2]) > std::fabs(d[f])) f = 2;
  const int face = 2 * f + (d[f] < 0 ? 1 : 0);
  const double m = std::fabs(d[f]);
  const double u = d[(f + 1) % 3] / m, v = d[(f + 2) % 3] / m;
  const int iu = std::clamp(static_cast<int>((u + 1) / 2 * n_), 0, n_ - 1);
  const int iv = std::clamp(static_cast<int>((v + 1) / 2 * n_), 0, n_ - 1);
  return (face * n_ + iu) * n_ + iv;
}

Hit ConeReference::Intersect(const BruteForce& bf, const Ray& ray, IntersectionMode mode) const {
  return bf.Intersect(ray, candidates_[Cell(ray.dir)], mode);
}

double ConeReference::MeanCandidates() const {
  double sum = 0;
  for (const auto& c : candidates_) sum += c.size();
  return candidates_.empty() ? 0 : sum / candidates_.size();
}

}  // namespace robust
}  // namespace kdtree
