// Writes one generated scene as binary PLY.
//
//   bazel run -c opt //cc/scenes:generate -- --kind=hairball
//       --triangles=2880000 --seed=1 --out=/abs/path/hairball.ply
//   ... --kind=teapots --input=/abs/path/teapot.ply
//
// Kinds: hairball, voxel, teapots, city, forest, subdivide and refine (of --input),
// plant and courtyard (of --parts). --triangles 0 keeps the
// generator's default size. Same kind, size, seed (and input) => same bytes.
// Prints one JSON line: kind, triangles, vertices, bounds, seconds.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_format.h"
#include "cc/base/json_line.h"
#include "cc/scenes/assembly.h"
#include "cc/scenes/assimp_mesh.h"
#include "cc/scenes/city.h"
#include "cc/scenes/courtyard.h"
#include "cc/scenes/forest.h"
#include "cc/scenes/hairball.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/plant.h"
#include "cc/scenes/ply.h"
#include "cc/scenes/refine.h"
#include "cc/scenes/subdivide.h"
#include "cc/scenes/teapots.h"
#include "cc/scenes/voxel.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, kind, "", "hairball, voxel, teapots, city, forest, subdivide, refine, plant or courtyard");
ABSL_FLAG(int64_t, triangles, 0, "target triangle count (0: the generator's default)");
ABSL_FLAG(uint64_t, seed, 1, "random seed");
ABSL_FLAG(std::string, out, "", "output .ply path (absolute under bazel run)");
ABSL_FLAG(std::string, input, "", "teapots, subdivide, refine: the input mesh (any format assimp reads; PLY keeps shared vertices, cc/scenes/assimp_mesh.h)");
ABSL_FLAG(std::vector<std::string>, parts, {},
          "plant, courtyard: comma-separated role:height_m:path[:up_axis] (cc/scenes/assembly.h)");
ABSL_FLAG(int, input_up_axis, 1, "teapots: up axis of --input, 1 (y) or 2 (z)");

namespace kdtree {
namespace scenes {
namespace {

absl::StatusOr<Mesh> Generate(const std::string& kind, int64_t triangles, uint64_t seed) {
  if (kind == "hairball") {
    HairballConfig c;
    if (triangles > 0) c.target_triangles = triangles;
    c.seed = seed;
    return GenerateHairball(c);
  }
  if (kind == "voxel") {
    VoxelConfig c;
    if (triangles > 0) c.target_triangles = triangles;
    c.seed = seed;
    return GenerateVoxel(c);
  }
  if (kind == "city") {
    CityConfig c;
    if (triangles > 0) c.target_triangles = triangles;
    c.seed = seed;
    return GenerateCity(c);
  }
  if (kind == "forest") {
    ForestConfig c;
    if (triangles > 0) c.target_triangles = triangles;
    c.seed = seed;
    return GenerateForest(c);
  }
  if (kind == "plant" || kind == "courtyard") {
    std::vector<Part> parts;
    for (const std::string& spec : absl::GetFlag(FLAGS_parts)) {
      absl::StatusOr<Part> part = ReadPart(spec);
      if (!part.ok()) return part.status();
      parts.push_back(*std::move(part));
    }
    if (kind == "plant") {
      PlantConfig c;
      if (triangles > 0) c.target_triangles = triangles;
      c.seed = seed;
      return GeneratePlant(c, parts);
    }
    CourtyardConfig c;
    if (triangles > 0) c.target_triangles = triangles;
    c.seed = seed;
    return GenerateCourtyard(c, parts);
  }
  if (kind != "teapots" && kind != "subdivide" && kind != "refine") {
    return absl::InvalidArgumentError(absl::StrFormat("unknown --kind '%s'", kind));
  }
  const std::string input = absl::GetFlag(FLAGS_input);
  if (input.empty()) return absl::InvalidArgumentError("--kind=" + kind + " needs --input");
  absl::StatusOr<Mesh> instance = ReadMesh(input);
  if (!instance.ok()) return instance.status();
  if (kind == "refine") {
    RefineConfig c;
    c.target_triangles = triangles;
    return RefineMesh(c, *instance);
  }
  if (kind == "subdivide") {
    SubdivideConfig c;
    c.target_triangles = triangles;
    return SubdivideMesh(c, *instance);
  }
  TeapotsConfig c;
  if (triangles > 0) c.target_triangles = triangles;
  c.seed = seed;
  c.input_up_axis = absl::GetFlag(FLAGS_input_up_axis);
  return GenerateTeapots(c, *instance);
}

int Main() {
  const std::string kind = absl::GetFlag(FLAGS_kind), out = absl::GetFlag(FLAGS_out);
  if (out.empty()) {
    std::fprintf(stderr, "generate: --out is required\n");
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<Mesh> mesh =
      Generate(kind, absl::GetFlag(FLAGS_triangles), absl::GetFlag(FLAGS_seed));
  if (!mesh.ok()) {
    std::fprintf(stderr, "generate: %s\n", mesh.status().ToString().c_str());
    return 1;
  }
  if (absl::Status s = WritePly(out, *mesh); !s.ok()) {
    std::fprintf(stderr, "generate: %s\n", s.ToString().c_str());
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const AABB b = mesh->Bounds();
  const nlohmann::ordered_json line = {
      {"kind", kind},
      {"triangles", mesh->TriangleCount()},
      {"vertices", mesh->vertices.size()},
      {"bounds", {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}},
      {"seconds", seconds}};
  std::printf("%s\n", JsonLine(line).c_str());
  return 0;
}

}  // namespace
}  // namespace scenes
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return kdtree::scenes::Main();
}
