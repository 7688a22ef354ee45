#include "cc/scenes/hairball.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

// Uniform random point in the unit ball (rejection sampling).
Vec3 RandomInBall(Rng& rng) {
  while (true) {
    const Vec3 p(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
    if (Dot(p, p) <= 1.0f) return p;
  }
}

Vec3 RandomDirection(Rng& rng) {
  while (true) {
    const Vec3 p = RandomInBall(rng);
    const float len2 = Dot(p, p);
    if (len2 > 1e-4f) return p / std::sqrt(len2);
  }
}

// Any unit vector perpendicular to unit `t`.
Vec3 Perpendicular(const Vec3& t) {
  const Vec3 axis = std::fabs(t.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return Normalize(Cross(t, axis));
}

// Rotates `v` about unit `axis` by `angle` (Rodrigues).
Vec3 Rotate(const Vec3& v, const Vec3& axis, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + Cross(axis, v) * s + axis * (Dot(axis, v) * (1.0f - c));
}

// One smooth random curve of `points` points starting inside the ball.
std::vector<Vec3> RandomCurve(Rng& rng, int points, const HairballConfig& config) {
  std::vector<Vec3> curve;
  curve.reserve(points);
  Vec3 p = RandomInBall(rng) * (0.9f * config.ball_radius);
  Vec3 t = RandomDirection(rng);
  Vec3 turn = RandomDirection(rng);  // axis of the current turn, drifts slowly
  const float step = config.step * config.ball_radius;
  for (int i = 0; i < points; ++i) {
    curve.push_back(p);
    turn = Normalize(turn + RandomDirection(rng) * 0.3f);
    Vec3 axis = Cross(t, turn);
    if (Dot(axis, axis) < 1e-8f) axis = Perpendicular(t);
    t = Normalize(Rotate(t, Normalize(axis), config.curl * rng.Uniform(0.2f, 1.0f)));
    const float r = Length(p);
    if (r > config.ball_radius) {  // steer back inside, harder the further out
      const float pull = std::min(1.0f, 2.0f * (r / config.ball_radius - 1.0f) + 0.1f);
      t = Normalize(t - p / r * pull);
    }
    p = p + t * step;
  }
  return curve;
}

// Emits a tube of `sides` sides around `curve`, with parallel-transported frames.
void AddTube(Mesh& mesh, const std::vector<Vec3>& curve, int sides, float radius) {
  const int n = static_cast<int>(curve.size());
  const int32_t base = static_cast<int32_t>(mesh.vertices.size());
  Vec3 normal;
  for (int i = 0; i < n; ++i) {
    const Vec3 t = Normalize(i + 1 < n ? curve[i + 1] - curve[i] : curve[i] - curve[i - 1]);
    if (i == 0) {
      normal = Perpendicular(t);
    } else {
      const Vec3 projected = normal - t * Dot(normal, t);
      normal = Dot(projected, projected) > 1e-12f ? Normalize(projected) : Perpendicular(t);
    }
    const Vec3 binormal = Cross(t, normal);
    for (int s = 0; s < sides; ++s) {
      const float angle = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(sides);
      mesh.AddVertex(curve[i] + (normal * std::cos(angle) + binormal * std::sin(angle)) * radius);
    }
  }
  for (int i = 0; i + 1 < n; ++i) {
    for (int s = 0; s < sides; ++s) {
      const int s1 = (s + 1) % sides;
      mesh.AddQuad(base + i * sides + s, base + i * sides + s1, base + (i + 1) * sides + s1,
                   base + (i + 1) * sides + s);
    }
  }
}

}  // namespace

Mesh GenerateHairball(const HairballConfig& config) {
  const int sides = std::max(3, config.sides);
  const int per_tube = std::max(1, config.segments_per_tube);
  const int64_t target = std::max<int64_t>(config.target_triangles, 2 * sides);
  const int64_t segments = std::max<int64_t>(1, (target + sides) / (2 * sides));
  const int64_t tubes = (segments + per_tube - 1) / per_tube;
  float radius = config.tube_radius;
  if (radius <= 0) {
    radius = std::min(0.03f, 0.0025f * std::sqrt(2880000.0f / static_cast<float>(target)));
  }
  radius *= config.ball_radius;

  Mesh mesh;
  mesh.vertices.reserve(static_cast<size_t>((segments + tubes) * sides));
  mesh.faces.reserve(static_cast<size_t>(2 * sides * segments));
  Rng rng(Mix64(config.seed) ^ 0x4861697262616c6cULL);  // "Hairball"
  for (int64_t k = 0; k < tubes; ++k) {
    // Equal shares: the first (segments % tubes) tubes take one more segment.
    const int64_t count = segments / tubes + (k < segments % tubes ? 1 : 0);
    AddTube(mesh, RandomCurve(rng, static_cast<int>(count) + 1, config), sides, radius);
  }
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
