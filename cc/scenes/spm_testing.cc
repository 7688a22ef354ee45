#include "cc/scenes/spm_testing.h"

#include <cstdint>
#include <cstring>

#include "cc/geometry/aabb.h"

namespace kdtree {
namespace scenes {
namespace {

void Put(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

void PutFloat(std::string& out, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  Put(out, bits, 4);
}

}  // namespace

std::string EncodeSpm(const SpmWriteOptions& options,
                      const std::vector<std::vector<SpmTestBuffer>>& sections) {
  std::string out = "SP";
  out.push_back(static_cast<char>(1 << 3 | (options.skinned ? 1 : 2)));
  out.push_back(static_cast<char>((options.normals ? 1 : 0) | (options.colors ? 2 : 0) |
                                  (options.tangents ? 4 : 0)));
  AABB box;
  for (const auto& section : sections) {
    for (const SpmTestBuffer& b : section) {
      for (const Vec3& p : b.mesh.vertices) box.Extend(p);
    }
  }
  if (!box.Valid()) box = AABB(Vec3(0, 0, 0), Vec3(0, 0, 0));
  for (int a = 0; a < 3; ++a) PutFloat(out, box.lo[a]);
  for (int a = 0; a < 3; ++a) PutFloat(out, box.hi[a]);
  Put(out, options.materials.size(), 2);
  for (const auto& [tex1, tex2] : options.materials) {
    Put(out, tex1.size(), 1);
    out += tex1;
    Put(out, tex2.size(), 1);
    out += tex2;
  }
  Put(out, sections.size(), 2);
  for (const auto& section : sections) {
    Put(out, section.size(), 2);
    for (const SpmTestBuffer& b : section) {
      const auto& [tex1, tex2] = options.materials.at(b.material);
      const size_t nv = b.mesh.vertices.size();
      Put(out, nv, 4);
      Put(out, 3 * b.mesh.faces.size(), 4);
      Put(out, b.material, 2);
      for (size_t v = 0; v < nv; ++v) {
        for (int a = 0; a < 3; ++a) PutFloat(out, b.mesh.vertices[v][a]);
        if (options.normals) Put(out, 0x1ff7fdffu, 4);
        if (options.colors) {
          if (v % 2 == 0) {
            Put(out, 128, 1);
          } else {
            Put(out, 0x10203040u, 4);
          }
        }
        if (!tex1.empty()) {
          Put(out, 0x3c003800u, 4);  // float16 UV (0.5, 1)
          if (options.tangents) Put(out, 0x5a5a5a5au, 4);
          if (!tex2.empty()) Put(out, 0x00003c00u, 4);
        }
        if (options.skinned) {
          Put(out, 0x0001000000000000ull, 8);  // joints
          Put(out, 0x3c00ull, 8);              // weights
        }
      }
      for (const Mesh::Face& f : b.mesh.faces) {
        for (int32_t i : f) Put(out, static_cast<uint32_t>(i), nv < 256 ? 1 : 2);
      }
    }
  }
  out += options.trailer;
  return out;
}

std::string EncodeSpm(const Mesh& mesh) {
  SpmTestBuffer buffer;
  buffer.mesh = mesh;
  return EncodeSpm(SpmWriteOptions(), {{buffer}});
}

}  // namespace scenes
}  // namespace kdtree
