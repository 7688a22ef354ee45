// Instancing real parts into a large scene, to an exact triangle count: the
// shared pieces of the power plant (plant.h) and courtyard (courtyard.h)
// generators, which stand in for the report's scenes 14 (powerplant,
// 12,759,246 triangles) and 16 (san-miguel, 9,980,699).
//
// A part is a packaged model (a CAD engine, a tree, a chair...) normalised to
// its real size: rotated y-up, centred on the y axis, its bottom on y = 0,
// scaled to a given height in metres. Instances are flattened copies (as the
// report's scenes are triangle soups). Generators place parts until the next
// would pass the target, then close the gap with a few procedural pieces; the
// last gap is filled exactly by a flat fan (a drain cover, a manhole: n
// triangles for any n >= 1).
#ifndef KDTREE_CC_SCENES_ASSEMBLY_H_
#define KDTREE_CC_SCENES_ASSEMBLY_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct Part {
  std::string role;  // what the layout does with it ("tree", "machine", ...)
  float height = 1;  // metres, after normalisation
  Mesh mesh;         // normalised
};

// `mesh` rotated to y-up (up_axis 1: as is; 2: z-up input), centred on the y
// axis, bottom on y = 0, scaled to `height`.
Mesh NormalisePart(const Mesh& mesh, float height, int up_axis = 1);

// Parses "role:height:path[:up_axis]" and reads the mesh (assimp_mesh.h's
// ReadMesh).
absl::StatusOr<Part> ReadPart(const std::string& spec);

// Parts of `role`, in the order given; empty if none.
std::vector<const Part*> PartsOf(const std::vector<Part>& parts, const std::string& role);

// Appends `part` rotated by `yaw` (radians, about y), scaled by `scale` and
// moved to `position` (where its bottom centre lands). Triangles of zero area
// after the move are left out (the loader, cc/io, would drop them).
void Place(Mesh& out, const Mesh& part, const Vec3& position, float yaw, float scale = 1);

// Open tube between a and b, `sides` sides, `segments` segments along it:
// 2 * sides * segments triangles. a != b.
void AddTube(Mesh& out, const Vec3& a, const Vec3& b, float radius, int sides, int segments);

// Horizontal disc at `centre` (y up), exactly n >= 1 triangles (a fan).
void AddFan(Mesh& out, const Vec3& centre, float radius, int64_t n);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_ASSEMBLY_H_
