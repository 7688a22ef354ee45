#include "cc/scenes/ply.h"

#include <cstdint>
#include <cstring>
#include <fstream>

#include "absl/strings/str_cat.h"

namespace kdtree {
namespace scenes {
namespace {

void PutU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

void PutFloat(std::string& out, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  PutU32(out, bits);
}

}  // namespace

std::string EncodePly(const Mesh& mesh) {
  std::string out = absl::StrCat(
      "ply\nformat binary_little_endian 1.0\ncomment kdtree_repro cc/scenes generator\n",
      "element vertex ", mesh.vertices.size(),
      "\nproperty float x\nproperty float y\nproperty float z\n", "element face ",
      mesh.faces.size(), "\nproperty list uchar int vertex_indices\nend_header\n");
  out.reserve(out.size() + 12 * mesh.vertices.size() + 13 * mesh.faces.size());
  for (const Vec3& p : mesh.vertices) {
    PutFloat(out, p.x);
    PutFloat(out, p.y);
    PutFloat(out, p.z);
  }
  for (const Mesh::Face& f : mesh.faces) {
    out.push_back(3);
    for (int32_t i : f) PutU32(out, static_cast<uint32_t>(i));
  }
  return out;
}

absl::Status WritePly(const std::string& path, const Mesh& mesh) {
  const std::string bytes = EncodePly(mesh);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) return absl::NotFoundError(absl::StrCat("cannot open for writing: ", path));
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) return absl::DataLossError(absl::StrCat("write failed: ", path));
  return absl::OkStatus();
}

}  // namespace scenes
}  // namespace kdtree
