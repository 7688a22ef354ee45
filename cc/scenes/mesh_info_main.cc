// Counts what a renderer gets from a mesh file through assimp: loads it with
// aiProcess_Triangulate, walks the node hierarchy (a mesh referenced by k
// nodes counts k times, as a flattened scene has it), and prints one JSON line:
//   {"triangles": flattened triangles, "triangles_unique": sum over meshes,
//    "lines": .., "points": .., "meshes": .., "instances": ..,
//    "dropped": faces/meshes skipped because the reader left them malformed,
//    "skipped_nodes": nodes left out by --skip_nodes (with their subtrees),
//    "bounds": [[lo], [hi]]}   (bounds of the flattened triangles)
// --skip_nodes=A,B leaves out every node named A or B and its subtree: helper
// geometry a scene file carries but never draws (FlightGear's Cessna has two
// 200 m light cones around an 8 m aircraft).
// With --ply_out=PATH it also writes the flattened triangles as binary PLY
// (cc/scenes/ply.h), the form in which fetch.py keeps scenes whose reader is
// fragile (Quake 3 maps in a .pk3; the TORCS .acc variant of AC3D): the
// loaders then read a plain file.
//
// The reading and flattening are cc/scenes/assimp_mesh.h's, which the
// generators also read their inputs with. Used by data/fetch.py as a child
// process (some readers still crash on some files).
//
//   bazel run //cc/scenes:mesh_info -- /abs/path/scene.blend [--ply_out=/abs/out.ply]
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "cc/base/json_line.h"
#include "cc/scenes/assimp_mesh.h"
#include "cc/scenes/mesh.h"
#include "cc/scenes/ply.h"
#include "nlohmann/json.hpp"

ABSL_FLAG(std::string, ply_out, "", "also write the flattened triangles to this binary PLY");
ABSL_FLAG(std::vector<std::string>, skip_nodes, {},
          "comma-separated node names left out with their subtrees (helper geometry)");

int main(int argc, char** argv) {
  const std::vector<char*> args = absl::ParseCommandLine(argc, argv);
  if (args.size() != 2) {
    std::fprintf(stderr, "usage: mesh_info FILE [--ply_out=OUT.ply] [--skip_nodes=A,B]\n");
    return 2;
  }
  const char* path = args[1];
  const std::string ply_out = absl::GetFlag(FLAGS_ply_out);
  kdtree::scenes::Mesh flattened;
  kdtree::scenes::FlattenTotals t;
  std::set<std::string> skip;
  for (const std::string& name : absl::GetFlag(FLAGS_skip_nodes)) {
    if (!name.empty()) skip.insert(name);
  }
  if (absl::Status s =
          kdtree::scenes::ReadFlattened(path, skip, &t, ply_out.empty() ? nullptr : &flattened);
      !s.ok()) {
    std::fprintf(stderr, "mesh_info: %s\n", std::string(s.message()).c_str());
    return 1;
  }
  if (!ply_out.empty() && t.triangles > 0) {
    const absl::Status s = kdtree::scenes::WritePly(ply_out, flattened);
    if (!s.ok()) {
      std::fprintf(stderr, "mesh_info: %s\n", s.ToString().c_str());
      return 1;
    }
  }
  const nlohmann::ordered_json line = {
      {"triangles", t.triangles},
      {"triangles_unique", t.triangles_unique},
      {"lines", t.lines},
      {"points", t.points},
      {"meshes", t.meshes},
      {"instances", t.instances},
      {"dropped", t.dropped},
      {"skipped_nodes", t.skipped_nodes},
      {"bounds", {{t.lo[0], t.lo[1], t.lo[2]}, {t.hi[0], t.hi[1], t.hi[2]}}}};
  std::printf("%s\n", kdtree::JsonLine(line).c_str());
  return t.triangles > 0 ? 0 : 1;
}
