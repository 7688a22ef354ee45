#include "cc/scenes/q3_bsp.h"

#include <cstring>
#include <vector>

#include "absl/strings/str_cat.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr int kTextures = 1, kVertices = 10, kMeshVerts = 11, kFaces = 13, kLumps = 17;
constexpr int kTextureSize = 72, kVertexSize = 44, kFaceSize = 104;
constexpr int32_t kSurfSky = 0x4, kSurfNodraw = 0x80;

int32_t I32(absl::string_view b, size_t at) {
  int32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

float F32(absl::string_view b, size_t at) {
  float v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

struct Lump {
  size_t offset = 0, count = 0;
};

Vec3 Bezier(const Vec3 c[3][3], float u, float v) {
  const float bu[3] = {(1 - u) * (1 - u), 2 * u * (1 - u), u * u};
  const float bv[3] = {(1 - v) * (1 - v), 2 * v * (1 - v), v * v};
  Vec3 p(0, 0, 0);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) p = p + c[j][i] * (bu[i] * bv[j]);
  }
  return p;
}

}  // namespace

absl::StatusOr<Mesh> ParseQ3Bsp(absl::string_view bytes, const Q3BspConfig& config,
                                Q3BspStats* stats) {
  Q3BspStats local;
  Q3BspStats& s = stats != nullptr ? *stats : local;
  s = Q3BspStats();
  if (bytes.size() < 8 + 8 * kLumps || bytes.substr(0, 4) != "IBSP") {
    return absl::InvalidArgumentError("not a Quake 3 map (no IBSP header)");
  }
  if (I32(bytes, 4) != 46) {
    return absl::InvalidArgumentError(absl::StrCat("IBSP version ", I32(bytes, 4), ", want 46"));
  }
  auto lump = [&](int index, int size) -> absl::StatusOr<Lump> {
    const int32_t offset = I32(bytes, 8 + 8 * index), length = I32(bytes, 12 + 8 * index);
    if (offset < 0 || length < 0 || static_cast<size_t>(offset) + length > bytes.size()) {
      return absl::InvalidArgumentError(absl::StrCat("lump ", index, " outside the file"));
    }
    return Lump{static_cast<size_t>(offset), static_cast<size_t>(length) / size};
  };
  absl::StatusOr<Lump> textures = lump(kTextures, kTextureSize);
  absl::StatusOr<Lump> vertices = lump(kVertices, kVertexSize);
  absl::StatusOr<Lump> meshverts = lump(kMeshVerts, 4);
  absl::StatusOr<Lump> faces = lump(kFaces, kFaceSize);
  for (const auto* l : {&textures, &vertices, &meshverts, &faces}) {
    if (!l->ok()) return l->status();
  }

  Mesh mesh;
  mesh.vertices.reserve(vertices->count);
  for (size_t i = 0; i < vertices->count; ++i) {
    const size_t at = vertices->offset + i * kVertexSize;
    mesh.vertices.emplace_back(F32(bytes, at), F32(bytes, at + 4), F32(bytes, at + 8));
  }
  const int64_t nv = static_cast<int64_t>(vertices->count);
  s.faces = static_cast<int64_t>(faces->count);
  for (size_t f = 0; f < faces->count; ++f) {
    const size_t at = faces->offset + f * kFaceSize;
    const int32_t texture = I32(bytes, at), type = I32(bytes, at + 8);
    const int64_t vertex = I32(bytes, at + 12), n_vertices = I32(bytes, at + 16);
    const int64_t meshvert = I32(bytes, at + 20), n_meshverts = I32(bytes, at + 24);
    int32_t flags = 0;
    if (texture >= 0 && static_cast<size_t>(texture) < textures->count) {
      flags = I32(bytes, textures->offset + texture * kTextureSize + 64);
    }
    if ((config.skip_sky && (flags & kSurfSky)) || (config.skip_nodraw && (flags & kSurfNodraw)) ||
        (type != 1 && type != 2 && type != 3)) {
      ++s.skipped_faces;
      continue;
    }
    if (vertex < 0 || n_vertices < 0 || vertex + n_vertices > nv) {
      return absl::InvalidArgumentError(absl::StrCat("face ", f, ": vertices outside the lump"));
    }
    if (type == 2) {
      const int w = I32(bytes, at + 96), h = I32(bytes, at + 100);
      if (w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || int64_t{w} * h != n_vertices) {
        return absl::InvalidArgumentError(absl::StrCat("face ", f, ": bad patch grid ", w, "x", h));
      }
      const int n = config.patch_subdivisions;
      for (int py = 0; py + 1 < h; py += 2) {
        for (int px = 0; px + 1 < w; px += 2) {
          Vec3 c[3][3];
          for (int j = 0; j < 3; ++j) {
            for (int i = 0; i < 3; ++i) c[j][i] = mesh.vertices[vertex + (py + j) * w + px + i];
          }
          const int32_t base = static_cast<int32_t>(mesh.vertices.size());
          for (int j = 0; j <= n; ++j) {
            for (int i = 0; i <= n; ++i) {
              mesh.AddVertex(Bezier(c, static_cast<float>(i) / n, static_cast<float>(j) / n));
            }
          }
          for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
              const int32_t a = base + j * (n + 1) + i;
              mesh.AddQuad(a, a + 1, a + n + 2, a + n + 1);
            }
          }
        }
      }
      ++s.patch_faces;
      continue;
    }
    if (meshvert < 0 || n_meshverts < 0 || n_meshverts % 3 != 0 ||
        static_cast<size_t>(meshvert + n_meshverts) > meshverts->count) {
      return absl::InvalidArgumentError(absl::StrCat("face ", f, ": mesh vertices outside the lump"));
    }
    for (int64_t k = 0; k < n_meshverts; k += 3) {
      int32_t t[3];
      for (int j = 0; j < 3; ++j) {
        const int64_t offset = I32(bytes, meshverts->offset + 4 * (meshvert + k + j));
        if (offset < 0 || offset >= n_vertices) {
          return absl::InvalidArgumentError(absl::StrCat("face ", f, ": mesh vertex out of range"));
        }
        t[j] = static_cast<int32_t>(vertex + offset);
      }
      mesh.AddTriangle(t[0], t[1], t[2]);
    }
    ++s.polygon_faces;
  }
  // Keep only the vertices that the kept faces use (sky faces' are dropped).
  std::vector<int32_t> remap(mesh.vertices.size(), -1);
  Mesh out;
  out.faces.reserve(mesh.faces.size());
  for (const Mesh::Face& face : mesh.faces) {
    Mesh::Face g;
    for (int j = 0; j < 3; ++j) {
      int32_t& r = remap[face[j]];
      if (r < 0) r = out.AddVertex(mesh.vertices[face[j]]);
      g[j] = r;
    }
    out.faces.push_back(g);
  }
  return out;
}

}  // namespace scenes
}  // namespace kdtree
