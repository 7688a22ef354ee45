// Scenes and ray sets of the adversarial suite (issue "Hard cases stay
// numerically stable"). Deterministic; every vertex shared by two triangles is
// computed once, so shared edges are bitwise identical (needed for the
// watertightness checks).
#ifndef KDTREE_CC_ROBUST_ROBUST_SCENES_H_
#define KDTREE_CC_ROBUST_ROBUST_SCENES_H_

#include <cstdint>
#include <string>
#include <vector>

#include "cc/geometry/ray.h"
#include "cc/geometry/triangle.h"

namespace kdtree {
namespace robust {

// A straight flight of `steps` steps rising along +y as z grows: riser k is
// the quad z = k tread, y in [k rise, (k + 1) rise]; tread k is the quad
// y = (k + 1) rise, z in [k tread, (k + 1) tread]; x in [0, width]. All
// treads and risers are axis-aligned (two triangles each).
TriangleSoup Stairs(int steps, float tread, float rise, float width);
// The coordinates the stairs use: StairZ(k) = float(k * tread), StairY(k) =
// float(k * rise), computed in double and rounded once (as Stairs does).
float StairZ(int k, float tread);
float StairY(int k, float rise);

// A closed icosphere (20 * 4^levels triangles), radius `radius`, centre
// `centre`; vertices are computed once in double and rounded to float.
TriangleSoup Icosphere(int levels, double radius, const double centre[3]);

// Small scenes by name: "tiny" (hand-made: shared edge, a triangle in a split
// plane, a sliver), "stairs", "voxels", "sphere", "thin", "flat", "blocks".
TriangleSoup SmallScene(const std::string& name);

// The names SmallScene knows, in that order (the suites' test parameters).
std::vector<std::string> SmallSceneNames();

// The scene with every coordinate multiplied by s (in double, rounded once).
TriangleSoup Scaled(const TriangleSoup& soup, double s);

// Unique vertices of the soup, and the midpoints (a + b) / 2 of its unique
// edges, each in float.
std::vector<Vec3> UniqueVertices(const TriangleSoup& soup);
std::vector<Vec3> EdgeMidpoints(const TriangleSoup& soup);

// Rays parallel to an axis: for each ray axis a, each point (p, q) of `grid`
// over the other two axes (b = (a + 1) % 3, c = (a + 2) % 3), the ray starts
// outside the box and runs along +a and along -a, each with the four sign
// combinations (+0/-0) of the zero components: 8 rays per grid point.
// grid[a] holds the (b, c) pairs for ray axis a.
struct AxisGrid {
  std::vector<std::pair<float, float>> points[3];
};
std::vector<Ray> AxisParallelRays(const AABB& box, const AxisGrid& grid);

// Grid over two value lists: the full product when it has at most
// max_points points, else every value of each list paired with `sample`
// evenly spaced values of the other, plus the product of the two samples.
std::vector<std::pair<float, float>> GridPoints(const std::vector<float>& u,
                                                const std::vector<float>& v, size_t max_points,
                                                size_t sample);

// At most n of the sorted values, evenly spaced, first and last included.
std::vector<float> Sample(const std::vector<float>& values, size_t n);

// The values, their midpoints, and a value beyond each end.
std::vector<float> WithMidpoints(const std::vector<float>& values);

}  // namespace robust
}  // namespace kdtree

#endif  // KDTREE_CC_ROBUST_ROBUST_SCENES_H_
