#include "cc/scenes/spm.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "cc/base/read_file.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr uint8_t kTypeSkinned = 1;
constexpr uint8_t kTypeStatic = 2;
constexpr uint8_t kFlagNormals = 1, kFlagColors = 2, kFlagTangents = 4;
constexpr uint8_t kWhite = 128;  // colour byte meaning "white, no RGB follows"

// Bounds-checked little-endian reads over the file's bytes.
class Reader {
 public:
  Reader(absl::string_view bytes, absl::string_view name) : bytes_(bytes), name_(name) {}

  size_t pos() const { return pos_; }
  size_t left() const { return bytes_.size() - pos_; }

  absl::Status Truncated(absl::string_view what, size_t need) const {
    return absl::InvalidArgumentError(absl::StrCat(name_, ": truncated at byte ", pos_,
                                                    " reading ", what, " (needs ", need,
                                                    " bytes, ", left(), " left)"));
  }
  absl::Status Malformed(absl::string_view why) const {
    return absl::InvalidArgumentError(absl::StrCat(name_, ": ", why));
  }

  absl::Status Skip(size_t n, absl::string_view what) {
    if (n > left()) return Truncated(what, n);
    pos_ += n;
    return absl::OkStatus();
  }
  absl::Status Bytes(size_t n, absl::string_view what, absl::string_view* out) {
    if (n > left()) return Truncated(what, n);
    *out = bytes_.substr(pos_, n);
    pos_ += n;
    return absl::OkStatus();
  }
  template <typename T>
  absl::Status Read(absl::string_view what, T* out) {
    static_assert(std::is_integral<T>::value, "integers only; floats via ReadFloat");
    if (sizeof(T) > left()) return Truncated(what, sizeof(T));
    uint64_t v = 0;
    for (size_t i = 0; i < sizeof(T); ++i) {
      v |= static_cast<uint64_t>(static_cast<uint8_t>(bytes_[pos_ + i])) << (8 * i);
    }
    pos_ += sizeof(T);
    *out = static_cast<T>(v);
    return absl::OkStatus();
  }
  absl::Status ReadFloat(absl::string_view what, float* out) {
    uint32_t bits = 0;
    if (absl::Status s = Read(what, &bits); !s.ok()) return s;
    std::memcpy(out, &bits, sizeof(*out));
    return absl::OkStatus();
  }

 private:
  absl::string_view bytes_;
  absl::string_view name_;
  size_t pos_ = 0;
};

struct Material {
  bool uv1 = false;  // texture 1 named: vertices carry UVs (and tangents)
  bool uv2 = false;  // texture 2 named too: a second UV set
};

#define SPM_RETURN_IF_ERROR(expr)                     \
  do {                                                \
    if (absl::Status _s = (expr); !_s.ok()) return _s; \
  } while (0)

// One vertex + index buffer, appended to `mesh`.
absl::Status ReadBuffer(Reader& in, const std::vector<Material>& materials, const SpmInfo& info,
                        int section, int buffer, Mesh& mesh) {
  const std::string where = absl::StrCat("section ", section, " buffer ", buffer);
  uint32_t vertex_count = 0, index_count = 0;
  uint16_t material = 0;
  SPM_RETURN_IF_ERROR(in.Read(where + " vertex count", &vertex_count));
  SPM_RETURN_IF_ERROR(in.Read(where + " index count", &index_count));
  SPM_RETURN_IF_ERROR(in.Read(where + " material", &material));
  if (vertex_count > 65535) {
    return in.Malformed(absl::StrCat(where, ": ", vertex_count,
                                     " vertices (the format's indices are 16-bit: at most 65535)"));
  }
  if (index_count % 3 != 0) {
    return in.Malformed(absl::StrCat(where, ": ", index_count, " indices, not a multiple of 3"));
  }
  if (material >= materials.size()) {
    return in.Malformed(absl::StrCat(where, ": material ", material, " of ", materials.size()));
  }
  const Material& m = materials[material];
  // Bytes after the position, per vertex: all fixed except the colour.
  size_t fixed = 0;
  if (info.normals) fixed += 4;
  if (m.uv1) fixed += 4 + (info.tangents ? 4 : 0) + (m.uv2 ? 4 : 0);
  if (info.skinned) fixed += 16;
  const size_t minimum = (12 + fixed + (info.colors ? 1 : 0)) * size_t{vertex_count};
  if (minimum > in.left()) return in.Truncated(where + " vertices", minimum);

  const int32_t base = static_cast<int32_t>(mesh.vertices.size());
  for (uint32_t v = 0; v < vertex_count; ++v) {
    Vec3 p;
    SPM_RETURN_IF_ERROR(in.ReadFloat("vertex x", &p.x));
    SPM_RETURN_IF_ERROR(in.ReadFloat("vertex y", &p.y));
    SPM_RETURN_IF_ERROR(in.ReadFloat("vertex z", &p.z));
    if (!IsFinite(p)) {
      return in.Malformed(absl::StrCat(where, ": vertex ", v, " is not finite"));
    }
    mesh.vertices.push_back(p);
    if (info.normals) SPM_RETURN_IF_ERROR(in.Skip(4, "normal"));
    if (info.colors) {
      uint8_t first = 0;
      SPM_RETURN_IF_ERROR(in.Read("colour", &first));
      if (first != kWhite) SPM_RETURN_IF_ERROR(in.Skip(3, "colour RGB"));
    }
    if (m.uv1) {
      SPM_RETURN_IF_ERROR(in.Skip(4, "UV"));
      if (info.tangents) SPM_RETURN_IF_ERROR(in.Skip(4, "tangent"));
      if (m.uv2) SPM_RETURN_IF_ERROR(in.Skip(4, "second UV"));
    }
    if (info.skinned) SPM_RETURN_IF_ERROR(in.Skip(16, "joints and weights"));
  }

  const size_t index_size = vertex_count < 256 ? 1 : 2;
  absl::string_view indices;
  SPM_RETURN_IF_ERROR(in.Bytes(index_size * index_count, where + " indices", &indices));
  for (uint32_t t = 0; t < index_count / 3; ++t) {
    int32_t corner[3];
    for (int k = 0; k < 3; ++k) {
      const size_t at = (3 * size_t{t} + k) * index_size;
      uint32_t i = static_cast<uint8_t>(indices[at]);
      if (index_size == 2) i |= static_cast<uint32_t>(static_cast<uint8_t>(indices[at + 1])) << 8;
      if (i >= vertex_count) {
        return in.Malformed(absl::StrCat(where, ": index ", i, " of triangle ", t, " >= ",
                                         vertex_count, " vertices"));
      }
      corner[k] = base + static_cast<int32_t>(i);
    }
    mesh.AddTriangle(corner[0], corner[1], corner[2]);
  }
  return absl::OkStatus();
}

absl::Status CheckBounds(const Mesh& mesh, const SpmInfo& info, const SpmOptions& options,
                         absl::string_view name) {
  if (options.bounds_tolerance < 0 || mesh.vertices.empty()) return absl::OkStatus();
  const AABB& b = info.header_bounds;
  float extent = 0;
  for (int a = 0; a < 3; ++a) extent = std::fmax(extent, b.hi[a] - b.lo[a]);
  const float slack = options.bounds_tolerance * extent + 1e-6f;
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    for (int a = 0; a < 3; ++a) {
      if (p[a] < b.lo[a] - slack || p[a] > b.hi[a] + slack) {
        return absl::InvalidArgumentError(absl::StrCat(
            name, ": vertex ", v, " lies outside the header's bounding box (axis ", a, ": ",
            p[a], " not in [", b.lo[a], ", ", b.hi[a], "]): misread vertex layout?"));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<Mesh> ParseSpm(absl::string_view bytes, absl::string_view name,
                              const SpmOptions& options, SpmInfo* info_out) {
  Reader in(bytes, name);
  SpmInfo info;
  absl::string_view magic;
  SPM_RETURN_IF_ERROR(in.Bytes(2, "magic", &magic));
  if (magic != "SP") return in.Malformed("not an .spm file (no 'SP' magic)");
  uint8_t version_type = 0, flags = 0;
  SPM_RETURN_IF_ERROR(in.Read("version", &version_type));
  const int version = version_type >> 3, type = version_type & 7;
  if (version != 1) return in.Malformed(absl::StrCat("unsupported version ", version));
  if (type != kTypeSkinned && type != kTypeStatic) {
    return in.Malformed(absl::StrCat("unknown mesh type ", type));
  }
  info.skinned = type == kTypeSkinned;
  SPM_RETURN_IF_ERROR(in.Read("flags", &flags));
  if (flags & ~(kFlagNormals | kFlagColors | kFlagTangents)) {
    return in.Malformed(absl::StrCat("unknown vertex flags 0x", absl::Hex(flags)));
  }
  info.normals = flags & kFlagNormals;
  info.colors = flags & kFlagColors;
  info.tangents = flags & kFlagTangents;
  float box[6];
  for (float& f : box) SPM_RETURN_IF_ERROR(in.ReadFloat("bounding box", &f));
  info.header_bounds = AABB(Vec3(box[0], box[1], box[2]), Vec3(box[3], box[4], box[5]));

  uint16_t material_count = 0;
  SPM_RETURN_IF_ERROR(in.Read("material count", &material_count));
  std::vector<Material> materials(material_count);
  for (Material& m : materials) {
    for (int t = 0; t < 2; ++t) {
      uint8_t length = 0;
      SPM_RETURN_IF_ERROR(in.Read("texture name length", &length));
      SPM_RETURN_IF_ERROR(in.Skip(length, "texture name"));
      (t == 0 ? m.uv1 : m.uv2) = length > 0;
    }
    m.uv2 = m.uv2 && m.uv1;  // a second UV set only with a first
  }
  info.materials = material_count;

  uint16_t section_count = 0;
  SPM_RETURN_IF_ERROR(in.Read("section count", &section_count));
  info.sections = section_count;
  Mesh mesh;
  for (int s = 0; s < section_count; ++s) {
    uint16_t buffer_count = 0;
    SPM_RETURN_IF_ERROR(in.Read(absl::StrCat("section ", s, " buffer count"), &buffer_count));
    for (int b = 0; b < buffer_count; ++b) {
      SPM_RETURN_IF_ERROR(ReadBuffer(in, materials, info, s, b, mesh));
      ++info.buffers;
    }
  }
  info.trailing_bytes = in.left();
  if (info.trailing_bytes > 0 && !info.skinned && !options.allow_trailing_bytes) {
    return in.Malformed(absl::StrCat(info.trailing_bytes, " bytes after the last index buffer of "
                                     "a static mesh"));
  }
  SPM_RETURN_IF_ERROR(CheckBounds(mesh, info, options, name));
  if (info_out != nullptr) *info_out = info;
  return mesh;
}

absl::StatusOr<Mesh> ReadSpm(const std::string& path, const SpmOptions& options, SpmInfo* info) {
  absl::StatusOr<std::string> bytes = ReadTextInput(path, "SPM mesh", kSceneInputBudget);
  if (!bytes.ok()) return bytes.status();
  return ParseSpm(*bytes, path, options, info);
}

#undef SPM_RETURN_IF_ERROR

}  // namespace scenes
}  // namespace kdtree
