#include "cc/scenes/ply.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "cc/base/read_file.h"
#include "absl/strings/str_split.h"

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

// Scalar property types of the PLY format.
enum class Scalar { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

bool ParseScalar(absl::string_view name, Scalar* out) {
  static const struct {
    const char* name;
    Scalar type;
  } kNames[] = {
      {"char", Scalar::kInt8},      {"int8", Scalar::kInt8},       {"uchar", Scalar::kUint8},
      {"uint8", Scalar::kUint8},    {"short", Scalar::kInt16},     {"int16", Scalar::kInt16},
      {"ushort", Scalar::kUint16},  {"uint16", Scalar::kUint16},   {"int", Scalar::kInt32},
      {"int32", Scalar::kInt32},    {"uint", Scalar::kUint32},     {"uint32", Scalar::kUint32},
      {"float", Scalar::kFloat32},  {"float32", Scalar::kFloat32}, {"double", Scalar::kFloat64},
      {"float64", Scalar::kFloat64}};
  for (const auto& n : kNames) {
    if (name == n.name) {
      *out = n.type;
      return true;
    }
  }
  return false;
}

int ScalarSize(Scalar s) {
  switch (s) {
    case Scalar::kInt8:
    case Scalar::kUint8:
      return 1;
    case Scalar::kInt16:
    case Scalar::kUint16:
      return 2;
    case Scalar::kInt32:
    case Scalar::kUint32:
    case Scalar::kFloat32:
      return 4;
    case Scalar::kFloat64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  bool is_list = false;
  Scalar count_type = Scalar::kUint8;
  Scalar type = Scalar::kFloat32;
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::vector<Property> properties;
};

// Reads values one by one from the body of an ascii or binary PLY file.
class ValueReader {
 public:
  ValueReader(absl::string_view body, bool binary) : body_(body), binary_(binary) {}

  bool Read(Scalar type, double* value) {
    if (!binary_) return ReadAscii(value);
    const int size = ScalarSize(type);
    if (pos_ + size > body_.size()) return false;
    uint64_t bits = 0;
    for (int i = 0; i < size; ++i) {
      bits |= static_cast<uint64_t>(static_cast<uint8_t>(body_[pos_ + i])) << (8 * i);
    }
    pos_ += size;
    switch (type) {
      case Scalar::kInt8:
        *value = static_cast<int8_t>(bits);
        break;
      case Scalar::kUint8:
        *value = static_cast<uint8_t>(bits);
        break;
      case Scalar::kInt16:
        *value = static_cast<int16_t>(bits);
        break;
      case Scalar::kUint16:
        *value = static_cast<uint16_t>(bits);
        break;
      case Scalar::kInt32:
        *value = static_cast<int32_t>(bits);
        break;
      case Scalar::kUint32:
        *value = static_cast<uint32_t>(bits);
        break;
      case Scalar::kFloat32: {
        const uint32_t b32 = static_cast<uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof(f));
        *value = f;
        break;
      }
      case Scalar::kFloat64: {
        double d;
        std::memcpy(&d, &bits, sizeof(d));
        *value = d;
        break;
      }
    }
    return true;
  }

 private:
  bool ReadAscii(double* value) {
    while (pos_ < body_.size() && absl::ascii_isspace(static_cast<unsigned char>(body_[pos_]))) {
      ++pos_;
    }
    size_t end = pos_;
    while (end < body_.size() && !absl::ascii_isspace(static_cast<unsigned char>(body_[end]))) {
      ++end;
    }
    if (end == pos_) return false;
    const bool ok = absl::SimpleAtod(body_.substr(pos_, end - pos_), value);
    pos_ = end;
    return ok;
  }

  absl::string_view body_;
  bool binary_;
  size_t pos_ = 0;
};

// Appends polygon `poly` as a fan of triangles.
absl::Status AddPolygon(Mesh& mesh, const std::vector<int64_t>& poly) {
  for (int64_t i : poly) {
    if (i < 0 || i >= static_cast<int64_t>(mesh.vertices.size())) {
      return absl::InvalidArgumentError(absl::StrCat("vertex index out of range: ", i));
    }
  }
  for (size_t k = 2; k < poly.size(); ++k) {
    mesh.AddTriangle(static_cast<int32_t>(poly[0]), static_cast<int32_t>(poly[k - 1]),
                     static_cast<int32_t>(poly[k]));
  }
  return absl::OkStatus();
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

absl::StatusOr<Mesh> ParsePly(absl::string_view bytes) {
  const size_t header_end = bytes.find("end_header");
  if (!absl::StartsWith(bytes, "ply") || header_end == absl::string_view::npos) {
    return absl::InvalidArgumentError("not a PLY file");
  }
  size_t body_start = bytes.find('\n', header_end);
  if (body_start == absl::string_view::npos) return absl::InvalidArgumentError("no PLY body");
  ++body_start;
  bool binary = false;
  std::vector<Element> elements;
  for (absl::string_view line : absl::StrSplit(bytes.substr(0, header_end), '\n')) {
    std::vector<absl::string_view> w =
        absl::StrSplit(absl::StripAsciiWhitespace(line), ' ', absl::SkipEmpty());
    if (w.empty()) continue;
    if (w[0] == "format") {
      if (w.size() < 2) return absl::InvalidArgumentError("bad format line");
      if (w[1] == "binary_little_endian") {
        binary = true;
      } else if (w[1] != "ascii") {
        return absl::UnimplementedError(absl::StrCat("PLY format ", w[1]));
      }
    } else if (w[0] == "element" && w.size() == 3) {
      Element e;
      e.name = std::string(w[1]);
      if (!absl::SimpleAtoi(w[2], &e.count) || e.count < 0) {
        return absl::InvalidArgumentError("bad element count");
      }
      elements.push_back(e);
    } else if (w[0] == "property" && !elements.empty()) {
      Property p;
      bool ok;
      if (w.size() == 5 && w[1] == "list") {
        p.is_list = true;
        ok = ParseScalar(w[2], &p.count_type) && ParseScalar(w[3], &p.type);
        p.name = std::string(w[4]);
      } else {
        ok = w.size() == 3 && ParseScalar(w[1], &p.type);
        p.name = std::string(w.back());
      }
      if (!ok) return absl::InvalidArgumentError(absl::StrCat("bad property: ", line));
      elements.back().properties.push_back(p);
    }
  }
  Mesh mesh;
  ValueReader reader(bytes.substr(body_start), binary);
  std::vector<int64_t> poly;
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    for (int64_t n = 0; n < e.count; ++n) {
      double xyz[3] = {0, 0, 0};
      for (const Property& p : e.properties) {
        double value;
        if (!p.is_list) {
          if (!reader.Read(p.type, &value)) return absl::DataLossError("truncated PLY");
          if (is_vertex && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') {
            xyz[p.name[0] - 'x'] = value;
          }
          continue;
        }
        double count;
        if (!reader.Read(p.count_type, &count)) return absl::DataLossError("truncated PLY");
        poly.clear();
        for (int64_t k = 0; k < static_cast<int64_t>(count); ++k) {
          if (!reader.Read(p.type, &value)) return absl::DataLossError("truncated PLY");
          poly.push_back(static_cast<int64_t>(value));
        }
        if (is_face && (p.name == "vertex_indices" || p.name == "vertex_index")) {
          absl::Status s = AddPolygon(mesh, poly);
          if (!s.ok()) return s;
        }
      }
      if (is_vertex) {
        mesh.AddVertex(Vec3(static_cast<float>(xyz[0]), static_cast<float>(xyz[1]),
                            static_cast<float>(xyz[2])));
      }
    }
  }
  return mesh;
}

absl::StatusOr<Mesh> ParseObj(absl::string_view text) {
  Mesh mesh;
  std::vector<int64_t> poly;
  for (absl::string_view line : absl::StrSplit(text, '\n')) {
    std::vector<absl::string_view> w =
        absl::StrSplit(absl::StripAsciiWhitespace(line), absl::ByAnyChar(" \t"), absl::SkipEmpty());
    if (w.empty()) continue;
    if (w[0] == "v") {
      double c[3];
      if (w.size() < 4 || !absl::SimpleAtod(w[1], &c[0]) || !absl::SimpleAtod(w[2], &c[1]) ||
          !absl::SimpleAtod(w[3], &c[2])) {
        return absl::InvalidArgumentError(absl::StrCat("bad OBJ vertex: ", line));
      }
      mesh.AddVertex(
          Vec3(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])));
    } else if (w[0] == "f") {
      poly.clear();
      for (size_t k = 1; k < w.size(); ++k) {
        int64_t index;
        const absl::string_view first = w[k].substr(0, w[k].find('/'));
        if (!absl::SimpleAtoi(first, &index) || index == 0) {
          return absl::InvalidArgumentError(absl::StrCat("bad OBJ face: ", line));
        }
        poly.push_back(index > 0 ? index - 1 : static_cast<int64_t>(mesh.vertices.size()) + index);
      }
      absl::Status s = AddPolygon(mesh, poly);
      if (!s.ok()) return s;
    }
  }
  return mesh;
}

absl::StatusOr<Mesh> ReadMesh(const std::string& path) {
  absl::StatusOr<std::string> read = ReadTextInput(path, "mesh", kSceneInputBudget);
  if (!read.ok()) return read.status();
  const std::string& bytes = *read;
  const std::string lower = absl::AsciiStrToLower(path);
  if (absl::EndsWith(lower, ".ply")) return ParsePly(bytes);
  if (absl::EndsWith(lower, ".obj")) return ParseObj(bytes);
  return absl::UnimplementedError(absl::StrCat("unknown mesh extension: ", path));
}

}  // namespace scenes
}  // namespace kdtree
