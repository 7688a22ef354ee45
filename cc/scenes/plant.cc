#include "cc/scenes/plant.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cc/scenes/random.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979f;

int Segments(float length, float per) { return std::max(1, static_cast<int>(std::lround(length / per))); }

// One bay with its lower-left corner at `o`.
Mesh Bay(const PlantConfig& c, const std::vector<const Part*>& machines,
         const std::vector<const Part*>& aux, int64_t index, Rng& rng, const Vec3& o) {
  Mesh bay;
  AddBox(bay, o + Vec3(0, -0.3f, 0), o + Vec3(c.bay_x, 0, c.bay_z));
  const float rack_y = 7.0f, rack_z = o.z + 0.8f * c.bay_z;
  for (int k = 0; k < c.machines_per_bay; ++k) {
    const Part& m = *machines[(index * c.machines_per_bay + k) % machines.size()];
    const float x = o.x + c.bay_x * (k + 0.5f) / c.machines_per_bay, z = o.z + 0.4f * c.bay_z;
    const float yaw = 0.5f * kPi * static_cast<float>(rng.UniformInt(4));
    AddBox(bay, Vec3(x - 2.5f, 0, z - 2.5f), Vec3(x + 2.5f, 0.5f, z + 2.5f));
    Place(bay, m.mesh, Vec3(x, 0.5f, z), yaw);
    // Riser from the machine's top to the rack, then across to it.
    const float top = 0.5f + m.height;
    AddTube(bay, Vec3(x, top, z), Vec3(x, rack_y, z), 0.15f, c.pipe_sides,
            Segments(rack_y - top, c.pipe_segment));
    AddTube(bay, Vec3(x, rack_y, z), Vec3(x, rack_y, rack_z), 0.15f, c.pipe_sides,
            Segments(rack_z - z, c.pipe_segment));
  }
  for (int j = 0; j < c.rack_pipes; ++j) {
    const float y = rack_y + 0.45f * static_cast<float>(j / 2), dz = (j % 2) ? 0.5f : -0.5f;
    AddTube(bay, Vec3(o.x, y, rack_z + dz), Vec3(o.x + c.bay_x, y, rack_z + dz),
            0.12f + 0.04f * static_cast<float>(j % 3), c.pipe_sides, Segments(c.bay_x, c.pipe_segment));
  }
  for (float x : {0.5f, 0.5f * c.bay_x, c.bay_x - 0.5f}) {
    AddBox(bay, Vec3(o.x + x - 0.15f, 0, rack_z - 0.9f), Vec3(o.x + x + 0.15f, rack_y - 0.3f, rack_z + 0.9f));
  }
  if (!aux.empty()) {
    const Part& a = *aux[index % aux.size()];
    Place(bay, a.mesh, Vec3(o.x + 0.5f * c.bay_x, 0, o.z + 0.12f * c.bay_z),
          0.5f * kPi * static_cast<float>(rng.UniformInt(4)));
  }
  return bay;
}

}  // namespace

absl::StatusOr<Mesh> GeneratePlant(const PlantConfig& c, const std::vector<Part>& parts) {
  const std::vector<const Part*> machines = PartsOf(parts, "machine");
  if (machines.empty()) return absl::InvalidArgumentError("plant: needs a 'machine' part");
  std::vector<const Part*> aux;
  for (const char* role : {"tank", "vessel", "transformer"}) {
    for (const Part* p : PartsOf(parts, role)) aux.push_back(p);
  }
  Rng rng(Mix64(c.seed) ^ 0x506c616e74ULL);  // "Plant"
  // The size of a bay decides the grid, so that the site is square.
  Rng probe(0);
  const int64_t per_bay = static_cast<int64_t>(Bay(c, machines, aux, 0, probe, Vec3(0, 0, 0)).faces.size());
  const int64_t bays = std::max<int64_t>(1, c.target_triangles / per_bay);
  const int cols = std::max(1, static_cast<int>(std::ceil(std::sqrt(bays * c.bay_z / c.bay_x))));
  const int rows = static_cast<int>((bays + cols - 1) / cols);
  const float width = cols * c.bay_x, depth = rows * c.bay_z;

  Mesh mesh;
  // The site behind the halls: cooling towers, chimneys, buildings in a row.
  float x = 0;
  for (const char* role : {"tower", "chimney", "building"}) {
    for (const Part* p : PartsOf(parts, role)) {
      const AABB b = p->mesh.Bounds();
      const float half = 0.5f * std::max(b.hi.x - b.lo.x, b.hi.z - b.lo.z);
      Place(mesh, p->mesh, Vec3(x + half, 0, depth + 20 + half), 0);
      x += 2 * half + 10;
    }
  }
  if (static_cast<int64_t>(mesh.faces.size()) > c.target_triangles) {
    return absl::InvalidArgumentError("plant: the site alone passes the target");
  }
  for (int64_t i = 0;; ++i) {
    const Vec3 o(static_cast<float>(i % cols) * c.bay_x, 0, static_cast<float>(i / cols) * c.bay_z);
    Mesh bay = Bay(c, machines, aux, i, rng, o);
    if (mesh.faces.size() + bay.faces.size() > static_cast<size_t>(c.target_triangles)) break;
    mesh.Append(bay);
  }
  // Header pipes along the front of the halls, then an exact fan.
  const int64_t per_pipe = 2LL * c.pipe_sides * Segments(width, c.pipe_segment);
  for (int j = 0; static_cast<int64_t>(mesh.faces.size()) + per_pipe <= c.target_triangles; ++j) {
    const float y = 1.0f + 0.7f * static_cast<float>(j % 12), z = -2.0f - 0.7f * static_cast<float>(j / 12);
    AddTube(mesh, Vec3(0, y, z), Vec3(width, y, z), 0.3f, c.pipe_sides, Segments(width, c.pipe_segment));
  }
  AddFan(mesh, Vec3(-5, 0, -5), 1.0f, c.target_triangles - static_cast<int64_t>(mesh.faces.size()));
  return mesh;
}

}  // namespace scenes
}  // namespace kdtree
