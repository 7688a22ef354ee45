// The PLY part of the mesh syntax check (mesh_syntax.h). PLY: G. Turk, "The
// PLY polygon file format" (Stanford, 1994): a text header, then the elements
// in ASCII (one item per line) or binary of either endianness.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cc/io/syntax_lines.h"

namespace kdtree {
namespace syntax {
namespace {

// ---------------------------------------------------------------- PLY
struct PlyProperty {
  int size = 0;        // scalar size, or the list's item size
  int count_size = 0;  // list count size; 0 for a scalar
  bool count_signed = false, item_float = false, item_signed = false;
  bool is_index = false;  // face vertex_indices / vertex_index
};
struct PlyElement {
  std::string name;
  int64_t count = 0;
  size_t line = 0;
  std::vector<PlyProperty> props;
};

// Size in bytes, signedness and floatness of a PLY type name (0: unknown).
int TypeSize(absl::string_view t, bool* is_signed, bool* is_float) {
  *is_float = t == "float" || t == "float32" || t == "double" || t == "float64";
  *is_signed = !(t == "uchar" || t == "uint8" || t == "ushort" || t == "uint16" || t == "uint" ||
                 t == "uint32");
  if (t == "char" || t == "int8" || t == "uchar" || t == "uint8") return 1;
  if (t == "short" || t == "int16" || t == "ushort" || t == "uint16") return 2;
  if (t == "int" || t == "int32" || t == "uint" || t == "uint32" || t == "float" ||
      t == "float32") {
    return 4;
  }
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// An integer of `size` bytes at p (float types truncated), either endianness.
int64_t ReadValue(const char* p, int size, bool is_signed, bool is_float, bool big) {
  unsigned char b[8];
  for (int i = 0; i < size; ++i) b[i] = static_cast<unsigned char>(p[big ? size - 1 - i : i]);
  if (is_float) {
    double d;
    if (size == 4) {
      float f;
      std::memcpy(&f, b, 4);
      d = f;
    } else {
      std::memcpy(&d, b, 8);
    }
    return d >= -9e18 && d <= 9e18 ? static_cast<int64_t>(d) : -1;  // NaN -> -1
  }
  uint64_t u = 0;
  for (int i = size - 1; i >= 0; --i) u = (u << 8) | b[i];
  if (is_signed && size < 8 && (u >> (8 * size - 1)) != 0) u |= ~uint64_t{0} << (8 * size);
  return static_cast<int64_t>(u);
}

}  // namespace

absl::Status CheckPly(absl::string_view data, const std::string& name) {
  Lines lines(data, false);
  std::vector<absl::string_view> tok;
  if (!lines.Next(&tok) || tok.size() != 1 || tok[0] != "ply") {
    return LineError(name, 1, "a PLY file starts with the line 'ply'");
  }
  std::string format;
  std::vector<PlyElement> elements;
  bool end = false;
  while (!end && lines.Next(&tok)) {
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    const size_t ln = lines.number();
    if (tok[0] == "format") {
      if (tok.size() != 3 || (tok[1] != "ascii" && tok[1] != "binary_little_endian" &&
                              tok[1] != "binary_big_endian")) {
        return LineError(name, ln, "expected 'format ascii|binary_little_endian|"
                                   "binary_big_endian 1.0'");
      }
      format = std::string(tok[1]);
    } else if (tok[0] == "element") {
      PlyElement e;
      if (tok.size() != 3 || !absl::SimpleAtoi(tok[2], &e.count) || e.count < 0) {
        return LineError(name, ln, "expected 'element NAME COUNT' with COUNT >= 0");
      }
      e.name = std::string(tok[1]);
      e.line = ln;
      elements.push_back(e);
    } else if (tok[0] == "property") {
      if (elements.empty()) return LineError(name, ln, "property before any element");
      PlyProperty p;
      bool f;
      if (tok.size() == 5 && tok[1] == "list") {
        p.count_size = TypeSize(tok[2], &p.count_signed, &f);
        p.size = TypeSize(tok[3], &p.item_signed, &p.item_float);
        if (p.count_size == 0 || f || p.size == 0) {
          return LineError(name, ln, "bad list property types");
        }
        p.is_index = elements.back().name == "face" &&
                     (tok[4] == "vertex_indices" || tok[4] == "vertex_index");
      } else if (tok.size() == 3) {
        p.size = TypeSize(tok[1], &p.item_signed, &p.item_float);
        if (p.size == 0) return LineError(name, ln, absl::StrCat("unknown type ", Quote(tok[1])));
      } else {
        return LineError(name, ln, "expected 'property TYPE NAME' or 'property list T T NAME'");
      }
      elements.back().props.push_back(p);
    } else if (tok[0] == "end_header") {
      end = true;
    } else {
      return LineError(name, lines.number(), absl::StrCat("unknown header line ", Quote(tok[0])));
    }
  }
  if (!end) return lines.Error(name, "no end_header");
  if (format.empty()) return LineError(name, lines.number(), "no format line in the header");
  const size_t body_start = lines.offset();
  const size_t body = data.size() - body_start;
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  int64_t vertices = -1;
  for (const PlyElement& e : elements) {
    if (e.name == "vertex") vertices = e.count;
    size_t min_bytes = 0;
    for (const PlyProperty& p : e.props) min_bytes += ascii ? 2 : (p.count_size ? p.count_size : p.size);
    if (min_bytes > 0 && static_cast<uint64_t>(e.count) > body / min_bytes) {
      return LineError(name, e.line,
                       absl::StrCat("element '", e.name, "' declares ", e.count,
                                    " items, more than the ", body,
                                    " bytes after the header can hold"));
    }
  }
  auto index_ok = [vertices](int64_t v) { return vertices < 0 || (v >= 0 && v < vertices); };
  if (!ascii) {
    size_t pos = body_start;
    for (const PlyElement& e : elements) {
      for (int64_t i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.props) {
          auto truncated = [&]() {
            return absl::InvalidArgumentError(
                absl::StrCat(name, ": byte ", pos, ": file ends inside element '", e.name,
                             "' item ", i, " of ", e.count, " (truncated)"));
          };
          if (p.count_size == 0) {
            if (data.size() - pos < static_cast<size_t>(p.size)) return truncated();
            pos += p.size;
            continue;
          }
          if (data.size() - pos < static_cast<size_t>(p.count_size)) return truncated();
          const int64_t n = ReadValue(data.data() + pos, p.count_size, p.count_signed, false, big);
          if (n < 0) {
            return absl::InvalidArgumentError(absl::StrCat(
                name, ": byte ", pos, ": negative list length in element '", e.name, "'"));
          }
          if (p.is_index && n < 3) {
            return absl::InvalidArgumentError(absl::StrCat(
                name, ": byte ", pos, ": face ", i, " has ", n, " vertices, needs at least 3"));
          }
          pos += p.count_size;
          if (static_cast<uint64_t>(n) > (data.size() - pos) / p.size) return truncated();
          for (int64_t k = 0; p.is_index && k < n; ++k) {
            const int64_t v = ReadValue(data.data() + pos + k * p.size, p.size, p.item_signed,
                                        p.item_float, big);
            if (!index_ok(v)) {
              return absl::InvalidArgumentError(absl::StrCat(
                  name, ": byte ", pos + k * p.size, ": face ", i, " vertex index ", v,
                  " is not in [0, ", vertices, ") (wrong endianness?)"));
            }
          }
          pos += static_cast<size_t>(n) * p.size;
        }
      }
    }
    return absl::OkStatus();
  }
  // ASCII body: one item per line (assimp reads it line by line): one token
  // per scalar, a list's length then its items.
  for (const PlyElement& e : elements) {
    for (int64_t i = 0; i < e.count; ++i) {
      do {
        if (!lines.Next(&tok)) {
          return lines.Error(name, absl::StrCat("file ends inside element '", e.name, "' item ",
                                                i, " of ", e.count));
        }
      } while (tok.empty());
      size_t next = 0;
      auto too_few = [&]() {
        return LineError(name, lines.number(),
                         absl::StrCat("element '", e.name, "' item ", i,
                                      ": too few values on the line"));
      };
      for (const PlyProperty& p : e.props) {
        int64_t n = 1;
        if (p.count_size != 0) {
          if (next >= tok.size()) return too_few();
          if (!absl::SimpleAtoi(tok[next], &n) || n < 0) {
            return LineError(name, lines.number(),
                             absl::StrCat("bad list length ", Quote(tok[next])));
          }
          ++next;
          if (p.is_index && n < 3) {
            return LineError(name, lines.number(),
                             absl::StrCat("face ", i, " has ", n, " vertices, needs at least 3"));
          }
        }
        for (int64_t k = 0; k < n; ++k) {
          if (next >= tok.size()) return too_few();
          const absl::string_view t = tok[next++];
          double d;
          if (!absl::SimpleAtod(t, &d)) {
            return LineError(name, lines.number(),
                             absl::StrCat("expected a number, got ", Quote(t)));
          }
          if (p.is_index && (!(d >= 0 && d < 9e18) || d != std::floor(d) ||
                             !index_ok(static_cast<int64_t>(d)))) {
            return LineError(name, lines.number(),
                             absl::StrCat("face ", i, ": vertex index ", Quote(t),
                                          " is not in [0, ", vertices, ")"));
          }
        }
      }
      if (next != tok.size()) {
        return LineError(name, lines.number(),
                         absl::StrCat("element '", e.name, "' item ", i,
                                      ": too many values on the line"));
      }
    }
  }
  return absl::OkStatus();
}


}  // namespace syntax
}  // namespace kdtree
